// glTF 2.0 -> SceneDesc: extension policy, the node hierarchy of the default scene (meshes,
// KHR_lights_punctual lights, camera) and the whole-scene checks.
#include "core/scene/gltf_loader.h"

#include "core/scene/gltf_internal.h"

#include "core/io/vdb_file.h"
#include "core/media/volume_grid.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <new>
#include <set>
#include <sstream>

namespace pathlab {
namespace gltf {

namespace {

// Extensions whose every feature pathlab renders (KHR_mesh_quantization: the accessor reader
// converts any component type). Their textures where they have any are warned about in place.
const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual",    "KHR_materials_emissive_strength", "KHR_materials_ior",
    "KHR_materials_specular", "KHR_materials_transmission",      "KHR_mesh_quantization",
    "KHR_texture_transform",  "KHR_materials_volume",            "KHR_materials_volume_scatter",
    "PATHLAB_materials_volume_grid"};

void checkExtensions(const tinygltf::Model& model, Warnings& warnings) {
  std::string unsupported;
  for (const std::string& name : model.extensionsRequired) {
    if (!kSupportedExtensions.count(name)) unsupported += (unsupported.empty() ? "" : ", ") + name;
  }
  if (!unsupported.empty()) throw LoadError("unsupported required extension " + unsupported);
  // One line for all of them: a file lists each extension once, however many materials use it.
  std::vector<std::string> ignored;
  for (const std::string& name : model.extensionsUsed) {
    if (!kSupportedExtensions.count(name) && std::find(ignored.begin(), ignored.end(), name) == ignored.end())
      ignored.push_back(name);
  }
  if (!ignored.empty()) {
    std::string list;
    for (const std::string& name : ignored) list += (list.empty() ? "" : ", ") + name;
    warnings.add(std::string(ignored.size() > 1 ? "optional extensions " : "optional extension ") +
                 list + (ignored.size() > 1 ? " are" : " is") + " not supported; ignored");
  }
}

// glTF 2.0 spec, sec. 3.5.3: matrix, or T * R * S with R a unit quaternion (x, y, z, w).
glm::dmat4 localTransform(const tinygltf::Model& model, int index) {
  const tinygltf::Node& node = model.nodes[size_t(index)];
  const std::string label = nodeLabel(model, index);
  auto check = [&](const std::vector<double>& v, size_t size, const char* what) {
    if (!v.empty() && v.size() != size) {
      throw LoadError(label + ": " + what + " must have " + std::to_string(size) + " numbers");
    }
    for (double x : v) {
      if (!std::isfinite(x)) throw LoadError(label + ": " + what + " is not finite");
    }
  };
  check(node.matrix, 16, "matrix");
  if (!node.matrix.empty()) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(4 * c + r)];
    }
    return m;
  }
  check(node.translation, 3, "translation");
  check(node.rotation, 4, "rotation");
  check(node.scale, 3, "scale");
  glm::dmat4 m(1.0);
  if (!node.translation.empty()) {
    m = glm::translate(m,
                       glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double len = glm::length(q);
    if (!(len > 1e-12)) throw LoadError(label + ": rotation is not a unit quaternion");
    m = m * glm::mat4_cast(q / len);
  }
  if (!node.scale.empty()) {
    m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return m;
}

// The camera frame without scale or shear: keep the view direction (-z) exactly, then the up
// vector (+y) as close as possible, right-handed.
Mat4 orthonormalCameraToWorld(const glm::dmat4& world, const std::string& label) {
  const glm::dvec3 z = glm::normalize(glm::dvec3(world[2]));
  glm::dvec3 y = glm::dvec3(world[1]);
  y = glm::normalize(y - z * glm::dot(y, z));
  const glm::dvec3 x = glm::cross(y, z);
  const glm::dmat4 m(glm::dvec4(x, 0.0), glm::dvec4(y, 0.0), glm::dvec4(z, 0.0), world[3]);
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) throw LoadError(label + ": degenerate camera transform");
    }
  }
  for (int r = 0; r < 3; ++r) toFiniteFloat(m[3][r], label + ": position coordinate");
  return Mat4(m);
}

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, SceneDesc& desc, Warnings& warnings)
      : model_(model), desc_(desc), warnings_(warnings) {}

  void build(const std::vector<NodeVisit>& visits);

 private:
  void visit(int index, const glm::dmat4& world);
  void addMesh(int nodeIndex, const glm::dmat4& world);
  void addCamera(int nodeIndex, const glm::dmat4& world);
  void addLight(int nodeIndex, const glm::dmat4& world);
  int defaultMaterial();
  void placeVolumeGrid(int nodeIndex, int material, const glm::dmat4& world);

  const tinygltf::Model& model_;
  SceneDesc& desc_;
  Warnings& warnings_;
  std::map<std::pair<int, int>, LocalPrimitive> primitives_;  // decoded once per (mesh, primitive)
  AttributeCache attributes_;
  int defaultMaterial_ = -1;
};

