// Colours of the technique maps, shared by `render --technique-maps` and the viewer: a fixed
// categorical palette by technique, viridis for shares, hatching for "cannot sample". Every
// function returns display colours (sRGB values in [0, 1]), not radiance.
#pragma once

#include "core/film/film.h"
#include "core/maps/technique_maps.h"
#include "core/math/types.h"

namespace pathlab {

// Viridis (perceptually uniform, colour-blind safe; van der Walt and Smith 2015), as a degree-6
// polynomial fit (Matt Zucker 2020); t clamped to [0,1]. Also the viewer's error view.
Vec3 viridis(float t);

// Kelly's colours of maximum contrast (Kelly 1965, less white and black) by Technique::index:
// every technique up to length 5 has its own; longer ones repeat them (the legends name them).
Vec3 techniqueColour(Technique x);
inline constexpr int kTechniquePaletteSize = 20;
inline const Vec3 kTieColour{1.f, 1.f, 1.f};
inline const Vec3 kEmptyColour{0.f, 0.f, 0.f};
inline const Vec3 kHatchColour{0.8f, 0.8f, 0.8f};

// Whether pixel (x, y) lies on a stripe of the hatching (diagonal, 8-pixel period).
inline bool onHatch(int x, int y) { return ((x + y) / 4) % 2 == 0; }

// A merge M(s,t) is told from a connection by pattern, not by colour alone: the palette repeats
// past length 5 and a merge's colour is some connection's. Its pixels in the dominant map (and
// its legend swatch) are crossed by dark horizontal lines, one row in three, unlike the
// cannot-sample map's diagonal hatching.
inline bool onMergeStripe(int y) { return y % 3 == 0; }
inline constexpr float kMergeStripeDarkening = 0.55f;
// Technique x's colour at pixel (x, y) of a map: techniqueColour, striped for a merge.
Vec3 techniqueColourAt(Technique x, int px, int py);

// width x height display images of the maps.
Image dominantColours(const DominantMap& m);
Image shareColours(const std::vector<float>& share, int width, int height);  // viridis; black where -1
// Viridis of the share of the length's image, hatched in proportion to the fraction the technique
// cannot sample (fully hatched: impossible; dark and unhatched: weighted away); black where empty.
Image cannotSampleColours(const CannotSampleMap& m);

// A Metropolis render's chain time density (MltSummary::density: 1 is an even spread) on a log
// scale: viridis from kDensityDecades decades below one (dark blue) to as many above (yellow),
// black where the chains never went.
inline constexpr float kDensityDecades = 2.f;
Image densityColours(const std::vector<float>& density, int width, int height);

// The variance maps (issue 34): a technique's variance per pixel on a log scale relative to
// `largest` (one for the whole mosaic, so that the techniques compare): viridis from
// kVarianceDecades decades below it (dark blue) to it and above (yellow), black where it is zero.
inline constexpr float kVarianceDecades = 4.f;
Image varianceColours(const std::vector<float>& variance, int width, int height, float largest);
// The top of the variance maps' scale: the 99.9th percentile of every technique's non-zero
// variances in lum.variance, not the largest (a firefly's pixel would push every other into the
// darkest decade); 0 without any.
float varianceScaleTop(const TechniqueLuminance& lum);

// The linear image whose PNG (writeImage: clamp, sRGB encode) shows these display colours.
Image displayToLinear(Image display);

}  // namespace pathlab
