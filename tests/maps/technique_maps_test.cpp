// The technique maps (issue 13 part 3): "cannot sample" agrees with closed-form delta reasoning
// (Veach 1997, sec. 10.3.5), the dominant technique is the one the delta structure leaves, the
// shares add up to one over the rendered image, and the map functions mark ties and empty pixels.
#include "core/render/technique_luminance.h"
#include "core/maps/technique_maps.h"
#include "core/maps/map_colours.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/region_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

constexpr int kSize = 24;

RenderSettings mapSettings(int maxLength, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = kSize;
  s.maxLength = maxLength;
  s.pyramidLength = maxLength;
  s.techniqueMaps = true;
  s.integrator = IntegratorKind::Bpt;
  s.seed = seed;
  return s;
}

TechniqueLuminance render(const Scene& scene, const RenderSettings& s, int passes) {
  RenderSession session(scene, s);
  for (int i = 0; i < passes; ++i) session.renderPass();
  return techniqueLuminance(session);
}

// Pixels of a label set (label >= 0).
std::vector<size_t> pixelsOf(const test::PixelLabels& labels) {
  std::vector<size_t> out;
  for (size_t i = 0; i < labels.label.size(); ++i)
    if (labels.label[i] >= 0) out.push_back(i);
  return out;
}

// The delta scene with a point light (tests/support/bpt_scenes.h) and the pinhole camera, its
// maps up to length 3, and the pixels that see only diffuse surfaces or only the mirror or glass.
struct PointLightMaps {
  Scene scene{test::deltaScene(test::DeltaLight::Point)};
  RenderSettings settings = mapSettings(3, 31);
  TechniqueLuminance lum = render(scene, settings, 24);
  std::vector<size_t> diffuse =
      pixelsOf(test::withoutSeenDirectly(scene, settings, test::gridLabels(kSize, kSize, 1, 1), test::hasDeltaLobe));
  std::vector<size_t> delta =
      pixelsOf(test::onlySeenDirectly(scene, settings, test::gridLabels(kSize, kSize, 1, 1), test::hasDeltaLobe));
};
const PointLightMaps& pointLightMaps() {
  static const PointLightMaps maps;
  return maps;
}

// Closed-form reasoning (Veach 1997, sec. 10.3.5: a connection cannot join a delta vertex, and a
// ray cannot hit a point):
//  - s = 0 cannot hit the point light: (0, t) is Impossible wherever its length carries light;
//  - where the camera sees a diffuse surface, a length-2 path x0 x1 x2 has x1 diffuse, so (1, 2)
//    (joins x0 x1) and (2, 1) (joins x1 and the camera) both sample every such path: nothing
//    of the length-2 image is out of their reach;
//  - where the camera sees only the mirror or the glass (x2 of a length-3 path is delta), (2, 2)
//    (joins x1 x2) and (3, 1) (joins x2 and the camera) are Impossible; the light that arrives
//    has x1 diffuse (with x1 delta too no technique samples it), which (1, 3) samples: all of
//    the length-3 image is within its reach.
TEST(TechniqueMaps, CannotSampleFollowsTheDeltaVertices) {
  const PointLightMaps& p = pointLightMaps();
  const TechniqueLuminance& lum = p.lum;
  ASSERT_GT(p.diffuse.size(), 200u);
  ASSERT_GT(p.delta.size(), 12u);

  // Length 1 is dark (the light is out of view); lengths 2 and 3 are not.
  for (int t = 3; t <= 4; ++t) {
    const CannotSampleMap m = cannotSampleMap(lum, Technique{0, t});
    int impossible = 0;
    for (size_t i = 0; i < m.reach.size(); ++i) {
      EXPECT_TRUE(m.reach[i] == Reach::Empty || m.reach[i] == Reach::Impossible) << "(0," << t << ") pixel " << i;
      impossible += m.reach[i] == Reach::Impossible;
    }
    EXPECT_GT(impossible, kSize * kSize / 4) << "(0," << t << ")";
  }

  for (const Technique x : {Technique{1, 2}, Technique{2, 1}}) {
    const CannotSampleMap m = cannotSampleMap(lum, x);
    int lit = 0;
    for (size_t i : p.diffuse) {
      if (m.reach[i] == Reach::Empty) continue;
      ++lit;
      EXPECT_NE(m.reach[i], Reach::Impossible) << "(" << x.s << "," << x.t << ") pixel " << i;
      EXPECT_LT(m.unreachable[i], 1e-4f) << "(" << x.s << "," << x.t << ") pixel " << i;
    }
    EXPECT_GT(lit, 150);
  }

  const CannotSampleMap m13 = cannotSampleMap(lum, Technique{1, 3});
  const CannotSampleMap m22 = cannotSampleMap(lum, Technique{2, 2});
  const CannotSampleMap m31 = cannotSampleMap(lum, Technique{3, 1});
  int lit = 0;
  for (size_t i : p.delta) {
    if (m13.reach[i] == Reach::Empty) continue;
    ++lit;
    EXPECT_EQ(m22.reach[i], Reach::Impossible) << "pixel " << i;
    EXPECT_EQ(m31.reach[i], Reach::Impossible) << "pixel " << i;
    EXPECT_LT(m13.unreachable[i], 1e-4f) << "pixel " << i;
  }
  EXPECT_GT(lit, 8);
}

