// The technique pyramid (Veach 1997, fig. 10.3; Tungsten's ImagePyramid): for every technique
// (s, t) up to a length, one buffer of its MIS-weighted contributions and one of its unweighted
// ones, from the same samples as the main film. The weighted buffers of the enabled techniques
// sum to the full image; each unweighted buffer is an unbiased estimate of all paths of length
// s + t - 1 that (s, t) can sample. The two are accumulated side by side, never one recovered
// from the other by dividing by the weight.
#pragma once

#include "core/film/film.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

class TechniqueFilms {
 public:
  TechniqueFilms(int width, int height, int maxLength);

  int maxLength() const { return maxLength_; }
  bool covers(int s, int t) const { return Technique{s, t}.valid() && s + t - 1 <= maxLength_; }
  // Bytes the buffers of a width x height pyramid up to maxLength take (checked before allocating).
  static uint64_t bytesFor(int width, int height, int maxLength);

  // t >= 2: the contribution of the camera sample through pRaster (its pixel is owned by the
  // calling thread for the pass). t = 1: a splat at pRaster, added atomically. Off-film splats
  // are ignored. Callers pass only valid (finite, non-negative) contributions.
  void add(int s, int t, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted);
  void clear();

  // Normalised like Film::readout: t >= 2 by camera samples per pixel, t = 1 by the number of
  // light subpaths over the pixel count.
  Image readout(int s, int t, bool unweighted, uint64_t samplesPerPixel, uint64_t lightSubpaths) const;

 private:
  size_t buffer(int s, int t, bool unweighted) const;
  int width_, height_, maxLength_;
  std::vector<std::vector<double>> buffers_;  // 2 per technique, 3 doubles a pixel
};

}  // namespace pathlab
