// Tests that the glTF loader opens only regular files, for the scene and for every buffer and
// image it references: a FIFO, a directory or a device fails at once with one line naming the
// file and what it is, and never hangs (each load runs in a child process with a deadline).
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_load_guard.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

namespace pathlab {
namespace {

using namespace gltf_test;

// A directory of its own per test, so the special files do not meet the other tests' files.
fs::path freshDir(const std::string& name) {
  const fs::path dir = tempDir() / "special" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

enum class Special { Fifo, Directory, Device };

// Creates `path` as the special file; the device is /dev/zero through a symlink (the loader
// follows symlinks, as open would).
void makeSpecial(const fs::path& path, Special kind) {
  switch (kind) {
    case Special::Fifo: ASSERT_EQ(mkfifo(path.c_str(), 0600), 0) << path; break;
    case Special::Directory: fs::create_directory(path); break;
    case Special::Device: fs::create_symlink("/dev/zero", path); break;
  }
}

const char* kindWord(Special kind) {
  return kind == Special::Fifo ? "FIFO" : kind == Special::Directory ? "directory" : "device";
}

// The load fails within the deadline with "PATH: <what> ... <kind> ..., not a regular file".
void expectRefused(const std::string& path, const std::string& what, Special kind) {
  const GuardedLoad r = loadWithDeadline(path);
  ASSERT_TRUE(r.finished) << path << ": the load did not finish (hung or crashed)";
  ASSERT_FALSE(r.loaded) << path << " loaded";
  EXPECT_EQ(r.message.rfind(path + ": ", 0), 0u) << r.message;
  EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
  EXPECT_NE(r.message.find(what), std::string::npos) << r.message;
  EXPECT_NE(r.message.find(kindWord(kind)), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("not a regular file"), std::string::npos) << r.message;
}

// One triangle whose vertex data is in the external buffer `uri`.
std::string withExternalBuffer(const TestGltf& g, const std::string& uri) {
  return replaced(g.json(), "data:application/octet-stream;base64," + base64(g.bin), uri);
}

TestGltf oneTriangleScene() {
  TestGltf g;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  return g;
}

// A textured triangle whose base colour image is the external file `uri`.
std::string withExternalImage(const std::string& uri) {
  TestGltf g;
  g.add("images", R"({"uri":")" + uri + R"("})");
  g.add("textures", R"({"source":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  addTexturedTriangle(g);
  return g.json();
}

constexpr Special kKinds[] = {Special::Fifo, Special::Directory, Special::Device};

TEST(GltfSpecialFiles, SceneFileThatIsNotARegularFileIsRefused) {
  for (Special kind : kKinds) {
    SCOPED_TRACE(kindWord(kind));
    const fs::path dir = freshDir(std::string("scene-") + kindWord(kind));
    const fs::path path = dir / "scene.gltf";
    makeSpecial(path, kind);
    expectRefused(path.string(), "scene.gltf: is ", kind);
  }
  // A device named directly, as a user might type it.
  expectRefused("/dev/zero", "/dev/zero: is a character device", Special::Device);
}

TEST(GltfSpecialFiles, BufferThatIsNotARegularFileIsRefused) {
  const TestGltf g = oneTriangleScene();
  for (Special kind : kKinds) {
    SCOPED_TRACE(kindWord(kind));
    const fs::path dir = freshDir(std::string("buffer-") + kindWord(kind));
    makeSpecial(dir / "data.bin", kind);
    const fs::path scene = dir / "scene.gltf";
    std::ofstream(scene) << withExternalBuffer(g, "data.bin");
    expectRefused(scene.string(), "buffer 'data.bin' is ", kind);
  }
}

TEST(GltfSpecialFiles, ImageThatIsNotARegularFileIsRefused) {
  for (Special kind : kKinds) {
    SCOPED_TRACE(kindWord(kind));
    const fs::path dir = freshDir(std::string("image-") + kindWord(kind));
    makeSpecial(dir / "texture.png", kind);
    const fs::path scene = dir / "scene.gltf";
    std::ofstream(scene) << withExternalImage("texture.png");
    expectRefused(scene.string(), "image 'texture.png' is ", kind);
  }
}

TEST(GltfSpecialFiles, BinaryGltfWithAFifoBufferIsRefused) {
  // A .glb may still name external buffers; the same guarded reader serves them.
  const TestGltf g = oneTriangleScene();
  const fs::path dir = freshDir("glb-buffer-fifo");
  makeSpecial(dir / "data.bin", Special::Fifo);
  const std::string from = R"("buffers":[{"byteLength":)" + std::to_string(g.bin.size()) + "}";
  // A GLB of a JSON chunk only, whose buffer is the external file.
  const std::string glb = [&] {
    std::string j = g.json(true);
    j = replaced(j, from, R"("buffers":[{"byteLength":)" + std::to_string(g.bin.size()) +
                              R"(,"uri":"data.bin"})");
    while (j.size() % 4) j += ' ';
    std::string out = "glTF";
    auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(uint32_t(12 + 8 + j.size()));
    u32(uint32_t(j.size()));
    u32(0x4E4F534A);
    return out + j;
  }();
  const fs::path scene = dir / "scene.glb";
  std::ofstream(scene, std::ios::binary) << glb;
  expectRefused(scene.string(), "buffer 'data.bin' is ", Special::Fifo);
}

TEST(GltfSpecialFiles, RegularExternalFilesStillLoad) {
  const TestGltf g = oneTriangleScene();
  const fs::path dir = freshDir("regular");
  std::ofstream(dir / "data.bin", std::ios::binary) << g.bin;
  std::ofstream(dir / "scene.gltf") << withExternalBuffer(g, "data.bin");
  EXPECT_EQ(loadGltf((dir / "scene.gltf").string()).meshes.size(), 1u);

  std::ofstream(dir / "texture.png", std::ios::binary)
      << encodePng(2, 2, 3, 8, std::vector<uint16_t>(12, 200));
  std::ofstream(dir / "textured.gltf") << withExternalImage("texture.png");
  const SceneDesc d = loadGltf((dir / "textured.gltf").string());
  ASSERT_EQ(d.textures.size(), 1u);
  EXPECT_EQ(d.textures[0].width, 2);

  // A symlink to a regular file is a regular file.
  fs::create_symlink(dir / "data.bin", dir / "linked.bin");
  std::ofstream(dir / "linked.gltf") << withExternalBuffer(g, "linked.bin");
  EXPECT_EQ(loadGltf((dir / "linked.gltf").string()).meshes.size(), 1u);
}

TEST(GltfSpecialFiles, ReferencedFilesResolveInTheScenesDirectoryOnly) {
  // tinygltf's own lookup falls back to the working directory; a relative URI means the scene's
  // directory, so a file that is only in the working directory is not found.
  const TestGltf g = oneTriangleScene();
  const fs::path dir = freshDir("cwd-fallback");
  const fs::path cwd = freshDir("cwd-fallback-cwd");
  std::ofstream(cwd / "only-in-cwd.bin", std::ios::binary) << g.bin;
  std::ofstream(dir / "scene.gltf") << withExternalBuffer(g, "only-in-cwd.bin");
  const fs::path previous = fs::current_path();
  fs::current_path(cwd);
  const std::string message = loadError((dir / "scene.gltf").string());
  fs::current_path(previous);
  EXPECT_NE(message.find("only-in-cwd.bin"), std::string::npos) << message;
  EXPECT_NE(message.find("not found"), std::string::npos) << message;
}

}  // namespace
}  // namespace pathlab
