// The environment light (core/lights/environment_light.h): the map's orientation, the exact
// solid-angle density of its direction sampling (chi-square against pdfDirection, for a map and
// for the constant environment), the emission disk of sampleLe, its power, and reading maps and
// colours from the command line's words (bad input: one line naming the file).
#include "core/film/image_io.h"
#include "core/lights/environment_file.h"
#include "core/lights/light.h"
#include "core/sampling/warp.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace pathlab {
namespace {

// Four chi-square tests below share a family-wise significance of 1 %.
const double kChi2Significance = test::sidakSignificance(0.01, 4);

// A 48 x 24 map with structure: a bright 3 x 2 texel "sun", a sky gradient, black ground rows
// and a black column (zero density where the radiance is zero).
EnvironmentDesc testMap(float rotationDegrees = 0.f) {
  EnvironmentDesc d;
  d.source = "test map";
  d.width = 48;
  d.height = 24;
  d.rotationDegrees = rotationDegrees;
  d.strength = 1.5f;
  d.texels.resize(static_cast<size_t>(d.width * d.height));
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) {
      Spectrum c = y < 14 ? Spectrum(0.2f + 0.05f * static_cast<float>(y), 0.4f, 1.f) : Spectrum(0.f);
      if (x == 40) c = Spectrum(0.f);
      if (x >= 10 && x < 13 && y >= 4 && y < 6) c = Spectrum(60.f, 50.f, 40.f);
      d.texels[static_cast<size_t>(y * d.width + x)] = c;
    }
  return d;
}

TEST(EnvironmentLight, MapOrientation) {
  EnvironmentDesc d = testMap();
  const EnvironmentLight env(d, Vec3(0.f), 1.f);
  // Straight ahead of a glTF camera (-z) is the map's centre, +x its right half, up its top row.
  EXPECT_NEAR(env.toMap(Vec3(0, 0, -1)).x, 0.5f, 1e-6f);
  EXPECT_NEAR(env.toMap(Vec3(0, 0, -1)).y, 0.5f, 1e-6f);
  EXPECT_NEAR(env.toMap(Vec3(1, 0, 0)).x, 0.75f, 1e-6f);
  EXPECT_NEAR(env.toMap(Vec3(0, 1, 0)).y, 0.f, 1e-6f);
  // Rotation by 90 degrees about +y (right-handed) carries the map's centre to -x.
  const EnvironmentLight turned(testMap(90.f), Vec3(0.f), 1.f);
  EXPECT_NEAR(turned.toMap(Vec3(-1, 0, 0)).x, 0.5f, 1e-5f);
  // fromMap inverts toMap.
  for (const Vec2 uv : {Vec2(0.1f, 0.2f), Vec2(0.6f, 0.7f), Vec2(0.95f, 0.5f)}) {
    const Vec2 back = turned.toMap(turned.fromMap(uv));
    EXPECT_NEAR(back.x, uv.x, 1e-5f);
    EXPECT_NEAR(back.y, uv.y, 1e-5f);
  }
  // The radiance of a texel, strength included, where its direction points.
  const Spectrum sun = env.Le(env.fromMap(Vec2(11.5f / 48.f, 5.f / 24.f)));
  EXPECT_FLOAT_EQ(sun.r, 90.f);
  EXPECT_EQ(env.Le(Vec3(0, -1, 0)), Spectrum(0.f));
}