// Where the camera sees only the mirror or the glass, (1, 3) is the one technique of length 3
// left (see above): it is the dominant technique of that length with the whole share, and the
// techniques of length 3 that cannot sample there have a share of zero.
TEST(TechniqueMaps, DominantIsTheOnlyTechniqueLeft) {
  const PointLightMaps& p = pointLightMaps();
  const DominantMap m = dominantMap(p.lum, 3);
  const std::vector<float> share22 = shareMap(p.lum, Technique{2, 2});
  int lit = 0;
  for (size_t i : p.delta) {
    if (m.technique[i] == kDominantEmpty) continue;
    ++lit;
    EXPECT_EQ(m.technique[i], static_cast<int>(Technique{1, 3}.index())) << "pixel " << i;
    EXPECT_NEAR(m.share[i], 1.f, 1e-4f) << "pixel " << i;
    EXPECT_EQ(share22[i], 0.f) << "pixel " << i;
  }
  EXPECT_GT(lit, 8);
}

// Veach 1997 eq. 10.9: the weighted techniques add up to the image. The maps divide by the sum of
// the pyramid's weighted films; with the pyramid as long as the paths that sum is the rendered
// film (splats and camera samples normalised alike), and the shares add up to one.
TEST(TechniqueMaps, SharesOfTheEnabledTechniquesSumToOne) {
  static const Scene box(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  for (const char* spec : {"all", "s=0;s=1;2,2"}) {
    SCOPED_TRACE(spec);
    RenderSettings s = mapSettings(3, 33);
    s.techniques = TechniqueSet::parse(spec);
    RenderSession session(box, s);
    for (int i = 0; i < 4; ++i) session.renderPass();
    const TechniqueLuminance lum = techniqueLuminance(session);
    const Image film = session.image();
    const std::vector<float> image = lum.image();
    std::vector<double> sum(lum.pixelCount(), 0.0);
    for (const Technique x : techniquesUpTo(3)) {
      const std::vector<float> share = shareMap(lum, x);
      for (size_t i = 0; i < sum.size(); ++i) sum[i] += std::max(share[i], 0.f);
    }
    int lit = 0;
    for (size_t i = 0; i < sum.size(); ++i) {
      const float filmY = luminance(Spectrum(film.rgb[3 * i], film.rgb[3 * i + 1], film.rgb[3 * i + 2]));
      EXPECT_NEAR(image[i], filmY, 1e-4f * filmY + 1e-7f) << "pixel " << i;
      if (!(image[i] > 0.f)) continue;
      ++lit;
      EXPECT_NEAR(sum[i], 1.0, 1e-4) << "pixel " << i;
    }
    EXPECT_GT(lit, kSize * kSize / 2);
  }
}

// Hand-made luminances: a clear winner, a tie within kTieTolerance, an empty pixel; and the
// cannot-sample classes from their definitions.
TEST(TechniqueMaps, DominantMarksTiesAndEmptyPixels) {
  TechniqueLuminance lum;
  lum.width = 3;
  lum.height = 1;
  lum.length = 1;
  // (0,2) and (1,1): pixel 0 won by (1,1), pixel 1 a tie, pixel 2 dark.
  lum.weighted = {{1.f, 0.500f, 0.f}, {3.f, 0.499f, 0.f}};
  lum.sampleable = {{0.f, 0.999f, 0.f}, {4.f, 0.999f, 0.f}};
  const DominantMap m = dominantMap(lum);
  EXPECT_EQ(m.technique[0], static_cast<int>(Technique{1, 1}.index()));
  EXPECT_FLOAT_EQ(m.share[0], 0.75f);
  EXPECT_EQ(m.technique[1], kDominantTie);
  EXPECT_EQ(m.technique[2], kDominantEmpty);
  const std::vector<float> share = shareMap(lum, Technique{0, 2});
  EXPECT_FLOAT_EQ(share[0], 0.25f);
  EXPECT_EQ(share[2], -1.f);

  const CannotSampleMap c = cannotSampleMap(lum, Technique{0, 2});
  EXPECT_EQ(c.reach[0], Reach::Impossible);
  EXPECT_FLOAT_EQ(c.unreachable[0], 1.f);
  EXPECT_EQ(c.reach[1], Reach::Sampled);
  EXPECT_EQ(c.reach[2], Reach::Empty);
  lum.weighted[0][1] = 0.001f;  // (0,2) can sample it but MIS gives it a thousandth
  EXPECT_EQ(cannotSampleMap(lum, Technique{0, 2}).reach[1], Reach::WeightedAway);
}

TEST(TechniqueMaps, RefusedWithoutAPyramidOrForThePathTracer) {
  RenderSettings s = mapSettings(3, 1);
  s.pyramidLength = 0;
  EXPECT_THROW(validateSettings(s), std::invalid_argument);
  s = mapSettings(3, 1);
  s.integrator = IntegratorKind::Pt;
  EXPECT_THROW(validateSettings(s), std::invalid_argument);
  EXPECT_NO_THROW(validateSettings(mapSettings(3, 1)));
}

// The Metropolis chains' time density on its log scale: an even spread (1) mid-scale, two decades
// either side the ends, beyond them clamped, never visited black.
TEST(DensityColours, LogScaleAroundAnEvenSpread) {
  const Image c = densityColours({0.f, 1.f, 100.f, 0.01f, 1e6f, 1e-6f}, 3, 2);
  ASSERT_EQ(c.rgb.size(), 18u);
  auto at = [&](size_t p) { return Vec3(c.rgb[3 * p], c.rgb[3 * p + 1], c.rgb[3 * p + 2]); };
  EXPECT_EQ(at(0), kEmptyColour);
  EXPECT_EQ(at(1), viridis(0.5f));
  EXPECT_EQ(at(2), viridis(1.f));
  EXPECT_EQ(at(3), viridis(0.f));
  EXPECT_EQ(at(4), viridis(1.f));
  EXPECT_EQ(at(5), viridis(0.f));
}

}  // namespace
}  // namespace pathlab
