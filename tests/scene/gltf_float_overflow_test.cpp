// Tests that scene values are checked as the 32-bit floats the renderer uses: a value finite as
// a double but infinite as a float (or a product, area or extent that overflows) is refused with
// one line naming it and saying "overflows", never rendered black nor reported as something else.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

struct OverflowCase {
  std::string file;
  std::string contents;
  std::vector<std::string> expected;  // substrings of the message
};

// One triangle with `nodeMembers` on its node and `material` (raw JSON, may be empty) as its
// material 0.
std::string triangleScene(const std::string& nodeMembers, const std::string& material = "") {
  TestGltf g;
  const int m = material.empty() ? -1 : g.add("materials", material);
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle), -1, g.vec3(kUp), -1, m)})) +
         (nodeMembers.empty() ? "" : "," + nodeMembers) + "}");
  return g.json();
}

// The builder's scene with its point light replaced by `light` (raw JSON) at `lightNode`.
std::string lightScene(const std::string& light, const std::string& lightNode = "") {
  TestGltf g;
  g.light = false;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  g.extensions = R"("KHR_lights_punctual":{"lights":[)" + light + "]}";
  g.root(R"({"extensions":{"KHR_lights_punctual":{"light":0}})" +
         (lightNode.empty() ? "" : "," + lightNode) + "}");
  return g.json();
}

std::string positionsScene(const std::vector<Vec3>& positions) {
  TestGltf g;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(positions))}, "huge")) + "}");
  return g.json();
}

std::vector<OverflowCase> overflowCases() {
  std::vector<OverflowCase> cases;
  const std::string emissive = R"("extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":)";
  cases.push_back({"emissive-strength.gltf",
                   triangleScene("", R"({"emissiveFactor":[1,1,1],)" + emissive + "1e39}}}"),
                   {"material 0", "emissiveStrength 1e+39 overflows a 32-bit float"}});
  cases.push_back({"emissive-product.gltf",
                   triangleScene("", R"({"emissiveFactor":[1e20,1,1],)" + emissive + "1e20}}}"),
                   {"material 0", "emissiveFactor x emissiveStrength (1e+20 x 1e+20) overflows"}});
  // Invalid by the extension's schema (minimum 0): refused, not taken as "no light" (issue 37).
  cases.push_back({"emissive-negative.gltf",
                   triangleScene("", R"({"emissiveFactor":[1,1,1],)" + emissive + "-1}}}"),
                   {"material 0", "emissiveStrength -1 is negative"}});
  cases.push_back({"emissive-factor.gltf", triangleScene("", R"({"emissiveFactor":[1e300,0,0]})"),
                   {"emissiveFactor 1e+300 overflows"}});
  cases.push_back({"base-color.gltf",
                   triangleScene("", R"({"pbrMetallicRoughness":{"baseColorFactor":[1e39,1,1,1]}})"),
                   {"baseColorFactor 1e+39 overflows"}});
  cases.push_back({"ior.gltf",
                   triangleScene("", R"({"extensions":{"KHR_materials_ior":{"ior":1e40}}})"),
                   {"ior 1e+40 overflows"}});
  cases.push_back({"light-intensity.gltf", lightScene(R"({"type":"point","intensity":1e39})"),
                   {"light 0", "intensity 1e+39 overflows a 32-bit float"}});
  cases.push_back({"light-color.gltf",
                   lightScene(R"({"type":"point","color":[1e39,1,1],"intensity":1})"),
                   {"light 0", "color 1e+39 overflows"}});
  cases.push_back({"light-product.gltf",
                   lightScene(R"({"type":"point","color":[1e20,1,1],"intensity":1e20})"),
                   {"color x intensity (1e+20 x 1e+20) overflows"}});
  cases.push_back({"light-power.gltf", lightScene(R"({"type":"point","intensity":1e38})"),
                   {"total emitted power", "overflows"}});
  cases.push_back({"emitter-power.gltf",
                   triangleScene(R"("scale":[1e3,1e3,1])",
                                 R"({"emissiveFactor":[1,1,1],)" + emissive + "1e34}}}"),
                   {"total emitted power", "overflows"}});
  cases.push_back({"light-translation.gltf",
                   lightScene(R"({"type":"point","intensity":1})", R"("translation":[1e39,0,0])"),
                   {"node 1", "position coordinate of light 0", "1e+39 overflows"}});
  cases.push_back({"mesh-translation.gltf", triangleScene(R"("translation":[0,1e39,0])"),
                   {"node 0", "after the node transform, vertex 0 coordinate 1e+39 overflows a 32-bit float"}});
  cases.push_back({"mesh-matrix.gltf",
                   triangleScene(R"("matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,-1e39,1])"),
                   {"node 0", "-1e+39 overflows"}});
  // Finite everywhere, but the triangle's cross product does not fit: not "zero area".
  cases.push_back({"mesh-scale.gltf", triangleScene(R"("scale":[1e20,1e20,1e20])"),
                   {"node 0", "triangle 0 (an edge of 1e+20) is too large: its area overflows"}});
  // Every coordinate fits, but the distance from the triangle to the light does not, squared.
  // (A triangle that far would collapse to a point in float, or overflow its own area first.)
  cases.push_back({"far-light.gltf",
                   lightScene(R"({"type":"point","intensity":1})", R"("translation":[1e25,0,0])"),
                   {"the scene spans 1e+25 units", "squared extent overflows"}});
  cases.push_back({"camera-translation.gltf",
                   [] {
                     TestGltf g;
                     g.add("cameras", R"({"type":"perspective","perspective":{"yfov":0.7,"znear":0.1}})");
                     g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
                     g.root(R"({"camera":0,"translation":[0,0,1e39]})");
                     return g.json();
                   }(),
                   {"camera 0", "position coordinate 1e+39 overflows"}});
  // Out of its range rather than overflowing, and named in the shortest form, not 300 digits.
  cases.push_back({"camera-yfov.gltf",
                   [] {
                     TestGltf g;
                     g.add("cameras", R"({"type":"perspective","perspective":{"yfov":1e300,"znear":0.1}})");
                     g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
                     g.root(R"({"camera":0})");
                     return g.json();
                   }(),
                   {"camera 0", "yfov 1e+300 is not in (0, pi)"}});
  cases.push_back({"positions-1e30.gltf",
                   positionsScene({{0, 0, 0}, {1e30f, 0, 0}, {0, 1e30f, 0}}),
                   {"mesh 0 'huge'", "triangle 0 (an edge of 1e+30) is too large: its area overflows"}});
  {
    // POSITION stored as doubles (componentType 5130) beyond the float range.
    TestGltf g;
    const std::vector<double> p = {0, 0, 0, 1e300, 0, 0, 0, 1, 0};
    const int view = g.view(p.data(), p.size() * sizeof(double));
    const int accessor = g.accessor(view, 5130, 3, "VEC3");
    g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(accessor)})) + "}");
    cases.push_back({"double-positions.gltf", g.json(),
                     {"accessor 0 (POSITION of mesh 0)", "element 1 component 0, 1e+300, overflows"}});
  }
  return cases;
}