void SceneBuilder::build(const std::vector<NodeVisit>& visits) {
  std::vector<glm::dmat4> world(visits.size());
  for (size_t i = 0; i < visits.size(); ++i) {
    const NodeVisit& v = visits[i];
    const glm::dmat4 parent = v.parent >= 0 ? world[size_t(v.parent)] : glm::dmat4(1.0);
    world[i] = parent * localTransform(model_, v.node);
    visit(v.node, world[i]);
  }
}

void SceneBuilder::visit(int index, const glm::dmat4& world) {
  const tinygltf::Node& node = model_.nodes[size_t(index)];
  if (node.mesh >= 0) addMesh(index, world);
  if (node.camera >= 0) addCamera(index, world);
  if (node.extensions.count("KHR_lights_punctual")) addLight(index, world);
}

int SceneBuilder::defaultMaterial() {
  if (defaultMaterial_ < 0) {
    Material m;  // glTF 2.0 spec, sec. 3.9.6: baseColor 1, metallic 1, roughness 1
    m.name = "default";
    desc_.materials.push_back(m);
    defaultMaterial_ = int(desc_.materials.size()) - 1;
  }
  return defaultMaterial_;
}

// A material's density grid lies in the space of the node that instances its meshes: one
// transform per material (a medium is the material's, wherever its meshes are).
void SceneBuilder::placeVolumeGrid(int nodeIndex, int material, const glm::dmat4& world) {
  Material& m = desc_.materials[size_t(material)];
  if (!m.volume || !m.volume->grid) return;
  VolumeGridRef& ref = *m.volume->grid;
  const Mat4 placement(world);
  if (ref.placed && ref.nodeToWorld != placement)
    throw LoadError(nodeLabel(model_, nodeIndex) + ": material " + std::to_string(material) + quotedName(m.name) +
                    " has a density grid (PATHLAB_materials_volume_grid) and is instanced by nodes with different"
                    " transforms; give each placement a material of its own");
  ref.placed = true;
  ref.nodeToWorld = placement;
}

// Reads every placed density grid, next to the glTF file (core/io/vdb_file.h).
void loadVolumeGrids(SceneDesc& desc, Warnings& warnings) {
  const std::filesystem::path dir = std::filesystem::path(desc.path).parent_path();
  for (size_t i = 0; i < desc.materials.size(); ++i) {
    Material& m = desc.materials[i];
    if (!m.volume || !m.volume->grid) continue;
    VolumeGridRef& ref = *m.volume->grid;
    const std::string label = "material " + std::to_string(i) + quotedName(m.name) + ": PATHLAB_materials_volume_grid";
    if (!ref.placed) continue;  // no node instances it: nothing to read
    if (m.transmissionFactor <= 0.f) continue;  // an opaque surface bounds no medium
    const std::string path = (dir / ref.uri).string();
    try {
      VdbDensity vdb = readDensityVdb(path, ref.grid, ref.densityScale);
      if (vdb.grid.voxelCount() == 0) warnings.add(label, ref.uri + ": grid '" + ref.grid + "' has no active voxel; the medium is empty");
      ref.data = std::make_shared<const VolumeGrid>(std::move(vdb.grid), ref.nodeToWorld * vdb.indexToWorld);
    } catch (const VdbError& e) {
      throw LoadError(label + ": " + e.what());
    }
  }
}

