// The technique maps (issue 13): per pixel, which technique (s, t) carries the image, what share
// each carries, and where a technique cannot sample at all, all derived from the technique
// pyramid's weighted films (their luminance) and the films of what each technique can sample
// (TechniqueFilms::keepsSampleable). Pure functions of those luminances; colours are elsewhere
// (map_colours.h).
#pragma once

#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// Per-pixel luminances (row-major) of every technique up to `length`, indexed by Technique::index.
// Per technique of lengths 1..length, by Technique::index() (a family not kept has empty entries):
struct TechniqueLuminance {
  int width = 0, height = 0, length = 0;
  TechniqueFamilies families = TechniqueFamilies::Connections;  // whose entries are filled
  std::vector<std::vector<float>> weighted;    // its MIS-weighted estimate
  std::vector<std::vector<float>> sampleable;  // the part of its length's image it can sample; may be empty
  // The variance of one pass's estimate by the technique alone (TechniqueFilms::readoutVariance,
  // the variance maps of issue 34); may be empty.
  std::vector<std::vector<float>> variance;
  bool has(Technique x) const { return x.index() < weighted.size() && !weighted[x.index()].empty(); }
  size_t pixelCount() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  // The image of length k (0: of every length up to `length`): the sum of the weighted films, so
  // that the shares of the techniques in it add up to one. With length = the maximum path length
  // and every technique in the pyramid it is the rendered image (tests/maps/technique_maps_test.cpp).
  std::vector<float> image(int k = 0) const;
};

// What the dominant map holds where no technique wins.
inline constexpr int kDominantEmpty = -1;  // no light: the image is zero
inline constexpr int kDominantTie = -2;    // the runner-up is within kTieTolerance of the winner
// Relative: a winner within 1 % of the runner-up is no winner (both estimates are noisy anyway).
inline constexpr float kTieTolerance = 0.01f;

struct DominantMap {
  int width = 0, height = 0;
  std::vector<int> technique;  // Technique::index of the winner, or kDominantEmpty / kDominantTie
  std::vector<float> share;    // the winner's share of the image considered (0 where empty)
};

// Per pixel, the technique whose weighted estimate is the largest part of the image: of every
// length (k = 0) or of length k only.
DominantMap dominantMap(const TechniqueLuminance& lum, int k = 0);
// Per pixel, the technique whose estimate has the most variance (lum.variance), and its share of
// the techniques' variances added (their covariances aside): where the noise comes from. Empty
// without lum.variance.
DominantMap dominantVarianceMap(const TechniqueLuminance& lum);

// A technique's weighted estimate over the image of every length, in [0, 1]; -1 where the image
// is zero. The shares of all techniques add up to one wherever the image is not zero.
std::vector<float> shareMap(const TechniqueLuminance& lum, Technique x);

// A family's weighted estimate (every merge M(s,t) up to lum.length, or every connection) over the
// image of every length, in [0, 1]; -1 where the image is zero. With merges on, the merges' share
// is where vertex merging carries the image (the caustics no connection samples).
std::vector<float> familyShareMap(const TechniqueLuminance& lum, TechniqueKind kind);

// Where technique x of length k stands at a pixel, for the "cannot sample" map.
enum class Reach : uint8_t {
  Empty,         // the length-k image is zero here: nothing to sample
  Impossible,    // light of length k arrives, but x can sample none of its paths
  WeightedAway,  // x can sample some of it, but MIS gives x less than kWeightedAwayShare of that
  Sampled,       // x carries a real part of what it can sample
};
inline constexpr float kWeightedAwayShare = 0.01f;

struct CannotSampleMap {
  int width = 0, height = 0;
  std::vector<Reach> reach;
  // The fraction of the length-k image whose paths x cannot sample (1 - sampleable / image),
  // in [0, 1]; -1 where Empty.
  std::vector<float> unreachable;
  // x's weighted estimate over the length-k image, in [0, 1]; -1 where Empty.
  std::vector<float> shareOfLength;
};

// Needs lum.sampleable (settings.techniqueMaps).
CannotSampleMap cannotSampleMap(const TechniqueLuminance& lum, Technique x);

}  // namespace pathlab
