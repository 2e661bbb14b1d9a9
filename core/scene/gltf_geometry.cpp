// Triangle primitives: decoding in mesh-local space (indices, normals, uvs) and instancing into
// world space with the node's transform.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pathlab::gltf {
namespace {

int attribute(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it != primitive.attributes.end() ? it->second : -1;
}

bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// glTF 2.0 spec, sec. 3.7.2.1: "When normals are not specified, client implementations MUST
// calculate flat normals". Each triangle gets its own three vertices.
void makeFlat(LocalPrimitive& p) {
  const size_t triangles = p.indices.size() / 3;
  std::vector<Vec3> positions(3 * triangles), normals(3 * triangles);
  std::vector<Vec2> uvs(p.uvs.empty() ? 0 : 3 * triangles);
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* idx = &p.indices[3 * t];
    Vec3 n = glm::cross(p.positions[idx[1]] - p.positions[idx[0]],
                        p.positions[idx[2]] - p.positions[idx[0]]);
    const float len = glm::length(n);
    // A zero-area triangle is dropped at instancing; any unit vector will do until then.
    n = len > 0.f && std::isfinite(len) ? n / len : Vec3(0.f, 0.f, 1.f);
    for (size_t k = 0; k < 3; ++k) {
      positions[3 * t + k] = p.positions[idx[k]];
      normals[3 * t + k] = n;
      if (!uvs.empty()) uvs[3 * t + k] = p.uvs[idx[k]];
    }
  }
  p.positions = std::move(positions);
  p.normals = std::move(normals);
  p.uvs = std::move(uvs);
  std::iota(p.indices.begin(), p.indices.end(), 0u);
}

// Authored normals that are zero or non-finite take the normal of a triangle that uses them.
size_t repairNormals(LocalPrimitive& p) {
  std::vector<char> invalid(p.normals.size());
  size_t count = 0;
  for (size_t i = 0; i < p.normals.size(); ++i) {
    const Vec3& n = p.normals[i];
    invalid[i] = !isFinite(n) || glm::dot(n, n) == 0.f;
    count += invalid[i];
  }
  if (count == 0) return 0;
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const uint32_t* idx = &p.indices[t];
    const Vec3 n = glm::cross(p.positions[idx[1]] - p.positions[idx[0]],
                              p.positions[idx[2]] - p.positions[idx[0]]);
    for (size_t k = 0; k < 3; ++k) {
      if (invalid[idx[k]]) p.normals[idx[k]] = n;
    }
  }
  for (size_t i = 0; i < p.normals.size(); ++i) {
    if (!isFinite(p.normals[i]) || glm::dot(p.normals[i], p.normals[i]) == 0.f) {
      p.normals[i] = Vec3(0.f, 0.f, 1.f);
    }
  }
  return count;
}

}  // namespace

const std::vector<Vec3>& AttributeCache::positions(const tinygltf::Model& model, int accessor,
                                                   const std::string& label) {
  if (auto it = vec3_.find(accessor); it != vec3_.end()) return it->second;
  std::vector<Vec3> p = readVec3(model, accessor, "POSITION of " + label);
  for (size_t i = 0; i < p.size(); ++i) {
    if (!isFinite(p[i])) {
      throw LoadError(label + ": accessor " + std::to_string(accessor) +
                      " (POSITION) has a non-finite vertex position at vertex " +
                      std::to_string(i));
    }
  }
  return vec3_.emplace(accessor, std::move(p)).first->second;
}

const std::vector<Vec3>& AttributeCache::vec3(const tinygltf::Model& model, int accessor,
                                              const std::string& what) {
  if (auto it = vec3_.find(accessor); it != vec3_.end()) return it->second;
  return vec3_.emplace(accessor, readVec3(model, accessor, what)).first->second;
}

const std::vector<Vec2>& AttributeCache::vec2(const tinygltf::Model& model, int accessor,
                                              const std::string& what) {
  if (auto it = vec2_.find(accessor); it != vec2_.end()) return it->second;
  return vec2_.emplace(accessor, readVec2(model, accessor, what)).first->second;
}

std::vector<uint32_t>& AttributeCache::remap(size_t size) {
  if (remap_.size() < size) remap_.resize(size, kUnused);
  return remap_;
}

