// The default scene's node tree: walked once, checked (a set of disjoint strict trees), and its
// instanced triangles counted before any geometry is decoded or copied.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <cstdint>

namespace pathlab::gltf {
namespace {

std::vector<int> rootNodes(const tinygltf::Model& model) {
  // tinygltf stores an absent "scene" as -1; any other negative index was written in the file.
  if (model.defaultScene < -1) {
    throw LoadError("default scene " + std::to_string(model.defaultScene) + " does not exist");
  }
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (model.scenes.empty()) {
    // "scene" indexes "scenes": with none, any index is out of range, not a request for all.
    if (model.defaultScene >= 0) {
      throw LoadError("default scene " + std::to_string(scene) +
                      " does not exist (the file has no scenes)");
    }
    // No scenes: render every node that is no other node's child.
    std::vector<char> isChild(model.nodes.size(), 0);
    for (const tinygltf::Node& node : model.nodes) {
      for (int c : node.children) {
        if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = 1;
      }
    }
    std::vector<int> roots;
    for (size_t i = 0; i < model.nodes.size(); ++i) {
      if (!isChild[i]) roots.push_back(int(i));
    }
    return roots;
  }
  if (size_t(scene) >= model.scenes.size()) {
    throw LoadError("default scene " + std::to_string(scene) + " does not exist");
  }
  return model.scenes[size_t(scene)].nodes;
}

int accessorCount(const tinygltf::Model& model, int accessor) {
  // An index out of range is reported when the primitive is decoded; it adds nothing here.
  return accessor >= 0 && size_t(accessor) < model.accessors.size()
             ? int(std::min<size_t>(model.accessors[size_t(accessor)].count, size_t(INT32_MAX)))
             : 0;
}

// Triangles one instance of `mesh` adds, read from accessor counts without decoding anything.
uint64_t meshTriangles(const tinygltf::Model& model, int mesh) {
  if (mesh < 0 || size_t(mesh) >= model.meshes.size()) return 0;
  uint64_t triangles = 0;
  for (const tinygltf::Primitive& prim : model.meshes[size_t(mesh)].primitives) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
    auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) continue;
    const int count = prim.indices >= 0 ? accessorCount(model, prim.indices)
                                        : accessorCount(model, position->second);
    triangles += uint64_t(count) / 3;
  }
  return triangles;
}

}  // namespace

std::string nodeLabel(const tinygltf::Model& model, int index) {
  return "node " + std::to_string(index) + quotedName(model.nodes[size_t(index)].name);
}

std::vector<NodeVisit> walkHierarchy(const tinygltf::Model& model) {
  std::vector<NodeVisit> visits;
  std::vector<NodeVisit> stack;
  const std::vector<int> roots = rootNodes(model);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1});
  // Explicit stack: a deep hierarchy must not overflow the call stack. Children are pushed in
  // reverse so nodes are visited in document (pre-)order, which defines "the first camera".
  std::vector<char> visited(model.nodes.size(), 0);
  while (!stack.empty()) {
    const NodeVisit item = stack.back();
    stack.pop_back();
    if (item.node < 0 || size_t(item.node) >= model.nodes.size()) {
      throw LoadError("the scene refers to node " + std::to_string(item.node) +
                      ", which does not exist");
    }
    if (visited[size_t(item.node)]) {
      // glTF 2.0 spec, sec. 3.5.1: the hierarchy is a set of disjoint strict trees. So every node
      // is visited once and the walk is linear in the file's size: a mesh is instanced once per
      // node that names it, never multiplied down shared subtrees.
      throw LoadError(nodeLabel(model, item.node) +
                      " is reached twice (a cycle, a node with two parents, or a repeated root)");
    }
    visited[size_t(item.node)] = 1;
    const int self = int(visits.size());
    visits.push_back(item);
    const std::vector<int>& children = model.nodes[size_t(item.node)].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      if (*it < 0 || size_t(*it) >= model.nodes.size()) {
        throw LoadError(nodeLabel(model, item.node) + ": child " + std::to_string(*it) +
                        " does not exist");
      }
      stack.push_back({*it, self});
    }
  }
  return visits;
}

InstanceCount countInstances(const tinygltf::Model& model, const std::vector<NodeVisit>& visits,
                             uint64_t maxTriangles) {
  std::vector<uint64_t> perMesh(model.meshes.size(), UINT64_MAX);
  InstanceCount count;
  for (const NodeVisit& visit : visits) {
    const int mesh = model.nodes[size_t(visit.node)].mesh;
    if (mesh < 0) continue;
    uint64_t triangles = 0;
    if (size_t(mesh) < perMesh.size()) {
      if (perMesh[size_t(mesh)] == UINT64_MAX) perMesh[size_t(mesh)] = meshTriangles(model, mesh);
      triangles = perMesh[size_t(mesh)];
    }
    ++count.instances;
    count.triangles += triangles;
    if (count.triangles > maxTriangles) {
      // Stop at once: the count is a lower bound, and the limit is what matters.
      throw LoadError("the node tree instances at least " + std::to_string(count.triangles) +
                      " triangles (" + std::to_string(count.instances) +
                      " mesh instances counted so far), more than the limit of " +
                      std::to_string(maxTriangles) + " triangles");
    }
  }
  return count;
}

}  // namespace pathlab::gltf