void SceneBuilder::addMesh(int nodeIndex, const glm::dmat4& world) {
  const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
  if (size_t(node.mesh) >= model_.meshes.size()) {
    throw LoadError(nodeLabel(model_, nodeIndex) + " refers to mesh " + std::to_string(node.mesh) +
                    ", which does not exist");
  }
  if (node.skin >= 0) {
    warnings_.add(nodeLabel(model_, nodeIndex), "skinning is not supported; bind pose used");
  }
  const tinygltf::Mesh& mesh = model_.meshes[size_t(node.mesh)];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string label = "mesh " + std::to_string(node.mesh) + quotedName(mesh.name) +
                              (mesh.primitives.size() > 1 ? " primitive " + std::to_string(p) : "");
    if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
      static const char* const kModes[] = {"POINTS",      "LINES",     "LINE_LOOP",
                                           "LINE_STRIP",  "TRIANGLES", "TRIANGLE_STRIP",
                                           "TRIANGLE_FAN"};
      const std::string mode =
          prim.mode >= 0 && prim.mode <= 6 ? kModes[prim.mode] : std::to_string(prim.mode);
      warnings_.add(label, "mode " + mode + " is not supported (triangles only); skipped");
      continue;
    }
    if (!prim.targets.empty()) warnings_.add(label, "morph targets are not supported; ignored");
    int material;
    if (prim.material < 0) {
      material = defaultMaterial();
    } else if (size_t(prim.material) < model_.materials.size()) {
      material = prim.material;
    } else {
      throw LoadError(label + " refers to material " + std::to_string(prim.material) +
                      ", which does not exist");
    }
    auto key = std::make_pair(node.mesh, int(p));
    auto it = primitives_.find(key);
    if (it == primitives_.end()) {
      const Material& m = desc_.materials[size_t(material)];
      const VertexNeeds needs{m.normalTexture.valid(), m.normalTexture.texCoord};
      it = primitives_
               .emplace(key, decodePrimitive(model_, node.mesh, int(p), needs, attributes_, warnings_))
               .first;
    }
    const LocalPrimitive& local = it->second;
    if (local.indices.empty()) continue;
    if (local.uvs1.empty()) {
      const Material& m = desc_.materials[size_t(material)];
      for (const TextureRef* ref : {&m.baseColorTexture, &m.metallicRoughnessTexture,
                                    &m.emissiveTexture, &m.normalTexture}) {
        if (ref->valid() && ref->texCoord == 1) {
          warnings_.add(label, "no TEXCOORD_1, which its material reads; TEXCOORD_0 used");
          break;
        }
      }
    }
    placeVolumeGrid(nodeIndex, material, world);
    TriangleMesh out;
    out.name = local.name;
    out.material = material;
    const DroppedTriangles dropped =
        instantiatePrimitive(local, world, nodeLabel(model_, nodeIndex) + ", " + label, out);
    if (dropped.zeroArea > 0) {
      warnings_.add(label, std::to_string(dropped.zeroArea) + " zero-area triangle" +
                    (dropped.zeroArea > 1 ? "s" : "") + " dropped");
    }
    if (dropped.collapsed > 0) {
      // Not "zero area": the cause is the transform's scale or distance, lost to float precision.
      warnings_.add(nodeLabel(model_, nodeIndex) + ", " + label,
                    std::to_string(dropped.collapsed) + " triangle" +
                    (dropped.collapsed > 1 ? "s" : "") +
                    " dropped: the node transform leaves them no area in 32-bit floats");
    }
    if (out.triangleCount() > 0) desc_.meshes.push_back(std::move(out));
  }
}

