// The technique maps with vertex merging (issue 32): the dominant, share and cannot-sample maps
// cover the merges M(s,t) beside the connections. The shares over C and M add up to one per
// pixel and length, merges carry a caustic, and a path that only a merge can sample (every vertex
// a connection could join is next to a delta vertex) is within the merge's reach and nobody
// else's (Veach 1997, sec. 10.3.5; Georgiev et al. 2012, sec. 4).
#include "core/maps/technique_maps.h"
#include "core/render/technique_luminance.h"
#include "core/sampling/technique_label.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/region_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace pathlab {
namespace {

constexpr int kMergeMapSize = 32;

RenderSettings vcmMapSettings(int maxLength, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = kMergeMapSize;
  s.maxLength = maxLength;
  s.pyramidLength = maxLength;
  s.techniqueMaps = true;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse("all;m=all");  // --integrator vcm
  s.mergeRadius = 0.02f;
  s.seed = seed;
  return s;
}

const Scene& cornellSpheres() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  return scene;
}

// The Cornell box with a mirror and a glass sphere under VCM, lengths up to 4, its luminances and
// its rendered film's.
struct SpheresVcmMaps {
  RenderSettings settings = vcmMapSettings(4, 41);
  TechniqueLuminance lum;
  std::vector<float> film;
  SpheresVcmMaps() {
    RenderSession session(cornellSpheres(), settings);
    for (int i = 0; i < 16; ++i) session.renderPass();
    lum = techniqueLuminance(session);
    const Image img = session.image();
    film.resize(lum.pixelCount());
    for (size_t i = 0; i < film.size(); ++i)
      film[i] = luminance(Spectrum(img.rgb[3 * i], img.rgb[3 * i + 1], img.rgb[3 * i + 2]));
  }
};
const SpheresVcmMaps& spheresVcmMaps() {
  static const SpheresVcmMaps maps;
  return maps;
}

// Veach 1997 eq. 10.9 over both families: the weighted connections and merges add up to the image,
// so the maps' image (the pyramid's sum) is the film, the shares of every C and M add up to one
// (as do the two families' shares, familyShareMap),
// and per length the shares of its C and M in its own image (the cannot-sample map's) too. And
// each technique's own contributions are paths it can sample: its weighted film never exceeds the
// part of its length it can reach, which never exceeds its length's image.
TEST(TechniqueMapsWithMerges, SharesOverConnectionsAndMergesSumToOne) {
  const SpheresVcmMaps& p = spheresVcmMaps();
  const TechniqueLuminance& lum = p.lum;
  ASSERT_EQ(lum.families, TechniqueFamilies::Connections | TechniqueFamilies::Merges);
  const std::vector<float> image = lum.image();
  std::vector<double> sum(lum.pixelCount(), 0.0);
  for (const Technique x : techniquesUpTo(lum.length, lum.families)) {
    const std::vector<float> share = shareMap(lum, x);
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += std::max(share[i], 0.f);
  }
  const std::vector<float> merges = familyShareMap(lum, TechniqueKind::Merge);
  const std::vector<float> connections = familyShareMap(lum, TechniqueKind::Connection);
  int lit = 0;
  for (size_t i = 0; i < sum.size(); ++i) {
    EXPECT_NEAR(image[i], p.film[i], 1e-4f * p.film[i] + 1e-7f) << "pixel " << i;
    if (!(image[i] > 0.f)) continue;
    ++lit;
    EXPECT_NEAR(sum[i], 1.0, 1e-4) << "pixel " << i;
    EXPECT_NEAR(merges[i] + connections[i], 1.f, 1e-4f) << "pixel " << i;
  }
  EXPECT_GT(lit, kMergeMapSize * kMergeMapSize / 2);

  for (int k = 2; k <= lum.length; ++k) {
    const std::vector<float> imageK = lum.image(k);
    std::vector<double> sumK(lum.pixelCount(), 0.0);
    for (const Technique x : techniquesOfLength(k, lum.families)) {
      const CannotSampleMap m = cannotSampleMap(lum, x);
      const std::vector<float>& w = lum.weighted[x.index()];
      const std::vector<float>& reach = lum.sampleable[x.index()];
      for (size_t i = 0; i < sumK.size(); ++i) {
        sumK[i] += std::max(m.shareOfLength[i], 0.f);
        EXPECT_LE(w[i], reach[i] * (1.f + 1e-4f) + 1e-9f) << techniqueLabel(x) << " pixel " << i;
        EXPECT_LE(reach[i], imageK[i] * (1.f + 1e-4f) + 1e-9f) << techniqueLabel(x) << " pixel " << i;
      }
    }
    for (size_t i = 0; i < sumK.size(); ++i) {
      if (!(imageK[i] > 0.f)) continue;
      EXPECT_NEAR(sumK[i], 1.0, 1e-4) << "length " << k << " pixel " << i;
    }
  }
}

