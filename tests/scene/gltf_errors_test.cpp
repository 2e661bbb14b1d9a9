// Tests of the glTF loader on malformed input (one-line SceneError "PATH: problem", never a
// crash) and on required and optional extensions it does not support.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

namespace pathlab {
namespace {

using namespace gltf_test;

// ---- extensions ------------------------------------------------------------------------------

TEST(GltfExtensions, RequiredUnsupportedIsAnErrorOptionalUnsupportedOneWarning) {
  TestGltf g;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  TestGltf required = g, optional = g, supported = g;
  required.members.push_back(R"("extensionsUsed":["KHR_draco_mesh_compression"])");
  required.members.push_back(R"("extensionsRequired":["KHR_draco_mesh_compression"])");
  EXPECT_NE(loadError(required.write("required.gltf")).find("KHR_draco_mesh_compression"),
            std::string::npos);

  // Every unsupported optional extension in one line, once per file.
  optional.members.push_back(
      R"("extensionsUsed":["KHR_materials_sheen","KHR_lights_punctual","KHR_materials_clearcoat"])");
  const SceneDesc d = loadGltf(optional.write("optional.gltf"));
  ASSERT_EQ(d.warnings.size(), 1u) << ::testing::PrintToString(d.warnings);
  EXPECT_EQ(d.warnings[0],
            "optional extensions KHR_materials_sheen, KHR_materials_clearcoat are not supported; "
            "ignored");

  supported.members.push_back(R"("extensionsUsed":["KHR_materials_ior","KHR_lights_punctual"])");
  supported.members.push_back(
      R"("extensionsRequired":["KHR_materials_ior","KHR_lights_punctual"])");
  EXPECT_TRUE(loadGltf(supported.write("supported.gltf")).warnings.empty());
}

// ---- malformed input: one-line SceneError "PATH: problem", never a crash ----------------------

// A valid one-triangle scene lit by the builder's point light; the cases below break one thing.
TestGltf validScene() {
  TestGltf g;
  // Accessors 0 indices, 1 POSITION, 2 NORMAL; bufferViews likewise (offsets 0, 8, 44).
  const int idx = g.indices(std::vector<uint16_t>{0, 1, 2});
  const int pos = g.vec3(kTriangle);
  const int nrm = g.vec3(kUp);
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(pos, idx, nrm)}, "tri")) + "}");
  return g;
}

struct BadCase {
  std::string file;
  std::string contents;
  std::string expected;  // a substring of the message
};

