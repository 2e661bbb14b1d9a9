// Textures are decoded by stb_image only after their header is checked (issue 37): a PNG whose
// header claims more texels than the budget or than its bytes can hold, and a Radiance HDR (which
// Debian's stb_image can loop on, and glTF does not allow; a data URI's MIME type is not checked
// against its bytes), are refused in one line.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

std::string sceneWithImage(const std::string& mime, const std::string& bytes) {
  TestGltf g;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  g.add("images", R"({"uri":"data:)" + mime + ";base64," + base64(bytes) + "\"}");
  return g.json();
}

// The PNG's IHDR width and height (big-endian, right after the 8-byte signature and the chunk's
// length and type) set to w x h; stb_image reads the header without checking its CRC.
std::string claiming(std::string png, uint32_t w, uint32_t h) {
  for (int i = 0; i < 4; ++i) {
    png[16 + size_t(i)] = char(w >> (24 - 8 * i));
    png[20 + size_t(i)] = char(h >> (24 - 8 * i));
  }
  return png;
}

TEST(GltfTextureClaims, LyingPngHeadersAndHdrTexturesAreRefused) {
  const std::string png = encodePng(2, 2, 3, 8, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
  EXPECT_NO_THROW(loadGltf(writeFile("png-ok.gltf", sceneWithImage("image/png", png))));
  const std::string huge = loadError(writeFile("png-huge.gltf", sceneWithImage("image/png", claiming(png, 20000, 10000))));
  EXPECT_NE(huge.find("image 0: the header claims 20000x10000 texels, more than the"), std::string::npos) << huge;
  const std::string lying = loadError(writeFile("png-lying.gltf", sceneWithImage("image/png", claiming(png, 8000, 8000))));
  EXPECT_NE(lying.find("can hold (truncated or corrupt)"), std::string::npos) << lying;
  const std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x00", 5);
  const std::string refused = loadError(writeFile("hdr-texture.gltf", sceneWithImage("image/png", hdr)));
  EXPECT_NE(refused.find("a Radiance HDR image, not a glTF texture"), std::string::npos) << refused;
  for (const std::string& m : {huge, lying, refused}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

}  // namespace
}  // namespace pathlab
