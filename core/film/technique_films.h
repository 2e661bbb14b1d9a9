// The technique pyramid (Veach 1997, fig. 10.3; Tungsten's ImagePyramid): for every technique
// (s, t) up to a length, of the families it is made for (connections; merges when asked), one buffer of its MIS-weighted contributions and one of its unweighted
// ones, from the same samples as the main film. The weighted buffers of the enabled techniques
// sum to the full image; each unweighted buffer is an unbiased estimate of all paths of length
// s + t - 1 that (s, t) can sample. The two are accumulated side by side, never one recovered
// from the other by dividing by the weight.
//
// For the technique maps (technique_maps.h) a pyramid may also keep, per technique (s, t) of
// length k, the luminance of the MIS-weighted contributions of every technique of length k whose
// path (s, t) could have sampled (TechniqueResult::sampleableBy, a bit per Technique::slot()): the part of the length-k image
// that (s, t) can reach at all. Where the length-k image is bright but that part is zero, (s, t)
// cannot sample there (a delta vertex at its connection edge, a point light for s = 0); where it
// is non-zero but (s, t)'s weighted film is not, the technique was weighted away. Luminance only
// (the maps are luminance ratios), and only when asked: two doubles a pixel and technique, one for
// camera contributions and one for splats, which are normalised differently.
#pragma once

#include "core/film/film.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <span>
#include <vector>

namespace pathlab {

class TechniqueFilms {
 public:
  TechniqueFilms(int width, int height, int maxLength, bool sampleable = false,
                 TechniqueFamilies families = TechniqueFamilies::Connections);

  int maxLength() const { return maxLength_; }
  bool covers(Technique x) const {
    return x.valid() && x.length() <= maxLength_ && pathlab::covers(families_, x.kind);
  }
  // Whether the films of the part each technique can sample are kept (addSampleable).
  bool keepsSampleable() const { return !sampleable_.empty(); }
  // Bytes the buffers of a width x height pyramid up to maxLength take (checked before allocating).
  static uint64_t bytesFor(int width, int height, int maxLength, bool sampleable = false,
                           TechniqueFamilies families = TechniqueFamilies::Connections);

  // t >= 2: the contribution of the camera sample through pRaster (its pixel is owned by the
  // calling thread for the pass). t = 1: a splat at pRaster, added atomically. Off-film splats
  // are ignored. Callers pass only valid (finite, non-negative) contributions.
  void add(Technique x, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted);
  // One weighted contribution of a path of length k (luminance), added to the sampleable film of
  // every technique of length k whose bit slot() is set in sampleableBy; pRaster as in add (a
  // splat when `splat`). Needs keepsSampleable().
  void addSampleable(int k, uint64_t sampleableBy, Vec2 pRaster, bool splat, double weightedLuminance);
  void clear();
  // Every buffer as a flat array of doubles, in a fixed order: pyramids that accumulated disjoint
  // samples of one image combine by adding these element by element (Film::sums).
  std::vector<std::span<double>> sums();

  // Normalised like Film::readout: t >= 2 by camera samples per pixel, t = 1 by the number of
  // light subpaths over the pixel count.
  Image readout(Technique x, bool unweighted, uint64_t samplesPerPixel, uint64_t lightSubpaths) const;
  // The luminance of the length-k image that x can sample, per pixel (row-major), normalised
  // as readout; zeros without keepsSampleable().
  std::vector<float> readoutSampleable(Technique x, uint64_t samplesPerPixel, uint64_t lightSubpaths) const;

 private:
  static size_t buffer(Technique x, bool unweighted) { return 2 * x.index() + (unweighted ? 1 : 0); }
  // The pixel of pRaster, or -1 off the film.
  long long pixel(Vec2 pRaster) const;
  int width_, height_, maxLength_;
  TechniqueFamilies families_;
  std::vector<std::vector<double>> buffers_;  // 2 per technique, 3 doubles a pixel (empty: family not kept)
  // keepsSampleable(): 2 per technique (camera contributions, splats), 1 double a pixel.
  std::vector<std::vector<double>> sampleable_;
};

}  // namespace pathlab