void SceneBuilder::addCamera(int nodeIndex, const glm::dmat4& world) {
  const int index = model_.nodes[size_t(nodeIndex)].camera;
  if (size_t(index) >= model_.cameras.size()) {
    throw LoadError(nodeLabel(model_, nodeIndex) + " refers to camera " + std::to_string(index) +
                    ", which does not exist");
  }
  const tinygltf::Camera& camera = model_.cameras[size_t(index)];
  const std::string label = "camera " + std::to_string(index) + quotedName(camera.name);
  if (camera.type != "perspective" && camera.type != "orthographic") {
    warnings_.add(label, camera.type + " cameras are not supported; ignored");
    return;
  }
  if (desc_.camera) return;  // the first camera in document order wins
  if (camera.type == "orthographic") {
    // glTF 2.0 sec. 5.13: xmag and ymag are half the view's width and height, never zero (a
    // negative one would mirror the image, which no viewer does: refused too).
    const double xmag = camera.orthographic.xmag, ymag = camera.orthographic.ymag;
    if (!(xmag > 0.0) || !(ymag > 0.0)) {
      throw LoadError(label + ": orthographic xmag " + formatNumber(xmag) + " and ymag " + formatNumber(ymag) +
                      " must both be positive");
    }
    CameraDesc c;
    c.name = camera.name;
    c.orthographic = Vec2(toFiniteFloat(xmag, label + ": xmag"), toFiniteFloat(ymag, label + ": ymag"));
    if (!(c.orthographic->x > 0.f) || !(c.orthographic->y > 0.f))
      throw LoadError(label + ": xmag or ymag is 0 as a 32-bit float");
    c.aspectRatio = toFiniteFloat(xmag / ymag, label + ": xmag / ymag");
    if (!(*c.aspectRatio > 0.f)) throw LoadError(label + ": xmag / ymag is 0 as a 32-bit float");
    c.cameraToWorld = orthonormalCameraToWorld(world, label);
    desc_.camera = c;
    return;
  }
  const double yfov = camera.perspective.yfov;
  if (!(yfov > 0.0 && yfov < glm::pi<double>())) {
    throw LoadError(label + ": yfov " + formatNumber(yfov) + " is not in (0, pi)");
  }
  CameraDesc c;
  c.name = camera.name;
  c.yfov = float(yfov);
  const double aspect = camera.perspective.aspectRatio;
  // Absent (0) or not positive: the image's own aspect ratio is used.
  if (aspect > 0.0) c.aspectRatio = toFiniteFloat(aspect, label + ": aspectRatio");
  if (c.aspectRatio && !(*c.aspectRatio > 0.f)) {
    throw LoadError(label + ": aspectRatio " + formatNumber(aspect) + " is 0 as a 32-bit float");
  }
  c.cameraToWorld = orthonormalCameraToWorld(world, label);
  desc_.camera = c;
}

