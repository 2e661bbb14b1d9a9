// Film accumulation, read-out normalisation and the guard at its door; image files round trips.
#include "core/film/film.h"
#include "core/film/image_io.h"
#include "core/film/splat_buffer.h"
#include "core/math/rng.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

namespace pathlab {
namespace {

namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) {
  const fs::path dir = fs::path(PATHLAB_TEST_TMP) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(Film, RejectsNaNInfAndNegativeAtTheDoor) {
  Film film(2, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(film.addSample(0, 0, Spectrum(1.f, 2.f, 3.f)));
  EXPECT_FALSE(film.addSample(0, 0, Spectrum(nan, 0.f, 0.f)));
  EXPECT_FALSE(film.addSample(0, 0, Spectrum(0.f, inf, 0.f)));
  EXPECT_FALSE(film.addSample(0, 0, Spectrum(0.f, 0.f, -1e-3f)));
  EXPECT_FALSE(film.splat(Vec2(1.5f, 0.5f), Spectrum(nan)));
  film.finishPass(1, 2);
  const Image img = film.readout();
  EXPECT_EQ(img.at(0, 0), Vec3(1.f, 2.f, 3.f));
  EXPECT_EQ(img.at(1, 0), Vec3(0.f));
}

// pixel = cameraSum / spp + splatSum * pixels / lightSubpaths (camera.h's normalisation).
TEST(Film, CombinesCameraSamplesAndSplatsAtReadout) {
  Film film(4, 2);
  for (int pass = 0; pass < 4; ++pass) film.addSample(3, 1, Spectrum(static_cast<float>(pass)));
  film.splat(Vec2(3.2f, 1.9f), Spectrum(2.f));
  film.splat(Vec2(-0.1f, 0.5f), Spectrum(100.f));  // off the film: no pixel measures it
  film.finishPass(4, 16);
  const Image img = film.readout();
  EXPECT_FLOAT_EQ(img.at(3, 1).x, 1.5f + 2.f * 8.f / 16.f);
  EXPECT_FLOAT_EQ(img.at(0, 0).x, 0.f);
  film.clear();
  EXPECT_EQ(film.samplesPerPixel(), 0u);
  EXPECT_FLOAT_EQ(film.readout().at(3, 1).x, 0.f);
}

// Accumulation in double precision: a million tiny additions to a large value are not lost.
TEST(Film, AccumulatesWithoutFloatDrift) {
  Film film(1, 1);
  film.addSample(0, 0, Spectrum(1e7f));
  const int n = 1000000;
  for (int i = 0; i < n; ++i) film.addSample(0, 0, Spectrum(0.25f));
  film.finishPass(static_cast<uint64_t>(n) + 1, 0);
  EXPECT_NEAR(film.readout().at(0, 0).x, (1e7 + 0.25 * n) / (n + 1), 1e-6 * 10.25);
}

Image testImage() {
  Image img{5, 3, {}};
  for (int i = 0; i < 15; ++i)
    for (int c = 0; c < 3; ++c) img.rgb.push_back(0.01f * static_cast<float>(i) * static_cast<float>(c + 1) + 1e-7f);
  return img;
}

// A work item's SplatBuffer keeps its splats in order and SplatSums adds them with the pixels
// prefetched ahead: each pixel's float sum must be bit for bit the in-order sum of its splats
// (values of very different magnitudes, so that another order or a lost splat shows), across the
// buffers of a pass, passes and the door's rejections. Without SplatSums the splats go to the
// film's doubles one by one, in the same order.
TEST(SplatBuffer, SumsEqualInOrderAdditionAcrossItemsAndPasses) {
  const int width = 7, height = 5, pixels = width * height;
  SplatBuffer buffer(width, height);
  SplatSums sums(width, height);
  Film film(width, height), direct(width, height);
  std::vector<double> expected(3 * pixels, 0.0), expectedDirect(3 * pixels, 0.0);
  Pcg32 rng(42, 7);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<float> passSum(3 * pixels, 0.f);
    for (int item = 0; item < 3; ++item) {
      for (int i = 0; i < 2000; ++i) {
        const Vec2 p(rng.next1D() * (width + 2) - 1.f, rng.next1D() * (height + 2) - 1.f);
        const float magnitude = std::ldexp(1.f, static_cast<int>(rng.next1D() * 40.f) - 20);
        const Spectrum v(magnitude * rng.next1D(), magnitude, i % 97 == 0 ? -1.f : 0.5f);
        const std::optional<size_t> pixel = filmPixel(p, width, height);
        EXPECT_EQ(buffer.splat(p, v), isValidContribution(v));
        if (!pixel || !isValidContribution(v)) continue;
        for (int c = 0; c < 3; ++c) {
          passSum[3 * *pixel + c] += v[c];
          expectedDirect[3 * *pixel + c] += v[c];
        }
      }
      SplatBuffer copy = buffer;
      buffer.addTo(&sums, film, nullptr);
      copy.addTo(nullptr, direct, nullptr);
    }
    sums.mergeInto(film);
    for (int i = 0; i < 3 * pixels; ++i) expected[i] += passSum[i];
  }
  // readout = splat sum x pixels / light subpaths: exactly the sum with as many subpaths as pixels.
  film.finishPass(1, pixels);
  direct.finishPass(1, pixels);
  const Image img = film.readout(), imgDirect = direct.readout();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = 3 * static_cast<size_t>(y * width + x) + static_cast<size_t>(c);
        EXPECT_EQ(img.at(x, y)[c], static_cast<float>(expected[i])) << x << "," << y;
        EXPECT_EQ(imgDirect.at(x, y)[c], static_cast<float>(expectedDirect[i])) << x << "," << y;
      }
  // addTo empties the buffer, and SplatSums after clear() adds nothing.
  Film empty(width, height);
  buffer.addTo(&sums, empty, nullptr);
  buffer.splat(Vec2(0.5f), Spectrum(1.f));
  buffer.addTo(&sums, empty, nullptr);
  sums.clear();
  sums.mergeInto(empty);
  empty.finishPass(1, pixels);
  EXPECT_EQ(empty.readout().at(0, 0), Vec3(0.f));
}

TEST(ImageIo, FloatFormatsRoundTripExactly) {
  const fs::path dir = scratchDir("image_io");
  const Image img = testImage();
  for (const char* name : {"a.exr", "a.pfm", "A.PFM"}) {
    const std::string path = (dir / name).string();
    writeImage(path, img);
    const Image back = readImage(path);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    EXPECT_EQ(back.rgb, img.rgb) << name;
  }
  // Written atomically: no temporary file is left beside the image.
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename().string()[0] != '.', true);
}