// The caustic below the glass sphere (light -> glass -> glass -> floor -> camera, length 4): next-
// event estimation (1,4) cannot sample it (its edge x0 x1 ends on the glass), so it is where the
// length-4 image is mostly out of (1,4)'s reach. There the merge at the floor, M(4,2), carries a
// real part of it.
TEST(TechniqueMapsWithMerges, MergesCarryTheCaustic) {
  const SpheresVcmMaps& p = spheresVcmMaps();
  const TechniqueLuminance& lum = p.lum;
  const CannotSampleMap nee = cannotSampleMap(p.lum, Technique{1, 4});
  const std::vector<float> image4 = lum.image(4);
  double caustic = 0.0, merged = 0.0;
  int pixels = 0, merging = 0;
  for (size_t i = 0; i < image4.size(); ++i) {
    if (nee.reach[i] == Reach::Empty || nee.unreachable[i] < 0.5f) continue;
    ++pixels;
    caustic += image4[i];
    double m = 0.0;
    for (const Technique x : techniquesOfLength(4, TechniqueFamilies::Merges)) m += lum.weighted[x.index()][i];
    merged += m;
    merging += m > 0.0;
  }
  std::cout << pixels << " caustic pixels, " << merging << " with merges, merges' share " << merged / caustic << "\n";
  ASSERT_GT(pixels, 4);
  EXPECT_GT(merging, pixels / 4);
  EXPECT_GT(merged / caustic, 0.01);  // 0.036 with this seed (1024 light subpaths a pass)
}

// The delta scene with a point light (bpt_scenes.h), where the camera sees only the mirror or
// the glass: x3 of a length-4 path x0 .. x4 scatters by a delta lobe, so the connections (3,2)
// and (4,1) cannot sample it, nor can (0,5) hit the point light. The light that arrives has
//  - x1 diffuse: (1,4) joins x0 x1, and M(2,4) merges at x1 (also M(3,3) when x2 is diffuse);
//  - x1 delta (the mirror) and x2 diffuse: no connection can, only the merge at x2, M(3,3).
// With merges on, that second kind is in the image and within M(3,3)'s reach: the cannot-sample
// map hatches it for every connection but not for M(3,3); and every path of the length-4 image
// there is within the reach of (1,4) or M(3,3) (x1 diffuse or delta; both when x1 and x2 are
// diffuse), while M(2,4) reaches exactly (1,4)'s.
TEST(TechniqueMapsWithMerges, OnlyAMergeSamplesLightBetweenDeltaVertices) {
  static const Scene scene(test::deltaScene(test::DeltaLight::Point));
  RenderSettings s = vcmMapSettings(4, 43);
  s.mergeRadius = 0.03f;
  RenderSession session(scene, s);
  for (int i = 0; i < 32; ++i) session.renderPass();
  const TechniqueLuminance lum = techniqueLuminance(session);
  const test::PixelLabels seenDelta =
      test::onlySeenDirectly(scene, s, test::gridLabels(kMergeMapSize, kMergeMapSize, 1, 1), test::hasDeltaLobe);

  const std::vector<float> image4 = lum.image(4);
  const std::vector<float>& reach14 = lum.sampleable[Technique{1, 4}.index()];
  const std::vector<float>& reach24 = lum.sampleable[Technique::merge(2, 4).index()];
  const std::vector<float>& reach33 = lum.sampleable[Technique::merge(3, 3).index()];
  const CannotSampleMap m14 = cannotSampleMap(lum, Technique{1, 4});
  const CannotSampleMap m33 = cannotSampleMap(lum, Technique::merge(3, 3));
  int lit = 0, mergeOnly = 0;
  for (size_t i = 0; i < image4.size(); ++i) {
    if (seenDelta.label[i] < 0 || !(image4[i] > 0.f)) continue;
    ++lit;
    for (const Technique x : {Technique{0, 5}, Technique{3, 2}, Technique{4, 1}})
      EXPECT_EQ(cannotSampleMap(lum, x).reach[i], Reach::Impossible) << techniqueLabel(x) << " pixel " << i;
    EXPECT_GE((reach14[i] + reach33[i]) * (1.f + 1e-4f), image4[i]) << "pixel " << i;
    EXPECT_NEAR(reach24[i], reach14[i], 1e-4f * image4[i]) << "pixel " << i;
    if (m14.unreachable[i] > 0.5f) {
      ++mergeOnly;
      EXPECT_NE(m33.reach[i], Reach::Impossible) << "pixel " << i;
      EXPECT_LT(m33.unreachable[i], 0.5f) << "pixel " << i;
    }
  }
  std::cout << lit << " lit pixels seeing only delta surfaces, " << mergeOnly << " mostly merge-only\n";
  EXPECT_GT(lit, 8);
  EXPECT_GT(mergeOnly, 2);
}

}  // namespace
}  // namespace pathlab
