// The outlier finder (issue 34): the tally of a render's brightest weighted contributions is the
// brute force's (every sample of the render replayed, every technique's record in the image
// ranked by luminance), with merges too; collecting them changes no pixel of the image; the bounded
// heap keeps the largest of a stream in order.
#include "core/render/outliers.h"
#include "core/render/render_session.h"
#include "core/render/sample_inspection.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace pathlab {
namespace {

TEST(OutlierTally, KeepsTheLargestInOrder) {
  OutlierTally tally(3);
  OutlierTally::Heap& heap = tally.local();
  for (const float y : {0.5f, 4.f, 1.f, 3.f, 0.25f, 2.f}) tally.add(heap, Outlier{y, Spectrum(y), SampleId{1, 2, 0}});
  const std::vector<Outlier> top = tally.top();
  ASSERT_EQ(top.size(), 3u);
  EXPECT_EQ(top[0].luminance, 4.f);
  EXPECT_EQ(top[1].luminance, 3.f);
  EXPECT_EQ(top[2].luminance, 2.f);
}

void expectTallyIsTheBruteForce(RenderSettings s, const std::string& name) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name));
  constexpr int kTop = 12, kPasses = 3;
  RenderSession plain(scene, s);
  RenderSession session(scene, s);
  session.setOutlierCount(kTop);
  for (int i = 0; i < kPasses; ++i) plain.renderPass(), session.renderPass();
  EXPECT_EQ(plain.image().rgb, session.image().rgb) << name;  // the same image, bit for bit
  const std::vector<Outlier> top = session.outliers();
  ASSERT_EQ(top.size(), static_cast<size_t>(kTop)) << name;
  // Brute force: every sample replayed, every weighted contribution in the image.
  std::vector<Outlier> all;
  for (uint64_t pass = 0; pass < kPasses; ++pass)
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const SampleInspection in = inspectSample(session, x, y, pass);
        for (const TechniqueResult& r : in.trace.records) {
          if (r.outcome != TechniqueOutcome::Contributed || !r.inImage || !(r.imageWeight > 0.f)) continue;
          const Spectrum v = r.unweighted * r.imageWeight;
          if (luminance(v) > 0.f) all.push_back(Outlier{luminance(v), v, SampleId{x, y, pass}, r.technique(), r.pRaster});
        }
      }
  std::sort(all.begin(), all.end(), brighterOutlier);
  ASSERT_GE(all.size(), static_cast<size_t>(kTop)) << name;
  for (int i = 0; i < kTop; ++i) {
    const Outlier &a = top[static_cast<size_t>(i)], &b = all[static_cast<size_t>(i)];
    EXPECT_FLOAT_EQ(a.luminance, b.luminance) << name << " rank " << i;
    EXPECT_EQ(a.id.x, b.id.x) << name << " rank " << i;
    EXPECT_EQ(a.id.y, b.id.y) << name << " rank " << i;
    EXPECT_EQ(a.id.sample, b.id.sample) << name << " rank " << i;
    EXPECT_EQ(a.technique.index(), b.technique.index()) << name << " rank " << i;
  }
}

TEST(Outliers, TheTallyIsTheBruteForceScan) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.width = 16;
  s.height = 12;
  s.maxLength = 5;
  expectTallyIsTheBruteForce(s, "cornell-spheres.gltf");
}

TEST(Outliers, TheTallyIsTheBruteForceScanWithMerges) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse("all;m=all");
  s.width = 12;
  s.height = 12;
  s.maxLength = 4;
  s.mergeRadius = 0.05f;
  expectTallyIsTheBruteForce(s, "cornell-spheres.gltf");
}

TEST(Outliers, RefusedWithoutIndependentBidirectionalSamples) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  RenderSettings s;
  s.width = s.height = 8;
  s.integrator = IntegratorKind::Pt;
  RenderSession pt(scene, s);
  EXPECT_THROW(pt.setOutlierCount(4), std::invalid_argument);
  EXPECT_NO_THROW(pt.setOutlierCount(0));
}

}  // namespace
}  // namespace pathlab
