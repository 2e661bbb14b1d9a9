// The ray log behind the own-rays ceiling benchmark (core/scene/ray_log.h): it holds exactly the
// queries the counters count, of both kinds, each as Embree received it (raw Embree answers it
// again bit for bit: the benchmark's ceiling is then of the same work), it stops when detached,
// and it does not change the image.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/ray_log.h"
#include "core/scene/ray_replay.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

namespace pathlab {
namespace {

const Scene& rayLogCornellBox() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  return scene;
}

RenderSettings smallBpt() {
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.maxLength = 6;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

// One pass of `session` with every ray query going into `log`, detached afterwards (also on a
// failed assertion's early return).
void renderLogged(const Scene& scene, RenderSession& session, RayLog& log) {
  struct Detach {
    const Scene& scene;
    ~Detach() { scene.setRayLog(nullptr); }
  } detach{scene};
  scene.setRayLog(&log);
  session.renderPass();
}

TEST(RayLog, HoldsEveryQueryTheCountersCount) {
  const Scene& scene = rayLogCornellBox();
  RenderSession session(scene, smallBpt());
  RayLog log;
  renderLogged(scene, session, log);
  const Counters& c = session.counters();
  ASSERT_GT(c.shadowRays, 0u);
  ASSERT_GT(c.rays, 0u);
  size_t shadow = 0, closest = 0;
  for (const std::vector<LoggedRay>* stream : log.streams())
    for (const LoggedRay& r : *stream) (r.occluded ? shadow : closest) += 1;
  EXPECT_EQ(shadow, c.shadowRays);
  EXPECT_EQ(closest, c.rays);
  EXPECT_EQ(log.size(), c.totalRays());
}

TEST(RayLog, StopsWhenDetached) {
  const Scene& scene = rayLogCornellBox();
  RenderSession session(scene, smallBpt());
  RayLog log;
  renderLogged(scene, session, log);
  const size_t logged = log.size();
  ASSERT_EQ(logged, session.counters().totalRays());
  session.renderPass();
  EXPECT_GT(session.counters().totalRays(), logged);
  EXPECT_EQ(log.size(), logged);
  log.clear();
  EXPECT_EQ(log.size(), 0u);
}

// Had the log taken a ray before its origin was offset, or with another tfar, some answers would
// differ (a closest hit's distance in its last bits at least).
TEST(RayLog, RawEmbreeGivesTheLoggedAnswers) {
  const Scene& scene = rayLogCornellBox();
  RenderSession session(scene, smallBpt());
  RayLog log;
  renderLogged(scene, session, log);
  size_t blocked = 0, hits = 0;
  for (const std::vector<LoggedRay>* stream : log.streams()) {
    EXPECT_EQ(replayRays(scene, stream->data(), stream->size()), 0u);
    for (const LoggedRay& r : *stream) (r.occluded ? blocked : hits) += r.tAfter < r.tfar;
  }
  EXPECT_GT(blocked, 0u);  // both kinds of answer were compared
  EXPECT_GT(hits, 0u);
}

TEST(RayLog, DoesNotChangeTheImage) {
  // One thread: with several, the light-tracing splats' float sums depend on the schedule.
  tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const Scene& scene = rayLogCornellBox();
  RenderSession plain(scene, smallBpt()), logged(scene, smallBpt());
  plain.renderPass();
  RayLog log;
  renderLogged(scene, logged, log);
  EXPECT_EQ(plain.image().rgb, logged.image().rgb);
}

}  // namespace
}  // namespace pathlab
