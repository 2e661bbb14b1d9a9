// Scale invariance (issue 6): the Cornell box modelled from 1e-6 to 1e5 times its size, emission
// unchanged, renders the same image under the path tracer and the bidirectional tracer. Ray
// origins are offset by floating-point error bounds proportional to the coordinates (ray.h), not
// a fixed epsilon: a fixed one shadows a micro-scale scene completely and leaks light through a
// kilometre-scale one.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

SceneDesc scaledCornellBox(float scale) {
  SceneDesc desc = loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf");
  for (TriangleMesh& m : desc.meshes)
    for (Vec3& p : m.positions) p *= scale;
  desc.camera->cameraToWorld[3] = Vec4(Vec3(desc.camera->cameraToWorld[3]) * scale, 1.f);
  return desc;
}

// Mean of the image over independent seeds, each seed's whole-image mean one sample (channel sum).
test::MeanEstimate imageMean(const Scene& scene, IntegratorKind integrator, int seeds) {
  test::RunningStats stats;
  for (int seed = 0; seed < seeds; ++seed) {
    RenderSettings s;
    s.width = s.height = 16;
    s.maxLength = 4;
    s.seed = 1000 + static_cast<uint64_t>(seed);
    s.integrator = integrator;
    RenderSession session(scene, s);
    for (int i = 0; i < 4; ++i) session.renderPass();
    EXPECT_EQ(session.counters().discarded(), 0u);
    double sum = 0.0;
    for (float v : session.image().rgb) sum += v;
    stats.add(sum / static_cast<double>(session.image().rgb.size()));
  }
  return stats.estimate();
}

TEST(ScaleInvariance, CornellBoxFromMicrometresToKilometres) {
  constexpr int kSeeds = 12;
  for (IntegratorKind integrator : {IntegratorKind::Pt, IntegratorKind::Bpt}) {
    const Scene unit(scaledCornellBox(1.f));
    const test::MeanEstimate reference = imageMean(unit, integrator, kSeeds);
    ASSERT_GT(reference.mean, 0.0);
    for (float scale : {1e-6f, 1e-4f, 1e-2f, 1e2f, 1e5f}) {
      const Scene scene(scaledCornellBox(scale));
      const test::MeanEstimate m = imageMean(scene, integrator, kSeeds);
      const double z = (m.mean - reference.mean) /
                       std::sqrt(m.standardError * m.standardError + reference.standardError * reference.standardError);
      // 10 comparisons: |z| < 4 has a family-wise false-alarm rate below 10 x 6.3e-5.
      EXPECT_LT(std::abs(z), 4.0) << integratorName(integrator) << " at scale " << scale << ": " << m.mean << " +- "
                                  << m.standardError << " vs " << reference.mean << " +- " << reference.standardError;
    }
  }
}

}  // namespace
}  // namespace pathlab