std::vector<BadCase> badCases() {
  std::vector<BadCase> cases;
  const std::string good = validScene().json();
  const std::string glb = validScene().glb();
  const std::string bufferJson =
      R"("buffers":[{"byteLength":)" + std::to_string(validScene().bin.size());

  cases.push_back({"empty.gltf", "", "empty file"});
  cases.push_back(
      {"not-json.gltf", std::string("\x89\x00\xfe\xffnot json\nat all", 20), "parse error"});
  cases.push_back({"truncated.gltf", good.substr(0, good.size() / 2), "parse error"});
  cases.push_back({"array.gltf", "[1, 2, 3]", "cannot load glTF"});
  // tinygltf would recurse once per level and overflow the stack.
  cases.push_back({"deep.gltf",
                   replaced(good, R"("asset":{"version":"2.0"})",
                            R"("asset":{"version":"2.0"},"extras":)" + std::string(100000, '[') +
                                std::string(100000, ']')),
                   "nested deeper than"});
  cases.push_back({"no-asset.gltf", R"({"scenes":[]})", "cannot load glTF"});
  cases.push_back({"bad-magic.glb", "glTX" + glb.substr(4), "magic"});
  cases.push_back({"short-header.glb", glb.substr(0, 8), "truncated"});
  cases.push_back({"truncated-chunk.glb", glb.substr(0, glb.size() - 8), "truncated"});
  cases.push_back({"bad-version.glb",
                   replaced(glb, std::string("glTF\x02", 5), std::string("glTF\x01", 5)),
                   "version 1"});
  {
    std::string longJson = glb;
    const uint32_t huge = 1u << 20;
    std::memcpy(&longJson[12], &huge, 4);
    cases.push_back({"json-chunk-too-long.glb", longJson, "JSON chunk"});
  }
  // Accessor 0 (POSITION) claims 4 vertices in a 36-byte bufferView.
  cases.push_back(
      {"accessor-past-end.gltf",
       replaced(good, R"("componentType":5126,"count":3)", R"("componentType":5126,"count":4)"),
       "accessor 1 (POSITION of mesh 0 'tri') reads past the end of bufferView"});
  cases.push_back(
      {"view-past-buffer.gltf",
       replaced(good, R"("byteOffset":8,"byteLength":36)", R"("byteOffset":8,"byteLength":400)"),
       "reads past the end of buffer 0"});
  cases.push_back({"short-data-uri.gltf",
                   replaced(good, bufferJson, R"("buffers":[{"byteLength":4000)"),
                   "cannot load glTF"});
  cases.push_back({"missing-accessor.gltf", replaced(good, R"("POSITION":1)", R"("POSITION":99)"),
                   "accessor 99, which does not exist"});
  cases.push_back({"vec2-positions.gltf",
                   replaced(good, R"("count":3,"type":"VEC3")", R"("count":3,"type":"VEC2")"),
                   "VEC3"});
  cases.push_back({"float-indices.gltf",
                   replaced(good, R"("componentType":5123)", R"("componentType":5122)"),
                   "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"});
  cases.push_back(
      {"sparse.gltf",
       replaced(
           good, R"("type":"VEC3","byteOffset":0})",
           R"("type":"VEC3","byteOffset":0,"sparse":{"count":1,"indices":{"bufferView":0,"componentType":5123},"values":{"bufferView":1}}})"),
       "sparse"});
  cases.push_back(
      {"missing-buffer.gltf",
       R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"no-such-buffer.bin"}]})",
       "no-such-buffer.bin"});
  {
    TestGltf g = validScene();
    g.add("images", R"({"uri":"no-such-image.png"})");
    g.add("textures", R"({"source":0})");
    g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
    addTexturedTriangle(g);
    cases.push_back({"missing-image.gltf", g.json(), "no-such-image.png"});
  }
  {
    TestGltf g = validScene();
    g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":3}}})");
    addTexturedTriangle(g);
    cases.push_back({"missing-texture.gltf", g.json(), "texture 3, which does not exist"});
  }
  {
    // An image whose bufferView lies past the end of the buffer: tinygltf 2.7 would hand stb a
    // pointer past the end.
    TestGltf g = validScene();
    g.add("bufferViews", R"({"buffer":0,"byteOffset":0,"byteLength":100000})");
    g.add("images", R"({"bufferView":3,"mimeType":"image/png"})");
    cases.push_back(
        {"image-view-past-buffer.gltf", g.json(), "image 0: bufferView 3 reads past the end"});
  }
  {
    // Zero-length GLB buffer (tinygltf 2.7 throws std::out_of_range from vector::at).
    TestGltf g = validScene();
    std::string zero = g.glb();
    zero = replaced(zero, R"("buffers":[{"byteLength":)" + std::to_string(g.bin.size()) + "}",
                    R"("buffers":[{"byteLength":0)" +
                        std::string(std::to_string(g.bin.size()).size() - 1, ' ') + "}");
    cases.push_back({"zero-buffer.glb", zero, "cannot load glTF"});
  }
  {
    TestGltf g = validScene();
    g.light = false;
    cases.push_back({"no-emitter.gltf", g.json(), "no light source"});
    // An emissive material no triangle uses, and a black light, emit nothing either.
    g.add("materials", R"({"emissiveFactor":[1,1,1]})");
    g.extensions = R"("KHR_lights_punctual":{"lights":[{"type":"point","intensity":0}]})";
    g.root(R"({"extensions":{"KHR_lights_punctual":{"light":0}}})");
    cases.push_back({"unused-emitter.gltf", g.json(), "no light source"});
  }
  {
    std::vector<Vec3> nan = kTriangle, inf = kTriangle;
    nan[1].y = std::numeric_limits<float>::quiet_NaN();
    inf[2].x = -std::numeric_limits<float>::infinity();
    for (const auto& [name, positions] :
         {std::pair{"nan-vertex.gltf", nan}, std::pair{"inf-vertex.gltf", inf}}) {
      TestGltf g;
      g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(positions))}, "broken")) + "}");
      cases.push_back({name, g.json(),
                       "mesh 0 'broken': accessor 0 (POSITION) has a non-finite vertex position"});
    }
  }
  {
    TestGltf g;
    const int idx = g.indices(std::vector<uint32_t>{0, 1, 3});
    g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle), idx)})) + "}");
    cases.push_back({"bad-index.gltf", g.json(),
                     "index 3 (accessor 0, element 2) is out of range of the vertex count 3"});
  }
  {
    TestGltf g = validScene();
    g.node(R"({"children":[2]})");
    g.node(R"({"children":[1]})");
    g.roots.push_back(1);
    cases.push_back({"cycle.gltf", g.json(), "reached twice"});
  }
  {
    TestGltf g = validScene();
    g.root(R"({"children":[42]})");
    cases.push_back({"bad-child.gltf", g.json(), "child 42 does not exist"});
    TestGltf h = validScene();
    h.root(R"({"mesh":9})");
    cases.push_back({"bad-mesh.gltf", h.json(), "mesh 9, which does not exist"});
    TestGltf c = validScene();
    c.root(R"({"camera":4})");
    cases.push_back({"bad-camera.gltf", c.json(), "camera 4, which does not exist"});
    TestGltf l = validScene();
    l.root(R"({"extensions":{"KHR_lights_punctual":{"light":6}}})");
    cases.push_back({"bad-light.gltf", l.json(), "light 6"});
    TestGltf s = validScene();
    s.members.push_back(R"("scene":5)");
    cases.push_back({"bad-scene.gltf", s.json(), "default scene 5 does not exist"});
    TestGltf m = validScene();
    m.root(R"({"mesh":)" + str(m.mesh({TestGltf::primitive(0, -1, -1, -1, 7)})) + "}");
    cases.push_back({"bad-material.gltf", m.json(), "material 7, which does not exist"});
  }
  return cases;
}

