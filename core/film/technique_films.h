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
//
// For the variance maps (issue 34, "where the noise comes from") it may also keep, per technique,
// the second moment of its weighted estimate across passes: each pass's estimate of a pixel by the
// technique alone (its camera contribution there, or the sum of its splats there scaled as the
// film scales a pass's splats), X_p in luminance, squared and summed at the pass's end
// (finishPass). A pass's estimates of a pixel are independent across passes (each pass draws from
// streams keyed by its index), so sum X_p^2 / n - (sum X_p / n)^2 is the variance of one pass's
// estimate, the technique's share of the pixel's noise (covariances between the techniques of one
// sample aside).
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
                 TechniqueFamilies families = TechniqueFamilies::Connections, bool moments = false);

  int maxLength() const { return maxLength_; }
  bool covers(Technique x) const {
    return x.valid() && x.length() <= maxLength_ && pathlab::covers(families_, x.kind);
  }
  // Whether the films of the part each technique can sample are kept (addSampleable).
  bool keepsSampleable() const { return !sampleable_.empty(); }
  // Whether the second moments across passes are kept (finishPass, readoutVariance).
  bool keepsMoments() const { return !moments_.empty(); }
  // Bytes the buffers of a width x height pyramid up to maxLength take (checked before allocating).
  static uint64_t bytesFor(int width, int height, int maxLength, bool sampleable = false,
                           TechniqueFamilies families = TechniqueFamilies::Connections, bool moments = false);

  // t >= 2: the contribution of the camera sample through pRaster (its pixel is owned by the
  // calling thread for the pass). t = 1: a splat at pRaster, added atomically. Off-film splats
  // are ignored. Callers pass only valid (finite, non-negative) contributions.
  void add(Technique x, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted);
  // One weighted contribution of a path of length k (luminance), added to the sampleable film of
  // every technique of length k whose bit slot() is set in sampleableBy; pRaster as in add (a
  // splat when `splat`). Needs keepsSampleable().
  void addSampleable(int k, uint64_t sampleableBy, Vec2 pRaster, bool splat, double weightedLuminance);
  void clear();
  // The end of a pass (keepsMoments()): each technique's pass estimate of every pixel, X_p (camera
  // contributions as they are, splats times `splatScale`, the film's P / light subpaths of the
  // pass), squared into the moments, and the pass's estimates cleared. Not concurrent with add.
  void finishPass(double splatScale);
  // Drops the pass's estimates without adding them (a cancelled pass).
  void discardPass();
  // Every buffer as a flat array of doubles, in a fixed order: pyramids that accumulated disjoint
  // samples of one image combine by adding these element by element (Film::sums).
  std::vector<std::span<double>> sums();

  // Normalised like Film::readout: t >= 2 by camera samples per pixel, t = 1 by the number of
  // light subpaths over the pixel count.
  Image readout(Technique x, bool unweighted, uint64_t samplesPerPixel, uint64_t lightSubpaths) const;
  // The luminance of the length-k image that x can sample, per pixel (row-major), normalised
  // as readout; zeros without keepsSampleable().
  std::vector<float> readoutSampleable(Technique x, uint64_t samplesPerPixel, uint64_t lightSubpaths) const;
  // The variance of one pass's estimate of each pixel by x alone (luminance, row-major), from
  // `passes` passes: (sum X_p^2 - n mean^2) / (n - 1), the mean from the weighted film (normalised
  // as readout); zeros without keepsMoments() or with fewer than two passes.
  std::vector<float> readoutVariance(Technique x, uint64_t passes, uint64_t samplesPerPixel,
                                     uint64_t lightSubpaths) const;

 private:
  static size_t buffer(Technique x, bool unweighted) { return 2 * x.index() + (unweighted ? 1 : 0); }
  // The pixel of pRaster, or -1 off the film.
  long long pixel(Vec2 pRaster) const;
  int width_, height_, maxLength_;
  TechniqueFamilies families_;
  std::vector<std::vector<double>> buffers_;  // 2 per technique, 3 doubles a pixel (empty: family not kept)
  // keepsSampleable(): 2 per technique (camera contributions, splats), 1 double a pixel.
  std::vector<std::vector<double>> sampleable_;
  // keepsMoments(): per technique (by Technique::index()), 1 double a pixel each: this pass's
  // estimate X_p and the sum of X_p^2 over the passes.
  std::vector<std::vector<double>> passEstimate_, moments_;
};

}  // namespace pathlab