TEST(GltfFloatOverflow, EveryValueThatOverflowsAFloatIsRefusedAndSaysSo) {
  for (const OverflowCase& c : overflowCases()) {
    SCOPED_TRACE(c.file);
    const std::string message = loadError(writeFile(c.file, c.contents));
    for (const std::string& e : c.expected) EXPECT_NE(message.find(e), std::string::npos) << message;
    EXPECT_EQ(message.find("zero-area"), std::string::npos) << message;
  }
}

TEST(GltfFloatOverflow, LargeValuesThatFitStillLoad) {
  // Big but representable: a 1e6 translation, a 1e4 scale, a strong emitter.
  const SceneDesc far = loadGltf(writeFile("far-ok.gltf", triangleScene(R"("translation":[1e6,0,0])")));
  EXPECT_EQ(totalTriangles(far), 1u);
  const SceneDesc big = loadGltf(writeFile("big-ok.gltf", triangleScene(R"("scale":[1e4,1e4,1e4])")));
  EXPECT_EQ(totalTriangles(big), 1u);
  const std::string emissive =
      R"({"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":1e20}}})";
  const SceneDesc bright = loadGltf(writeFile("bright-ok.gltf", triangleScene("", emissive)));
  EXPECT_FLOAT_EQ(bright.materials[0].emissiveStrength, 1e20f);
}

TEST(GltfFloatOverflow, TrianglesLostToFloatPrecisionAreNotCalledZeroArea) {
  // A unit triangle 1e12 from the origin: its corners round to one float. It had an area in its
  // mesh, so the warning blames the node transform, not the triangle.
  TestGltf g;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))}, "small")) +
         R"(,"translation":[1e12,0,0]})");
  const SceneDesc d = loadGltf(g.write("collapsed.gltf"));
  EXPECT_EQ(totalTriangles(d), 0u);
  EXPECT_TRUE(hasWarning(d, "1 triangle dropped: the node transform leaves them no area in 32-bit floats"))
      << ::testing::PrintToString(d.warnings);
  EXPECT_FALSE(hasWarning(d, "zero-area")) << ::testing::PrintToString(d.warnings);
}

}  // namespace
}  // namespace pathlab