// KHR_lights_punctual: the light sits at the node's origin and shines down the node's -z.
void SceneBuilder::addLight(int nodeIndex, const glm::dmat4& world) {
  const std::string nodeName = nodeLabel(model_, nodeIndex);
  const tinygltf::Value& ext = model_.nodes[size_t(nodeIndex)].extensions.at("KHR_lights_punctual");
  if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber()) {
    throw LoadError(nodeName + ": KHR_lights_punctual has no light index");
  }
  const double lightIndex = ext.Get("light").GetNumberAsDouble();
  if (!(lightIndex >= 0.0 && lightIndex < double(model_.lights.size())) ||
      lightIndex != std::floor(lightIndex)) {
    std::ostringstream index;
    index << lightIndex;
    throw LoadError(nodeName + " refers to light " + index.str() + ", which does not exist");
  }
  const tinygltf::Light& g = model_.lights[size_t(lightIndex)];
  const std::string label = "light " + std::to_string(size_t(lightIndex)) + quotedName(g.name);
  PunctualLightDesc light;
  light.name = !g.name.empty() ? g.name : label;
  if (g.type == "point") {
    light.type = PunctualLightType::Point;
  } else if (g.type == "spot") {
    light.type = PunctualLightType::Spot;
  } else if (g.type == "directional") {
    light.type = PunctualLightType::Directional;
  } else {
    warnings_.add(label, "light type '" + g.type + "' is not supported; ignored");
    return;
  }
  if (!g.color.empty()) {
    if (g.color.size() != 3) throw LoadError(label + ": color must have 3 components");
    for (int k = 0; k < 3; ++k) light.color[k] = toFiniteFloat(g.color[size_t(k)], label + ": color");
  }
  light.intensity = toFiniteFloat(g.intensity, label + ": intensity");
  if (light.intensity < 0.f || light.color.r < 0.f || light.color.g < 0.f || light.color.b < 0.f) {
    throw LoadError(label + ": color and intensity must be non-negative");
  }
  // The renderer's emitted intensity is this product, in float.
  if (!isFinite(light.color * light.intensity)) {
    throw LoadError(label + ": color x intensity (" + formatNumber(maxComponent(light.color)) +
                    " x " + formatNumber(light.intensity) + ") " + overflowText());
  }
  // `range` is ignored: pathlab's lights follow the inverse-square law to infinity.
  if (light.type == PunctualLightType::Spot) {
    // Checked and clamped in double: a huge angle must not pass as float infinity.
    double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    if (!(outer > 0.0 && outer <= kPi / 2.0 && inner >= 0.0 && inner < outer)) {
      warnings_.add(label, "cone angles (inner " + formatNumber(inner) + ", outer " +
                    formatNumber(outer) + ") need 0 <= inner < outer <= pi/2; clamped");
      outer = std::isfinite(outer) ? std::clamp(outer, 1e-4, kPi / 2.0) : kPi / 4.0;
      inner = std::isfinite(inner) ? std::clamp(inner, 0.0, outer * 0.999) : 0.0;
    }
    light.innerConeAngle = float(inner);
    light.outerConeAngle = float(outer);
  }
  const glm::dvec4 position = world * glm::dvec4(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    light.position[k] = toFiniteFloat(position[k], nodeName + ": position coordinate of " + label);
  }
  const glm::dvec3 direction = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  const double len = glm::length(direction);
  if (!(len > 0.0) || !std::isfinite(len)) {
    throw LoadError(nodeName + ": degenerate transform for " + label);
  }
  light.direction = Vec3(direction / len);
  desc_.punctualLights.push_back(light);
}

SceneDesc load(const std::string& path, const LoadOptions& options) {
  Warnings warnings;
  tinygltf::Model model = parseFile(path, warnings);
  checkExtensions(model, warnings);
  // Counted before any material, texture or geometry is decoded: an instancing bomb is refused
  // in the time it takes to walk its node tree.
  const std::vector<NodeVisit> visits = walkHierarchy(model);
  countInstances(model, visits, options.maxTriangles);
  SceneDesc desc;
  desc.path = path;
  convertMaterials(model, desc, warnings);
  SceneBuilder(model, desc, warnings).build(visits);
  loadVolumeGrids(desc, warnings);
  addEnvironment(options, desc, warnings);
  desc.lightSelection = options.lightSelection;
  checkScene(desc, options.requireEmitter);
  desc.warnings = warnings.take();
  return desc;
}

}  // namespace
}  // namespace gltf

SceneDesc loadGltf(const std::string& path, const LoadOptions& options) {
  try {
    return gltf::load(path, options);
  } catch (const gltf::LoadError& e) {
    throw SceneError(gltf::oneLine(path + ": " + e.what()));
  } catch (const std::bad_alloc&) {
    throw SceneError(gltf::oneLine(path + ": out of memory while loading"));
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(gltf::oneLine(path + ": " + e.what()));
  }
}

}  // namespace pathlab
