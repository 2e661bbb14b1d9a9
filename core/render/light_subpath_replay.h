// The light subpaths a render traces, replayed one at a time without the render's films, pyramid
// or check (RenderSession allocates those): the viewer's light particles (ui/inspect/view3d.h). The same
// settings and streams (sampleStream) give exactly the subpaths the render's samples traced.
#pragma once

#include "core/bpt/bidir_tracer.h"
#include "core/camera/camera.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

#include <memory>
#include <vector>

namespace pathlab {

class LightSubpathReplay {
 public:
  // Throws std::invalid_argument for settings a RenderSession would refuse.
  LightSubpathReplay(const Scene& scene, const RenderSettings& settings);
  LightSubpathReplay(const LightSubpathReplay&) = delete;
  LightSubpathReplay& operator=(const LightSubpathReplay&) = delete;

  const RenderSettings& settings() const { return settings_; }
  // The light subpath of sample `pass` of pixel (x, y); empty for the path tracer.
  std::vector<PathVertex> subpath(int x, int y, uint64_t pass) const;

 private:
  RenderSettings settings_;
  Camera camera_;
  std::unique_ptr<BidirTracer> tracer_;  // refers to camera_
};

}  // namespace pathlab