LocalPrimitive decodePrimitive(const tinygltf::Model& model, int meshIndex, int primitiveIndex,
                               AttributeCache& cache, Warnings& warnings) {
  const tinygltf::Mesh& mesh = model.meshes[size_t(meshIndex)];
  const tinygltf::Primitive& prim = mesh.primitives[size_t(primitiveIndex)];
  std::string label = "mesh " + std::to_string(meshIndex) + quoted(mesh.name);
  if (mesh.primitives.size() > 1) label += " primitive " + std::to_string(primitiveIndex);

  LocalPrimitive out;
  out.name = !mesh.name.empty() ? mesh.name : "mesh " + std::to_string(meshIndex);
  if (mesh.primitives.size() > 1) out.name += "." + std::to_string(primitiveIndex);

  const int positionAccessor = attribute(prim, "POSITION");
  if (positionAccessor < 0) {
    // glTF 2.0 spec, sec. 3.7.2.1: without positions a client SHOULD skip the primitive.
    warnings.add(label + " has no POSITION attribute; skipped");
    return out;
  }
  const std::vector<Vec3>& positions = cache.positions(model, positionAccessor, label);
  const size_t vertexCount = positions.size();
  const std::vector<Vec3>* normals = nullptr;
  if (const int accessor = attribute(prim, "NORMAL"); accessor >= 0) {
    normals = &cache.vec3(model, accessor, "NORMAL of " + label);
    if (normals->size() != vertexCount) {
      throw LoadError(label + ": NORMAL has " + std::to_string(normals->size()) +
                      " elements but POSITION has " + std::to_string(vertexCount));
    }
  }
  const std::vector<Vec2>* uvs = nullptr;
  if (const int accessor = attribute(prim, "TEXCOORD_0"); accessor >= 0) {
    uvs = &cache.vec2(model, accessor, "TEXCOORD_0 of " + label);
    if (uvs->size() != vertexCount) {
      throw LoadError(label + ": TEXCOORD_0 has " + std::to_string(uvs->size()) +
                      " elements but POSITION has " + std::to_string(vertexCount));
    }
  }

  if (prim.indices >= 0) {
    out.indices = readIndices(model, prim.indices, "indices of " + label);
    for (size_t i = 0; i < out.indices.size(); ++i) {
      if (out.indices[i] >= vertexCount) {
        throw LoadError(label + ": index " + std::to_string(out.indices[i]) + " (accessor " +
                        std::to_string(prim.indices) + ", element " + std::to_string(i) +
                        ") is out of range of the vertex count " + std::to_string(vertexCount));
      }
    }
  } else {
    out.indices.resize(vertexCount);
    std::iota(out.indices.begin(), out.indices.end(), 0u);
  }
  if (const size_t extra = out.indices.size() % 3; extra != 0) {
    warnings.add(label + ": " + std::to_string(out.indices.size()) +
                 " indices is not a multiple of 3; the last " + std::to_string(extra) + " ignored");
    out.indices.resize(out.indices.size() - extra);
  }

  // Keep the vertices this primitive uses, renumbered in order of first use.
  std::vector<uint32_t>& remap = cache.remap(vertexCount);
  std::vector<uint32_t> used;
  used.reserve(std::min(vertexCount, out.indices.size()));
  for (uint32_t& i : out.indices) {
    if (remap[i] == AttributeCache::kUnused) {
      remap[i] = uint32_t(used.size());
      used.push_back(i);
    }
    i = remap[i];
  }
  for (uint32_t v : used) remap[v] = AttributeCache::kUnused;
  out.positions.reserve(used.size());
  for (uint32_t v : used) out.positions.push_back(positions[v]);
  if (uvs) {
    out.uvs.reserve(used.size());
    size_t bad = 0;
    for (uint32_t v : used) {
      const Vec2 uv = (*uvs)[v];
      const bool finite = std::isfinite(uv.x) && std::isfinite(uv.y);
      out.uvs.push_back(finite ? uv : Vec2(0.f));
      bad += !finite;
    }
    if (bad > 0)
      warnings.add(label + ": " + std::to_string(bad) + " non-finite TEXCOORD_0 set to 0");
  }
  if (normals) {
    out.normals.reserve(used.size());
    for (uint32_t v : used) out.normals.push_back((*normals)[v]);
    if (const size_t repaired = repairNormals(out); repaired > 0) {
      warnings.add(label + ": " + std::to_string(repaired) +
                   " zero or non-finite normals replaced by face normals");
    }
  } else {
    makeFlat(out);
  }
  return out;
}

