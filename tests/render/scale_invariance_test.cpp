// Scale invariance (issue 6): the Cornell box modelled from 1e-6 to 1e5 times its size, emission
// unchanged, renders the same image under the path tracer and the bidirectional tracer. Ray
// origins are offset by floating-point error bounds proportional to the coordinates (ray.h), not
// a fixed epsilon: a fixed one shadows a micro-scale scene completely and leaks light through a
// kilometre-scale one.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/image_means.h"

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

// Whole-image mean over independent seeds, each seed's render one sample.
test::MeanEstimate imageMean(const Scene& scene, IntegratorKind integrator, int seeds) {
  RenderSettings s;
  s.width = s.height = 16;
  s.maxLength = 4;
  s.integrator = integrator;
  return test::seedMeans(scene, s, seeds, 4, 1000);
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
      const double z = test::zDifference(m, reference);
      // 10 comparisons: |z| < 4 has a family-wise false-alarm rate below 10 x 6.3e-5.
      EXPECT_LT(std::abs(z), 4.0) << integratorName(integrator) << " at scale " << scale << ": " << m.mean << " +- "
                                  << m.standardError << " vs " << reference.mean << " +- " << reference.standardError;
    }
  }
}

}  // namespace
}  // namespace pathlab
