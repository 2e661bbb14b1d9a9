// Internals shared by the glTF loader's source files (gltf_*.cpp); not part of pathlab's interface.
#pragma once

#include "core/scene/gltf_loader.h"
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

// The scene's warnings: each distinct (subject, problem) once (an instanced mesh warns once, not
// per instance), and the same problem of many subjects folded into one line with a count
// ("2 zero-area triangles dropped (98 times: mesh 0 'Sphere', mesh 1 'Sphere', ...)"), in the
// order problems first appeared.
class Warnings {
 public:
  // `subject` names the object ("material 3 'glass'"); "" for a problem of the whole file.
  void add(const std::string& subject, const std::string& problem);
  void add(const std::string& message) { add("", message); }
  std::vector<std::string> take();

 private:
  struct Problem {
    std::string text;
    std::vector<std::string> subjects;
  };
  std::vector<Problem> problems_;
  std::unordered_map<std::string, size_t> index_;  // problem text -> problems_ index
  std::unordered_set<std::string> seen_;           // subject + '\0' + problem
};

// Replaces line breaks and tabs by single spaces and trims: SceneError messages are one line.
std::string oneLine(const std::string& text);
// Shortens every base64 data URI in tinygltf's messages to its header: a message is one line,
// not megabytes of an embedded buffer.
std::string elideDataUris(const std::string& text);
std::string quotedName(const std::string& name);  // " 'name'", or "" for an unnamed object

// Reads and parses `path` (.gltf or .glb, told apart by the magic bytes); tinygltf's warnings are
// added to `warnings`. Throws LoadError for a missing, unreadable, truncated or invalid file, and
// for a buffer or image file that is not a regular file.
tinygltf::Model parseFile(const std::string& path, Warnings& warnings);

// ---- file access (gltf_fs.cpp) ---------------------------------------------------------------
// readGuardedFile (core/io/guarded_file.h), its refusal as a LoadError without the path
// ("is a FIFO, not a regular file"): the loader's messages name the file their own way.
std::vector<unsigned char> readRegularFile(const std::string& path);

// tinygltf's file-system callbacks for the files a scene references, resolved in its directory
// `baseDir` and read with readRegularFile; each refused file is kept for parseFile's message.
class ExternalFiles {
 public:
  struct Refusal {
    std::string path;      // as tinygltf asked for it
    std::string relative;  // to the scene's directory, for the message
    std::string problem;   // readRegularFile's message
  };
  explicit ExternalFiles(std::string baseDir);
  tinygltf::FsCallbacks callbacks();  // valid while this object lives
  const std::vector<Refusal>& refusals() const { return refusals_; }

 private:
  std::string relative(const std::string& path) const;
  static bool exists(const std::string& path, void* self);
  static std::string expand(const std::string& path, void* self);
  static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* self);
  static bool write(std::string* err, const std::string& path,
                    const std::vector<unsigned char>& contents, void* self);

  std::string baseDir_;
  std::vector<Refusal> refusals_;
};

// ---- numbers (gltf_numbers.cpp) --------------------------------------------------------------
std::string formatNumber(double value);  // shortest readable form, e.g. "1e+39"
std::string overflowText();              // "overflows a 32-bit float (largest 3.40282e+38)"
// `value` as the float the renderer will use; LoadError "WHAT VALUE is not a finite number" or
// "WHAT VALUE overflows a 32-bit float (...)". `what` names the value, e.g. "material 0: ior".
float toFiniteFloat(double value, const std::string& what);

// ---- node hierarchy (gltf_hierarchy.cpp) -----------------------------------------------------
std::string nodeLabel(const tinygltf::Model& model, int index);  // "node 3 'name'"

struct NodeVisit {
  int node;
  int parent;  // index of the parent's visit, -1 for a root
};
// The default scene's nodes in document pre-order (parents before children). Throws LoadError
// for a default scene that does not exist, a node or child that does not exist, and a node
// reached twice.
std::vector<NodeVisit> walkHierarchy(const tinygltf::Model& model);

struct InstanceCount {
  uint64_t instances = 0;  // nodes with a mesh
  uint64_t triangles = 0;  // before zero-area triangles are dropped
};
// Counts what `visits` will instance from the accessor counts alone; throws LoadError naming the
// count and the limit as soon as the triangles pass `maxTriangles`.
InstanceCount countInstances(const tinygltf::Model& model, const std::vector<NodeVisit>& visits,
                             uint64_t maxTriangles);

