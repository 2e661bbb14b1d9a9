// forEachConnection: both walks, then every prefix pair formConnection accepts.
#include "tests/support/random_connections.h"

namespace pathlab::test {

void forEachConnection(const Scene& scene, const Camera& camera, int maxLength, int samples, Pcg32 rng,
                       const std::function<void(const MisPath& path, int s, int t)>& visit) {
  CameraSubpath cp;
  LightSubpath lp;
  Counters counters;
  const float w = static_cast<float>(camera.width()), h = static_cast<float>(camera.height());
  for (int sample = 0; sample < samples; ++sample) {
    const Vec2 pRaster(rng.next1D() * w, rng.next1D() * h);
    const int nt = generateCameraSubpath(scene, camera, pRaster, rng.next2D(), rng, WalkOptions{maxLength + 1, true, scene.mediumAt(camera.position())}, cp, counters);
    const int ns = generateLightSubpath(scene, rng, WalkOptions{maxLength, true}, lp, counters);
    for (int t = 1; t <= nt; ++t)
      for (int s = 0; s <= std::max(ns, 1) && s + t - 1 <= maxLength; ++s) {
        if (s + t < 2 || (s > ns && !(s == 1 && t >= 2))) continue;  // s = 1, t >= 2 draws its own light sample
        Pcg32 connectionRng(static_cast<uint64_t>(sample), static_cast<uint64_t>(s * 64 + t));
        Connection c;
        if (!formConnection(scene, camera, lp, s, cp, t, connectionRng, c)) continue;
        visit(MisPath{lp.data(), s, cp.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs}, s, t);
      }
  }
}

}  // namespace pathlab::test
