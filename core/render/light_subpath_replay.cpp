// LightSubpathReplay: a render's light subpaths walked again one by one, for the viewer's particles.
#include "core/render/light_subpath_replay.h"

#include "core/render/render_session.h"

namespace pathlab {

LightSubpathReplay::LightSubpathReplay(const Scene& scene, const RenderSettings& settings) : settings_(settings) {
  validateSettings(settings);
  validateSettingsForCamera(settings, scene.cameraDesc());
  camera_ = Camera(settings.camera.value_or(scene.cameraDesc()), settings.width, settings.height, settings.lens);
  if (settings.integrator != IntegratorKind::Pt) tracer_ = std::make_unique<BidirTracer>(scene, camera_, bidirOptions(settings));
}

std::vector<PathVertex> LightSubpathReplay::subpath(int x, int y, uint64_t pass) const {
  std::vector<PathVertex> out;
  if (!tracer_) return out;
  Pcg32 lightRng = sampleStream(settings_, x, y, pass, RngStream::Light);
  Counters counters;
  tracer_->traceLightSubpath(lightRng, out, counters);
  return out;
}

}  // namespace pathlab