// ---- accessors (gltf_accessors.cpp) ----------------------------------------------------------
// Every read is bounds-checked against the buffer before any byte is touched; violations throw
// LoadError naming the accessor, the bufferView and the buffer. `what` describes the use, e.g.
// "POSITION of mesh 'box'".
std::vector<Vec3> readVec3(const tinygltf::Model& model, int accessor, const std::string& what);
std::vector<Vec2> readVec2(const tinygltf::Model& model, int accessor, const std::string& what);
std::vector<Vec4> readVec4(const tinygltf::Model& model, int accessor, const std::string& what);
// COLOR_n: VEC3 (alpha 1) or VEC4, float or normalized integers.
std::vector<Vec4> readColors(const tinygltf::Model& model, int accessor, const std::string& what);
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                  const std::string& what);

// tinygltf image callback: refuses an image whose bufferView lies outside its buffer (tinygltf
// 2.7 passes such a pointer to stb unchecked), then decodes with tinygltf's stb loader.
// user_data: the tinygltf::Model being loaded.
bool loadImageChecked(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                      int reqWidth, int reqHeight, const unsigned char* bytes, int size,
                      void* userData);

// ---- materials and textures (gltf_materials.cpp) ---------------------------------------------
// Fills desc.materials 1:1 with model.materials and desc.textures with the images they use; the
// pixels of those images are moved out of `model` (held once, shared by their textures).
void convertMaterials(tinygltf::Model& model, SceneDesc& desc, Warnings& warnings);

// ---- geometry (gltf_geometry.cpp) ------------------------------------------------------------
// One triangle primitive decoded in its mesh's local space, shared by all nodes instancing it.
struct LocalPrimitive {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // unit, one per position (flat normals generated when absent)
  std::vector<Vec2> uvs;      // TEXCOORD_0: empty or one per position
  std::vector<Vec2> uvs1;     // TEXCOORD_1: empty or one per position
  std::vector<Vec4> colors;   // COLOR_0 (rgba): empty or one per position
  std::vector<Vec4> tangents; // TANGENT (xyz, w = handedness): empty or one per position
  std::vector<uint32_t> indices;
};

// What a primitive's material asks of its vertices beyond positions and normals.
struct VertexNeeds {
  bool tangents = false;   // a normal map: TANGENT from the file, else generated
  int tangentUvSet = 0;    // the uv set the normal map reads (tangents follow its derivatives)
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
  const std::vector<Vec4>& vec4(const tinygltf::Model& model, int accessor,
                                const std::string& what);
  const std::vector<Vec4>& colors(const tinygltf::Model& model, int accessor,
                                  const std::string& what);
  // Scratch old -> new vertex map of at least `size` entries, every entry kUnused between uses.
  std::vector<uint32_t>& remap(size_t size);
  static constexpr uint32_t kUnused = ~0u;

 private:
  std::unordered_map<int, std::vector<Vec3>> vec3_;
  std::unordered_map<int, std::vector<Vec2>> vec2_;
  std::unordered_map<int, std::vector<Vec4>> vec4_;
  std::unordered_map<int, std::vector<Vec4>> colors_;
  std::vector<uint32_t> remap_;
};

// Decodes mesh `meshIndex`'s primitive `primitiveIndex` (mode TRIANGLES, checked by the caller),
// keeping only the vertices its indices use.
LocalPrimitive decodePrimitive(const tinygltf::Model& model, int meshIndex, int primitiveIndex,
                               const VertexNeeds& needs, AttributeCache& cache,
                               Warnings& warnings);

struct DroppedTriangles {
  size_t zeroArea = 0;   // already without area in the mesh
  size_t collapsed = 0;  // with area in the mesh, none in float after the node transform
};
// Transforms `local` by `toWorld` into `out` (positions, inverse-transpose normals, winding
// flipped for a mirroring transform) and drops zero-area triangles. Throws LoadError (starting
// with `label`) for a position or a triangle area that overflows a float.
DroppedTriangles instantiatePrimitive(const LocalPrimitive& local, const glm::dmat4& toWorld,
                                      const std::string& label, TriangleMesh& out);

// ---- whole-scene checks (gltf_scene_checks.cpp) ---------------------------------------------
// Throws LoadError when nothing emits (if `requireEmitter`; an environment light counts), or when
// the scene's extent or its lights' total power overflows the floats the renderer computes them in.
void checkScene(const SceneDesc& desc, bool requireEmitter);
// Whether the file's own triangles or punctual lights emit anything.
bool hasEmitter(const SceneDesc& desc);
// Whether the file has a light meant to light it: a KHR_lights_punctual light, or an emissive
// material without an emissive texture (a lamp). Emission only through textures (a display, LEDs,
// a helmet's visor) marks glowing details, which other glTF viewers show under an environment.
bool hasLamp(const SceneDesc& desc);

// ---- environment light (gltf_environment.cpp) ------------------------------------------------
// LoadOptions::environment, or the default light for a file without one (a notice in warnings).
void addEnvironment(const LoadOptions& options, SceneDesc& desc, Warnings& warnings);

}  // namespace pathlab::gltf
