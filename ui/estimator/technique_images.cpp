// The pyramid's thumbnails and the technique map polled, toned or coloured, and uploaded.
#include "ui/estimator/technique_images.h"

#include <imgui.h>

#include <algorithm>
#include <thread>

namespace pathlab::ui {

namespace {

// Thumbnails and maps are taken at most this often: they follow the image, which the eye watches.
constexpr double kThumbnailRefreshSeconds = 0.5;

// True, and `last` set to now, when `force` or `kThumbnailRefreshSeconds` have passed since `last`.
bool due(std::chrono::steady_clock::time_point& last, bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && std::chrono::duration<double>(now - last).count() < kThumbnailRefreshSeconds) return false;
  last = now;
  return true;
}

}  // namespace

void uploadDisplayColours(Texture& texture, const Image& colours) {
  std::vector<uint8_t> rgba(4 * static_cast<size_t>(colours.width) * static_cast<size_t>(colours.height), 255);
  for (size_t i = 0; i < rgba.size() / 4; ++i)
    for (size_t c = 0; c < 3; ++c)
      rgba[4 * i + c] = static_cast<uint8_t>(std::clamp(colours.rgb[3 * i + c], 0.f, 1.f) * 255.f + 0.5f);
  texture.uploadRgba8(colours.width, colours.height, rgba.data());
}

void drawOverImage(const Texture& t, const PixelRect& image, float fbScale) {
  if (t.empty() || image.size.x <= 0 || image.size.y <= 0) return;
  const PixelRect r = fitAspect(image, static_cast<float>(t.width()) / static_cast<float>(t.height()));
  const ImVec2 p0(static_cast<float>(r.origin.x) / fbScale, static_cast<float>(r.origin.y) / fbScale);
  const ImVec2 p1(static_cast<float>(r.origin.x + r.size.x) / fbScale, static_cast<float>(r.origin.y + r.size.y) / fbScale);
  ImGui::GetBackgroundDrawList()->AddImage(t.imguiId(), p0, p1);
}

bool TechniqueImages::update(ProgressiveRenderer& renderer, const PyramidView& pyramidView, const MapView& mapView,
                             const DisplaySettings& display, bool force) {
  const bool thumbnails = pyramidView.show && updatePyramid(renderer, pyramidView, display, due(pyramid.lastPoll, force));
  const bool map = mapView.show && updateMaps(renderer, mapView, due(maps.lastPoll, force));
  return thumbnails || map;
}

bool TechniqueImages::updatePyramid(ProgressiveRenderer& renderer, const PyramidView& view,
                                    const DisplaySettings& display, bool due) {
  PyramidImages& p = pyramid;
  const bool fresh = due && renderer.pyramid(p.thumbnails, p.version);
  // Re-tone the thumbnails we have when their display changes (exposure mode, tone map, ...).
  const bool retone = !(p.toned == display) || p.tonedOwnExposure != view.ownExposure;
  if (!fresh && !retone) return false;
  p.toned = display;
  p.tonedOwnExposure = view.ownExposure;
  p.textures.resize(2 * p.thumbnails.size());
  for (size_t i = 0; i < p.thumbnails.size(); ++i) {
    const Image* images[2] = {&p.thumbnails[i].weighted, &p.thumbnails[i].unweighted};
    for (int u = 0; u < 2; ++u) {
      if (images[u]->width <= 0) continue;
      // Own exposure: every technique visible although their magnitudes differ by orders of
      // magnitude. Common exposure (the image's): the weighted shares compare directly.
      DisplaySettings d = display;
      if (view.ownExposure) d.exposure = autoExposure(*images[u]);
      const std::vector<uint8_t> rgba = toRgba8(*images[u], d);
      p.textures[2 * i + static_cast<size_t>(u)].uploadRgba8(images[u]->width, images[u]->height, rgba.data());
    }
  }
  return true;
}

bool TechniqueImages::updateMaps(ProgressiveRenderer& renderer, const MapView& view, bool due) {
  MapImages& m = maps;
  const bool fresh = due && renderer.techniqueMaps(m.lum, m.version);
  if (!fresh && m.coloured == view) return false;
  m.coloured = view;
  const Image map = mapImage(m.lum, view);
  if (map.width <= 0) {
    m.texture = Texture();
    return fresh;
  }
  uploadDisplayColours(m.texture, map);
  return true;
}

void TechniqueImages::drawMap(const MapView& mapView, const PixelRect& image, float fbScale) const {
  if (mapView.show) drawOverImage(maps.texture, image, fbScale);
}

void TechniqueImages::waitForPyramid(ProgressiveRenderer& renderer, double seconds) const {
  const auto start = std::chrono::steady_clock::now();
  std::vector<TechniqueThumbnail> probe;
  uint64_t version = pyramid.version;
  // The renderer publishes the thumbnails of a pass just after its image.
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    if (renderer.pyramid(probe, version) && !probe.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace pathlab::ui
