// Internals shared by the glTF loader's source files (gltf_*.cpp); not part of pathlab's interface.
#pragma once

#include "core/scene/scene_desc.h"

#include <tiny_gltf.h>

#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace pathlab::gltf {

// A problem with the file, without the path: loadGltf prefixes the path and rethrows it as a
// one-line SceneError.
class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The scene's warnings, each distinct message once (an instanced mesh warns once, not per
// instance).
class Warnings {
 public:
  void add(const std::string& message);
  std::vector<std::string> take() { return std::move(list_); }

 private:
  std::vector<std::string> list_;
  std::unordered_set<std::string> seen_;
};

// Replaces line breaks and tabs by single spaces and trims: SceneError messages are one line.
std::string oneLine(const std::string& text);
// Shortens every base64 data URI in tinygltf's messages to its header: a message is one line,
// not megabytes of an embedded buffer.
std::string elideDataUris(const std::string& text);
std::string quoted(const std::string& name);  // " 'name'", or "" for an unnamed object

// Reads and parses `path` (.gltf or .glb, told apart by the magic bytes); tinygltf's warnings are
// added to `warnings`. Throws LoadError for a missing, unreadable, truncated or invalid file.
tinygltf::Model parseFile(const std::string& path, Warnings& warnings);

// ---- accessors (gltf_accessors.cpp) ----------------------------------------------------------
// Every read is bounds-checked against the buffer before any byte is touched; violations throw
// LoadError naming the accessor, the bufferView and the buffer. `what` describes the use, e.g.
// "POSITION of mesh 'box'".
std::vector<Vec3> readVec3(const tinygltf::Model& model, int accessor, const std::string& what);
std::vector<Vec2> readVec2(const tinygltf::Model& model, int accessor, const std::string& what);
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                  const std::string& what);

// tinygltf image callback: refuses an image whose bufferView lies outside its buffer (tinygltf
// 2.7 passes such a pointer to stb unchecked), then decodes with tinygltf's stb loader.
// user_data: the tinygltf::Model being loaded.
bool loadImageChecked(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                      int reqWidth, int reqHeight, const unsigned char* bytes, int size,
                      void* userData);

// ---- materials and textures (gltf_materials.cpp) ---------------------------------------------
// Fills desc.materials 1:1 with model.materials and desc.textures with the decoded images they use.
void convertMaterials(const tinygltf::Model& model, SceneDesc& desc, Warnings& warnings);

// ---- geometry (gltf_geometry.cpp) ------------------------------------------------------------
// One triangle primitive decoded in its mesh's local space, shared by all nodes instancing it.
struct LocalPrimitive {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // unit, one per position (flat normals generated when absent)
  std::vector<Vec2> uvs;      // empty or one per position
  std::vector<uint32_t> indices;
};

// Vertex attributes decoded once per accessor: the primitives of a mesh often share one vertex
// buffer and each index a part of it, and decoding it per primitive would be quadratic.
class AttributeCache {
 public:
  // POSITION data, checked finite on first use (the error names `label`, the first user).
  const std::vector<Vec3>& positions(const tinygltf::Model& model, int accessor,
                                     const std::string& label);
  const std::vector<Vec3>& vec3(const tinygltf::Model& model, int accessor,
                                const std::string& what);
  const std::vector<Vec2>& vec2(const tinygltf::Model& model, int accessor,
                                const std::string& what);
  // Scratch old -> new vertex map of at least `size` entries, every entry kUnused between uses.
  std::vector<uint32_t>& remap(size_t size);
  static constexpr uint32_t kUnused = ~0u;

 private:
  std::unordered_map<int, std::vector<Vec3>> vec3_;
  std::unordered_map<int, std::vector<Vec2>> vec2_;
  std::vector<uint32_t> remap_;
};

// Decodes mesh `meshIndex`'s primitive `primitiveIndex` (mode TRIANGLES, checked by the caller),
// keeping only the vertices its indices use.
LocalPrimitive decodePrimitive(const tinygltf::Model& model, int meshIndex, int primitiveIndex,
                               AttributeCache& cache, Warnings& warnings);

// Transforms `local` by `toWorld` into `out` (positions, inverse-transpose normals, winding
// flipped for a mirroring transform) and drops zero-area triangles; returns how many it dropped.
size_t instantiatePrimitive(const LocalPrimitive& local, const glm::dmat4& toWorld,
                            TriangleMesh& out);

}  // namespace pathlab::gltf