TEST(GltfErrors, EveryMalformedInputIsAOneLineSceneErrorNamingTheProblem) {
  for (const BadCase& c : badCases()) {
    SCOPED_TRACE(c.file);
    const std::string message = loadError(writeFile(c.file, c.contents));
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

TEST(GltfErrors, ReasonablyDeepExtrasStillLoad) {
  const std::string good = validScene().json();
  const std::string deep = replaced(
      good, R"("asset":{"version":"2.0"})",
      R"("asset":{"version":"2.0"},"extras":)" + std::string(500, '[') + std::string(500, ']'));
  EXPECT_EQ(loadGltf(writeFile("deep-ok.gltf", deep)).meshes.size(), 1u);
}

TEST(GltfErrors, MissingFileAndDirectory) {
  const std::string missing = (tempDir() / "does-not-exist.gltf").string();
  EXPECT_NE(loadError(missing).find("file not found"), std::string::npos);
  EXPECT_NE(loadError(tempDir().string()).find("directory"), std::string::npos);
}

TEST(GltfErrors, TruncatedAndCorruptedFilesNeverCrash) {
  // Every prefix length class and pseudo-random byte corruptions (fixed seed) of a textured
  // .gltf and a .glb: each either loads or throws SceneError, never anything else.
  TestGltf g = validScene();
  g.add("images", R"({"uri":"data:image/png;base64,)" +
                      base64(encodePng(2, 2, 3, 8, std::vector<uint16_t>(12, 200))) + "\"}");
  g.add("textures", R"({"source":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  addTexturedTriangle(g);
  const std::string inputs[] = {g.json(), g.glb()};
  uint32_t state = 12345;
  auto next = [&] { return state = state * 1103515245u + 12345u, (state >> 8); };
  int loaded = 0, failed = 0;
  for (int which = 0; which < 2; ++which) {
    const std::string& original = inputs[which];
    const std::string name = which == 0 ? "fuzz.gltf" : "fuzz.glb";
    std::vector<std::string> variants;
    for (size_t cut = 0; cut < original.size(); cut += 1 + original.size() / 150) {
      variants.push_back(original.substr(0, cut));
    }
    for (int k = 0; k < 150; ++k) {
      std::string v = original;
      for (int flips = 1 + int(next() % 4); flips > 0; --flips) v[next() % v.size()] = char(next());
      variants.push_back(v);
    }
    for (const std::string& v : variants) {
      const std::string path = writeFile(name, v);
      try {
        loadGltf(path);
        ++loaded;
      } catch (const SceneError& e) {
        const std::string msg = e.what();
        ASSERT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
        ASSERT_EQ(msg.find('\n'), std::string::npos) << msg;
        ++failed;
      }
    }
  }
  EXPECT_GT(failed, 0);
  EXPECT_GT(loaded, 0);
}

TEST(GltfErrors, DegenerateTrianglesWarnButLoad) {
  TestGltf g;
  const int idx = g.indices(std::vector<uint8_t>{0, 1, 2, 1, 1, 2});
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle), idx)}, "m")) + "}");
  const SceneDesc d = loadGltf(g.write("one-degenerate.gltf"));
  EXPECT_EQ(totalTriangles(d), 1u);
  EXPECT_TRUE(hasWarning(d, "'m': 1 zero-area triangle dropped"))
      << ::testing::PrintToString(d.warnings);
}

}  // namespace
}  // namespace pathlab