// The density the map's sampling produces is pdfDirection, exactly: chi-square over the sphere.
TEST(EnvironmentLight, DirectionSamplingChiSquare) {
  uint64_t seed = 40;
  for (const float rotation : {0.f, 137.f}) {
    const EnvironmentLight env(testMap(rotation), Vec3(0.f), 1.f);
    const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
      const EnvironmentDirection d = env.sampleDirection(rng.next2D());
      if (!(d.pdfW > 0.f)) return std::nullopt;
      return d.w;
    };
    const auto pdf = [&](const Vec3& w) -> double { return env.pdfDirection(w); };
    const test::Chi2Result r = test::chi2SphereTest(sample, pdf, 24, 48, 300000, ++seed, kChi2Significance);
    EXPECT_TRUE(r.passed) << "rotation " << rotation << ": " << r.message;
  }
  EnvironmentDesc constant;
  constant.constant = Spectrum(2.f);
  const EnvironmentLight uniform(constant, Vec3(0.f), 1.f);
  const test::Chi2Result r = test::chi2SphereTest(
      [&](Pcg32& rng) -> std::optional<Vec3> { return uniform.sampleDirection(rng.next2D()).w; },
      [&](const Vec3& w) -> double { return uniform.pdfDirection(w); }, 16, 32, 100000, ++seed, kChi2Significance);
  EXPECT_TRUE(r.passed) << "constant: " << r.message;
}

// What sampleDirection reports is what pdfDirection says of the direction it returns; the light's
// sampleLi and pdfLe give the same densities (the MIS weights read them from both).
TEST(EnvironmentLight, SampledPdfMatchesPdfDirection) {
  const EnvironmentLight env(testMap(33.f), Vec3(1.f, 2.f, 3.f), 2.f);
  const Light light = Light::environment(&env);
  Pcg32 rng(7, 1);
  for (int i = 0; i < 2000; ++i) {
    const LightLiSample s = light.sampleLi(Vec3(0.5f), rng.next2D());
    ASSERT_GT(s.pdfW, 0.f);
    EXPECT_FALSE(s.isDelta);
    EXPECT_NEAR(s.pdfW, env.pdfDirection(s.wi), 1e-3f * s.pdfW);
    EXPECT_NEAR(light.pdfLe(Vec3(0.f), -s.wi, -s.wi).pdfDirW, s.pdfW, 1e-3f * s.pdfW);
    EXPECT_GT(luminance(s.Li), 0.f);  // never a direction of zero radiance
  }
}

// sampleLe: directions from the map (chi-square of -ray.d), origins on the disk of radius r normal
// to the direction, one radius out, uniform (pdfPosA = 1 / (pi r^2)), so every ray starts outside
// the bounding sphere and, aimed along -w, crosses it where the disk point projects.
TEST(EnvironmentLight, SampleLe) {
  const Vec3 center(1.f, -2.f, 0.5f);
  const float radius = 3.f;
  const EnvironmentLight env(testMap(-20.f), center, radius);
  const Light light = Light::environment(&env);
  Pcg32 rng(3, 9);
  for (int i = 0; i < 2000; ++i) {
    const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
    ASSERT_GT(s.pdfDirW, 0.f);
    EXPECT_FLOAT_EQ(s.pdfPosA, 1.f / (kPi * radius * radius));
    EXPECT_EQ(s.n, s.ray.d);
    const Vec3 offset = s.ray.o - center;
    EXPECT_NEAR(glm::dot(offset, -s.ray.d), radius, 1e-4f);  // one radius out along w
    const Vec3 inDisk = offset + radius * s.ray.d;
    EXPECT_LE(glm::length(inDisk), radius * (1.f + 1e-5f));
    const EmissionPdf e = light.pdfLe(s.ray.o, s.n, s.ray.d);
    EXPECT_FLOAT_EQ(e.pdfPosA, s.pdfPosA);
    EXPECT_NEAR(e.pdfDirW, s.pdfDirW, 1e-3f * s.pdfDirW);
  }
  const test::Chi2Result r = test::chi2SphereTest(
      [&](Pcg32& r2) -> std::optional<Vec3> {
        const LightLeSample s = light.sampleLe(r2.next2D(), r2.next2D());
        if (!(s.pdfDirW > 0.f)) return std::nullopt;
        return -s.ray.d;
      },
      [&](const Vec3& w) -> double { return light.pdfLe(Vec3(0.f), -w, -w).pdfDirW; }, 24, 48, 300000, 77,
      kChi2Significance);
  EXPECT_TRUE(r.passed) << r.message;
}

