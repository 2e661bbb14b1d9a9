// Image agreement by z-tests: per-region, per-channel means of a render with standard errors
// measured from its independent passes, their comparison, and the multiple-comparison threshold.
#pragma once

#include "core/render/render_session.h"
#include "tests/support/statistics.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace pathlab::test {

// Pixels grouped into regions: label[y * width + x] in [0, count), or -1 to leave a pixel out.
struct PixelLabels {
  int width = 0, height = 0, count = 0;
  std::vector<int> label;
};

// cellsX x cellsY rectangular cells covering the image (cell ry * cellsX + rx).
PixelLabels gridLabels(int width, int height, int cellsX, int cellsY);

using MaterialPredicate = std::function<bool(const Material&)>;

// `labels` without the pixels through which the camera (the scene's, as RenderSettings s frames
// it, through the lens centre) may see a surface whose material `which` selects: tested on an
// n x n grid of sub-pixel positions, then dilated by one pixel so that no edge pixel escapes.
// With hasDeltaLobe: what a pinhole camera cannot connect to (Veach 1997, sec. 10.3.5: no t = 1
// technique can sample a path whose vertex next to the camera scatters by a delta lobe).
PixelLabels withoutSeenDirectly(const Scene& scene, const RenderSettings& s, PixelLabels labels,
                                const MaterialPredicate& which, int n = 4);
// The complement's core: pixels whose every sub-pixel ray, and every neighbour's, sees such a
// surface.
PixelLabels onlySeenDirectly(const Scene& scene, const RenderSettings& s, PixelLabels labels,
                             const MaterialPredicate& which, int n = 4);

// True for a material that has a delta lobe (a smooth mirror, specular layer or glass; GGX
// alpha = roughness^2 below kDeltaAlpha). Textured roughness is not looked at.
bool hasDeltaLobe(const Material& m);
inline bool isEmissive(const Material& m) { return m.isEmissive(); }
inline bool emitterOrDelta(const Material& m) { return m.isEmissive() || hasDeltaLobe(m); }

int labelledPixels(const PixelLabels& labels);

struct RegionMeans {
  std::vector<std::array<MeanEstimate, 3>> region;  // [label][channel]
  std::array<MeanEstimate, 3> whole;                // every labelled pixel
  uint64_t discarded = 0;                           // NaN / Inf / negative samples refused
  double seconds = 0.0;                             // wall-clock time of the render
};

// Renders `passes` passes with one RenderSession. The film averages its passes (camera sums /
// spp and splats / passes both scale as 1/n), so pass p alone is p m_p - (p - 1) m_(p-1); passes
// draw from streams keyed by (seed, pixel, pass), so these are independent samples of the
// region means, and their spread is the measured standard error (no variance is assumed).
RegionMeans renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes, const PixelLabels& labels);
// The same render seen through several groupings of its pixels (one result per label set).
std::vector<RegionMeans> renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes,
                                           const std::vector<PixelLabels>& labelSets);
// Several images read from the same render after every pass (the film, technique buffers, or a
// difference of two of them: the per-pass difference of two estimates from the same samples is
// a paired sample, whose spread is the standard error of the difference itself). [image][label set]
using ImageOf = std::function<Image(const RenderSession&)>;
std::vector<std::vector<RegionMeans>> renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes,
                                                        const std::vector<PixelLabels>& labelSets,
                                                        const std::vector<ImageOf>& images);

// Two renders run in lockstep, pass by pass: the region means of a - b with the standard error
// of the per-pass differences (valid whether or not the two share random numbers; when they do,
// e.g. the path tracer at maximum lengths k and k - 1 with one seed, the shared part cancels).
RegionMeans renderPairedDifference(const Scene& scene, const RenderSettings& a, const RenderSettings& b, int passes,
                                   const PixelLabels& labels);

// a - b of two independent estimates (standard errors added in quadrature).
RegionMeans difference(const RegionMeans& a, const RegionMeans& b);
// Pixel-wise a - b (the same size).
Image imageDifference(const Image& a, const Image& b);

// Two-sided Bonferroni threshold: P(|Z| > z) = familyAlpha / comparisons for a standard normal Z,
// so that `comparisons` z-tests of unbiased estimators all pass with probability >= 1 - familyAlpha
// (whatever their correlation). familyAlpha = 1e-3 and 100 comparisons give z = 4.42.
double bonferroniZ(double familyAlpha, int comparisons);

struct Agreement {
  int comparisons = 0;
  double maxAbsZ = 0.0;
  std::string worst;  // which region and channel gave maxAbsZ, with both estimates
};

// z-test of every region and channel and of the whole image, channel by channel.
Agreement compareRegions(const RegionMeans& a, const RegionMeans& b);

// z-test of every region and channel of an estimated difference against zero.
Agreement testZero(const RegionMeans& d);

}  // namespace pathlab::test