TEST(ImageIo, PngIsExposedClampedAndSrgbEncoded) {
  Image img{3, 1, {0.f, 0.f, 0.f, 0.5f, 0.5f, 0.5f, 7.f, 7.f, 7.f}};
  const auto bytes = toneMapSrgb8(img, 0.f);
  EXPECT_EQ(bytes[0], 0);
  EXPECT_EQ(bytes[3], 188);  // sRGB(0.5) = 0.7354
  EXPECT_EQ(bytes[6], 255);
  EXPECT_EQ(toneMapSrgb8(img, 1.f)[3], 255);  // one stop up: 0.5 -> 1
  const fs::path dir = scratchDir("png");
  writeImage((dir / "x.png").string(), img);
  EXPECT_GT(fs::file_size(dir / "x.png"), 0u);
}

TEST(ImageIo, ErrorsNameTheFile) {
  const fs::path dir = scratchDir("errors");
  const Image img = testImage();
  auto expectError = [](auto f, const std::string& needle) {
    try {
      f();
      ADD_FAILURE() << "no error for " << needle;
    } catch (const ImageError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError([&] { writeImage((dir / "x.bmp").string(), img); }, "x.bmp");
  expectError([&] { writeImage((dir / "missing" / "x.exr").string(), img); }, "x.exr");
  expectError([&] { readImage((dir / "nope.exr").string()); }, "nope.exr");
  std::ofstream(dir / "bad.pfm") << "PF\n3 3\n-1\nshort";
  expectError([&] { readImage((dir / "bad.pfm").string()); }, "bad.pfm");
}

}  // namespace
}  // namespace pathlab