// Power = pi r^2 x the integral of Le over the sphere: exact for a constant (4 pi^2 r^2 L), and the
// map's texel-exact integral against a Monte Carlo estimate with uniform directions.
TEST(EnvironmentLight, PowerIsRadianceOverTheBoundingDisk) {
  EnvironmentDesc constant;
  constant.constant = Spectrum(0.5f, 1.f, 2.f);
  constant.strength = 2.f;
  const EnvironmentLight uniform(constant, Vec3(0.f), 3.f);
  EXPECT_NEAR(uniform.power().g, 4.f * kPi * kPi * 9.f * 2.f, 1e-3f);
  EXPECT_NEAR(Light::environment(&uniform).power().b, 4.f * kPi * kPi * 9.f * 4.f, 1e-2f);

  const EnvironmentLight env(testMap(10.f), Vec3(0.f), 2.f);
  Pcg32 rng(11, 2);
  test::RunningStats stats;
  for (int i = 0; i < 400000; ++i) {
    const Vec3 w = sampleUniformSphere(rng.next2D());
    stats.add(static_cast<double>(env.Le(w).r) / uniformSpherePdf());
  }
  const double expected = env.power().r / (kPi * 4.0);
  EXPECT_LT(std::abs(stats.estimate().zScore(expected)), 4.0)
      << stats.mean() << " vs " << expected << " se " << stats.standardError();
}

class EnvironmentFile : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pathlab-env-" + std::to_string(getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  static std::string errorOf(const std::string& spec) {
    try {
      readEnvironment(spec);
    } catch (const EnvironmentError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(EnvironmentFile, ReadsExrHdrAndColours) {
  Image image{4, 2, std::vector<float>(24, 0.f)};
  image.rgb[3 * 5 + 1] = 7.f;  // (1, 1), green
  writeImage(path("map.exr"), image);
  const EnvironmentDesc exr = readEnvironment(path("map.exr"));
  ASSERT_EQ(exr.width, 4);
  ASSERT_EQ(exr.height, 2);
  EXPECT_EQ(exr.texels[5], Spectrum(0.f, 7.f, 0.f));

  // Radiance RGBE, uncompressed (a width under 8 is never run-length encoded): (128, 128, 128,
  // 129) is 1.0 in every channel, (128, 0, 0, 131) is (4, 0, 0).
  {
    std::ofstream f(path("map.hdr"), std::ios::binary);
    f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n";
    const unsigned char px[8] = {128, 128, 128, 129, 128, 0, 0, 131};
    f.write(reinterpret_cast<const char*>(px), 8);
  }
  const EnvironmentDesc hdr = readEnvironment(path("map.hdr"));
  ASSERT_EQ(hdr.width, 2);
  EXPECT_NEAR(hdr.texels[0].g, 1.f, 1e-6f);
  EXPECT_NEAR(hdr.texels[1].r, 4.f, 1e-6f);

  const EnvironmentDesc c = readEnvironment("0.5, 1,2");
  EXPECT_TRUE(c.isConstant());
  EXPECT_EQ(c.constant, Spectrum(0.5f, 1.f, 2.f));
}

TEST_F(EnvironmentFile, RefusesBadInputInOneLine) {
  { std::ofstream(path("broken.exr")) << "not an exr"; }
  { std::ofstream(path("broken.hdr")) << "#?RADIANCE\nnonsense"; }
  const std::pair<std::string, std::string> cases[] = {
      {path("missing.exr"), "no such file"},
      {path("broken.exr"), "cannot read EXR"},
      {path("broken.hdr"), "cannot read the HDR image"},
      {path("map.png"), "an .exr or .hdr file or a colour"},
      {"1,2", "an .exr or .hdr file or a colour"},
      {"1,-2,3", "three finite non-negative numbers"},
  };
  for (const auto& [spec, expected] : cases) {
    const std::string message = errorOf(spec);
    EXPECT_NE(message.find(expected), std::string::npos) << spec << ": " << message;
    EXPECT_EQ(message.rfind(spec, 0), 0u) << "names the input first: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace pathlab
