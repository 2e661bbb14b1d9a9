// Tests that the image decoders are bounded by construction: a claimed size is checked against the
// file's length and kMaxImageTexels before any allocation, truncated PFM, EXR and Radiance HDR files
// (flat and run-length encoded) are refused in one line naming the file, and valid files decode.
#include "core/film/image_io.h"
#include "core/image/image_budget.h"
#include "core/image/image_read.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace pathlab {
namespace {

namespace fs = std::filesystem;

std::string decodePath(const std::string& name) {
  static const bool made = fs::create_directories(PATHLAB_TEST_TMP) || fs::is_directory(PATHLAB_TEST_TMP);
  return made ? std::string(PATHLAB_TEST_TMP) + "/image_decode_" + name : name;
}

void writeDecodeInput(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string readDecodeInput(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The one-line refusal of reading `path` (readImage, or readRadianceHdr for .hdr), "" if it loads;
// a refusal that takes more than a few seconds fails (a decoder working on a lying header).
std::string decodeRefusal(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".hdr") readRadianceHdr(path);
    else readImage(path);
  } catch (const ImageError& e) {
    message = e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3)) << path;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  if (!message.empty()) {
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "names the file first: " << message;
  }
  return message;
}

std::string pfmBytes(int w, int h, size_t floats) {
  std::string s = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
  for (size_t i = 0; i < floats; ++i) {
    const float v = float(i);
    s.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  return s;
}

TEST(ImageDecode, PfmSizesAreCheckedBeforeAllocating) {
  const std::string p = decodePath("claims.pfm");
  writeDecodeInput(p, pfmBytes(60000, 60000, 6));
  EXPECT_NE(decodeRefusal(p).find("claims 60000x60000 texels, more than the"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, pfmBytes(10000, 10000, 6));  // within the budget, but 1.2 GB of data missing
  EXPECT_NE(decodeRefusal(p).find("(truncated)"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, pfmBytes(2, 2, 11));  // one float short
  EXPECT_NE(decodeRefusal(p).find("(truncated)"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, pfmBytes(-2, 2, 12));
  EXPECT_NE(decodeRefusal(p).find("an empty image"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, pfmBytes(2, 2, 12));
  ASSERT_EQ(decodeRefusal(p), "");
  const Image img = readImage(p);
  EXPECT_EQ(img.at(0, 1), Vec3(0.f, 1.f, 2.f));  // bottom row first in the file
  EXPECT_EQ(img.at(1, 0), Vec3(9.f, 10.f, 11.f));
}

// Radiance header, then the data.
std::string hdrBytes(int w, int h, const std::string& data) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n" + data;
}

// One RLE scanline of `width` texels of colour (r, g, b, e): each component a run of 127 and a
// literal for the rest.
std::string rleScanline(int width, const unsigned char rgbe[4]) {
  std::string s = {2, 2, char(width >> 8), char(width & 0xff)};
  for (int k = 0; k < 4; ++k) {
    int left = width;
    while (left > 0) {
      const int n = std::min(left, 127);
      if (n > 2) {
        s += char(128 + n);
        s += char(rgbe[k]);
      } else {
        s += char(n);
        s.append(size_t(n), char(rgbe[k]));
      }
      left -= n;
    }
  }
  return s;
}

TEST(ImageDecode, RadianceHdrDecodesFlatAndRunLengthFiles) {
  const unsigned char two[4] = {128, 64, 32, 130};  // (128, 64, 32) / 256 * 2^(130-128) = (2, 1, 0.5)
  std::string rle;
  for (int y = 0; y < 3; ++y) rle += rleScanline(300, two);
  const std::string p = decodePath("rle.hdr");
  writeDecodeInput(p, hdrBytes(300, 3, rle));
  ASSERT_EQ(decodeRefusal(p), "");
  const Image img = readRadianceHdr(p);
  ASSERT_EQ(img.width, 300);
  ASSERT_EQ(img.height, 3);
  EXPECT_EQ(img.at(0, 0), Vec3(2.f, 1.f, 0.5f));
  EXPECT_EQ(img.at(299, 2), Vec3(2.f, 1.f, 0.5f));
  std::string flat;
  for (int i = 0; i < 4; ++i) flat.append(reinterpret_cast<const char*>(two), 4);
  writeDecodeInput(p, hdrBytes(2, 2, flat));
  ASSERT_EQ(decodeRefusal(p), "");
  EXPECT_EQ(readRadianceHdr(p).at(1, 1), Vec3(2.f, 1.f, 0.5f));
  // The bundled sky decodes to finite, positive texels.
  const Image sky = readRadianceHdr(std::string(PATHLAB_SOURCE_DIR) + "/assets/sky.hdr");
  EXPECT_EQ(sky.width, 128);
  EXPECT_GT(sky.at(0, 0).x, 0.f);
}

TEST(ImageDecode, TruncatedOrLyingRadianceHdrIsRefused) {
  const unsigned char c[4] = {100, 100, 100, 128};
  std::string rle;
  for (int y = 0; y < 64; ++y) rle += rleScanline(512, c);
  const std::string p = decodePath("bad.hdr");
  // Cut in the middle of a scanline (stb_image 2.27 loops forever on the empty runs past the end).
  writeDecodeInput(p, hdrBytes(512, 64, rle.substr(0, rle.size() - 7)));
  EXPECT_NE(decodeRefusal(p).find("truncated"), std::string::npos) << decodeRefusal(p);
  // An empty run inside a scanline.
  std::string zero = rleScanline(512, c);
  zero[4] = 0;
  writeDecodeInput(p, hdrBytes(512, 1, zero));
  EXPECT_NE(decodeRefusal(p).find("corrupt HDR run length 0"), std::string::npos) << decodeRefusal(p);
  // A run past the end of its scanline.
  std::string over = rleScanline(512, c);
  over[4] = char(128 + 127);
  over[6] = char(128 + 127);
  over[8] = char(128 + 127);
  over[10] = char(128 + 127);
  over[12] = char(128 + 127);
  writeDecodeInput(p, hdrBytes(512, 1, over));
  EXPECT_NE(decodeRefusal(p).find("corrupt HDR run length"), std::string::npos) << decodeRefusal(p);
  // A flat file a texel short (stb_image accepts it, the missing texels undefined).
  writeDecodeInput(p, hdrBytes(4, 1, std::string(12, char(100))));
  EXPECT_NE(decodeRefusal(p).find("truncated"), std::string::npos) << decodeRefusal(p);
  // A header claiming 16384 x 8192 with no pixels, and one past the budget.
  writeDecodeInput(p, hdrBytes(16384, 8192, ""));
  EXPECT_NE(decodeRefusal(p).find("claims 16384x8192 texels, which take at least"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, hdrBytes(1 << 20, 1 << 20, ""));
  EXPECT_NE(decodeRefusal(p).find("more than the"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n0000");
  EXPECT_NE(decodeRefusal(p).find("unsupported HDR FORMAT"), std::string::npos) << decodeRefusal(p);
}

// Patches the dataWindow of an EXR pathlab wrote to claim `w` x `h`.
std::string withDataWindow(std::string exr, int w, int h) {
  const size_t at = exr.find("dataWindow");
  EXPECT_NE(at, std::string::npos);
  const size_t box = at + std::strlen("dataWindow") + 1 + std::strlen("box2i") + 1 + 4;
  const int maxXY[2] = {w - 1, h - 1};
  std::memcpy(&exr[box + 8], maxXY, sizeof maxXY);
  return exr;
}

TEST(ImageDecode, ExrSizesAreCheckedAndTruncationRefused) {
  const std::string good = decodePath("good.exr");
  fs::remove(good);
  Image img{8, 4, std::vector<float>(3 * 32, 0.25f)};
  writeImage(good, img);
  ASSERT_EQ(decodeRefusal(good), "");
  EXPECT_EQ(readImage(good).at(7, 3), Vec3(0.25f));
  const std::string bytes = readDecodeInput(good);
  const std::string p = decodePath("bad.exr");
  writeDecodeInput(p, withDataWindow(bytes, 60000, 60000));
  EXPECT_NE(decodeRefusal(p).find("claims 60000x60000 texels, more than the"), std::string::npos) << decodeRefusal(p);
  writeDecodeInput(p, withDataWindow(bytes, 8000, 8000));
  EXPECT_NE(decodeRefusal(p).find("(truncated)"), std::string::npos) << decodeRefusal(p);
  for (size_t cut : {bytes.size() / 2, bytes.size() - 1, size_t(20)}) {
    writeDecodeInput(p, bytes.substr(0, cut));
    EXPECT_NE(decodeRefusal(p), "") << "cut at " << cut;
  }
}

}  // namespace
}  // namespace pathlab

namespace pathlab {
namespace {

// Inputs the image fuzzer (tests/fuzz/image_decoder_fuzz.cpp) found crashing, each named for what
// it is: refused in one line now.
TEST(ImageDecode, FuzzerFindingsAreRefused) {
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(PATHLAB_SOURCE_DIR) / "tests/image/bad")) {
    ++files;
    EXPECT_NE(decodeRefusal(entry.path().string()), "") << entry.path();
  }
  EXPECT_GE(files, 1u);
}

}  // namespace
}  // namespace pathlab