DroppedTriangles instantiatePrimitive(const LocalPrimitive& local, const glm::dmat4& toWorld,
                                     const std::string& label, TriangleMesh& out) {
  const size_t n = local.positions.size();
  const glm::dmat3 linear(toWorld);
  const double det = glm::determinant(linear);
  // Normals transform by the inverse transpose, here as the cofactor matrix
  // [c1 x c2, c2 x c0, c0 x c1] = det * M^-T, which stays defined for singular M; the sign of det
  // is folded in so a mirroring transform does not turn normals inside out.
  const double sign = det < 0.0 ? -1.0 : 1.0;
  const glm::dmat3 normalMatrix(sign * glm::cross(linear[1], linear[2]),
                                sign * glm::cross(linear[2], linear[0]),
                                sign * glm::cross(linear[0], linear[1]));
  // A mirroring transform reverses the winding; swapping two corners restores agreement between
  // the winding's geometric normal and the transformed shading normals.
  const bool flip = det < 0.0;

  out.positions.resize(n);
  out.normals.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec4 p = toWorld * glm::dvec4(glm::dvec3(local.positions[i]), 1.0);
    for (int k = 0; k < 3; ++k) {
      out.positions[i][k] = toFiniteFloat(
          p[k], label + ": after the node transform, vertex " + std::to_string(i) + " coordinate");
    }
    const glm::dvec3 nw = normalMatrix * glm::dvec3(local.normals[i]);
    const double len = glm::length(nw);
    out.normals[i] = len > 0.0 && std::isfinite(len) ? Vec3(nw / len) : Vec3(0.f);
  }
  out.uvs = local.uvs;

  out.indices.clear();
  out.indices.reserve(local.indices.size());
  DroppedTriangles dropped;
  for (size_t t = 0; t + 2 < local.indices.size(); t += 3) {
    uint32_t i0 = local.indices[t], i1 = local.indices[t + 1], i2 = local.indices[t + 2];
    if (flip) std::swap(i1, i2);
    // The renderer's geometric normal and area light, exactly: normalize(cross(p1 - p0, p2 - p0))
    // in float, whose squared length overflows long before the corners do.
    const Vec3& p0 = out.positions[i0];
    const Vec3 ng = glm::cross(out.positions[i1] - p0, out.positions[i2] - p0);
    const float len2 = glm::dot(ng, ng);
    if (!std::isfinite(len2)) {
      const double edge = std::max({glm::length(glm::dvec3(out.positions[i1]) - glm::dvec3(p0)),
                                    glm::length(glm::dvec3(out.positions[i2]) - glm::dvec3(p0))});
      throw LoadError(label + ": triangle " + std::to_string(t / 3) + " (an edge of " +
                      formatNumber(edge) + ") is too large: its area " + overflowText());
    }
    if (!(len2 > 0.f)) {
      const uint32_t* idx = &local.indices[t];
      const Vec3 q0 = local.positions[idx[0]];
      const Vec3 localNg = glm::cross(local.positions[idx[1]] - q0, local.positions[idx[2]] - q0);
      ++(glm::dot(localNg, localNg) > 0.f ? dropped.collapsed : dropped.zeroArea);
      continue;
    }
    for (uint32_t i : {i0, i1, i2}) {
      if (out.normals[i] == Vec3(0.f)) out.normals[i] = ng / std::sqrt(len2);
    }
    out.indices.push_back(i0);
    out.indices.push_back(i1);
    out.indices.push_back(i2);
  }
  if (dropped.zeroArea + dropped.collapsed > 0) {
    // Drop the vertices only dropped triangles used: they would widen the scene's bounds.
    std::vector<uint32_t> remap(n, AttributeCache::kUnused);
    uint32_t kept = 0;
    for (uint32_t& i : out.indices) {
      if (remap[i] == AttributeCache::kUnused) remap[i] = kept++;
      i = remap[i];
    }
    std::vector<Vec3> positions(kept), normals(kept);
    std::vector<Vec2> uvs(out.uvs.empty() ? 0 : kept);
    for (size_t v = 0; v < n; ++v) {
      if (remap[v] == AttributeCache::kUnused) continue;
      positions[remap[v]] = out.positions[v];
      normals[remap[v]] = out.normals[v];
      if (!uvs.empty()) uvs[remap[v]] = out.uvs[v];
    }
    out.positions = std::move(positions);
    out.normals = std::move(normals);
    out.uvs = std::move(uvs);
  }
  return dropped;
}

}  // namespace pathlab::gltf
