// The film: box-filtered accumulation in double precision of camera-sample estimates (each pixel
// owned by one thread during a pass) and, separately, of light-tracing splats (at arbitrary raster
// positions: a render session sums them per pass in a fixed order, SplatSums; a lone caller adds
// them atomically). The two are combined only at read-out.
#pragma once

#include "core/image/image.h"
#include "core/math/types.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <array>
#include <optional>
#include <span>
#include <vector>

namespace pathlab {

// The pixel (row-major index) a splat at raster position pRaster lands in; nullopt off the film.
inline std::optional<size_t> filmPixel(Vec2 pRaster, int width, int height) {
  const int x = static_cast<int>(std::floor(pRaster.x)), y = static_cast<int>(std::floor(pRaster.y));
  if (x < 0 || y < 0 || x >= width || y >= height) return std::nullopt;
  return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
}

// A splat that landed on the film: its pixel (row-major index) and value.
struct Splat {
  uint32_t pixel;
  Spectrum v;
};

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixelCount() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }

  // The film's door: returns false (and stores nothing) for NaN, Inf or negative values, which
  // the caller counts as discarded samples.
  bool addSample(int x, int y, const Spectrum& L);
  bool splat(Vec2 pRaster, const Spectrum& v);
  // Optimal MIS's corrections (core/bpt/optimal_mis.h), per camera sample, into the camera sums:
  // signed, so not through addSample's door (which refuses negative values); a non-finite one is
  // refused (false). The pixel's own thread during a pass; addCorrections once its samples are in.
  bool addCorrection(int x, int y, const Spectrum& c);
  void addCorrections(std::vector<DVec3>& perPixel);  // then zeroed
  // Adds a whole buffer of splat sums (3 floats a pixel, this film's size): SplatSums's merge.
  // Not concurrent with splat() or another merge.
  void addSplatSums(const std::vector<float>& rgb);
  // Adds splats one by one, in order (a pass's splats when SplatSums would be too large). Not
  // concurrent with splat() or another merge.
  void addSplats(std::span<const Splat> splats);

  // Called once per completed pass: how many camera samples each pixel received and how many
  // light subpaths were traced in that pass (they set the splat normalisation, camera.h).
  void finishPass(uint64_t samplesPerPixel, uint64_t lightSubpaths);
  void clear();

  uint64_t samplesPerPixel() const { return samplesPerPixel_; }
  // The camera-sample sums and the splat sums as flat arrays of doubles (3 a pixel): films that
  // rendered disjoint samples of one image combine by adding these element by element (then
  // finishPass with the other films' counts). Not concurrent with a pass.
  std::array<std::span<double>, 2> sums();
  std::array<std::span<const double>, 2> sums() const;
  uint64_t lightSubpaths() const { return lightSubpaths_; }

  // pixel = cameraSum / spp + splatSum * pixelCount / lightSubpaths.
  Image readout() const;

 private:
  int width_, height_;
  std::vector<DVec3> cameraSum_;
  std::vector<double> splatSum_;  // 3 doubles a pixel; splat() updates it with std::atomic_ref
  uint64_t samplesPerPixel_ = 0;
  uint64_t lightSubpaths_ = 0;
};

}  // namespace pathlab
