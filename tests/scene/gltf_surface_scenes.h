// Small glTF scenes for the alpha and normal-map tests (gltf_alpha_test.cpp,
// gltf_normal_map_test.cpp, gltf_surface_agreement_test.cpp): quads with uvs, a camera looking
// down, textures written as embedded PNGs.
#pragma once

#include "tests/scene/gltf_test_builder.h"

namespace pathlab::gltf_test {

// A quad centred at `c` spanned by half-axes `u` and `v` (normal u x v), uv (0,0)..(uvScale,
// uvScale) with u along `u` and v along `v`, material `material`; instanced by a root node.
inline void addQuad(TestGltf& g, Vec3 c, Vec3 u, Vec3 v, int material, float uvScale = 1.f) {
  const std::vector<Vec3> p = {c - u - v, c + u - v, c + u + v, c - u + v};
  const Vec3 n = glm::normalize(glm::cross(u, v));
  const std::vector<Vec3> normals(4, n);
  const std::vector<Vec2> uv = {{0, 0}, {uvScale, 0}, {uvScale, uvScale}, {0, uvScale}};
  const std::vector<uint16_t> idx = {0, 1, 2, 0, 2, 3};
  g.root(R"({"mesh":)" +
         str(g.mesh({TestGltf::primitive(g.vec3(p), g.indices(idx), g.vec3(normals), g.vec2(uv),
                                         material)})) +
         "}");
}

// An embedded PNG image, its texture (sampler `sampler`, -1 none); returns the texture index.
inline int addImageTexture(TestGltf& g, int w, int h, int channels,
                           const std::vector<uint16_t>& samples, int sampler = -1) {
  const std::string png = encodePng(w, h, channels, 8, samples);
  const int image = g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  return g.add("textures", R"({"source":)" + str(image) +
                               (sampler >= 0 ? R"(,"sampler":)" + str(sampler) : "") + "}");
}

// A perspective camera at height `height` above the origin looking straight down (-y), its up
// vector -z; and a point light of `intensity` at `light` (the builder's own light is turned off).
inline void addCameraAndLight(TestGltf& g, float height, Vec3 light, float intensity) {
  g.light = false;
  g.add("cameras", R"({"type":"perspective","perspective":{"yfov":1.0,"znear":0.01}})");
  g.root(R"({"camera":0,"translation":[0,)" + std::to_string(height) +
         R"(,0],"rotation":[-0.70710678,0,0,0.70710678]})");
  g.extensions = R"("KHR_lights_punctual":{"lights":[{"type":"point","intensity":)" +
                 std::to_string(intensity) + "}]}";
  g.root(R"({"translation":[)" + std::to_string(light.x) + "," + std::to_string(light.y) + "," +
         std::to_string(light.z) + R"(],"extensions":{"KHR_lights_punctual":{"light":0}}})");
}

}  // namespace pathlab::gltf_test
