// TechniqueLuminance from a RenderSession.
#include "core/render/technique_luminance.h"

namespace pathlab {

TechniqueLuminance techniqueLuminance(const RenderSession& session, int length) {
  TechniqueLuminance lum;
  if (!session.hasPyramid()) return lum;
  const RenderSettings& s = session.settings();
  lum.width = s.width;
  lum.height = s.height;
  lum.length = length > 0 && length < s.pyramidLength ? length : s.pyramidLength;
  lum.families = session.pyramidFamilies();
  lum.weighted.resize(Technique::countUpTo(lum.length));
  if (s.techniqueMaps) lum.sampleable.resize(lum.weighted.size());
  if (s.varianceMaps) lum.variance.resize(lum.weighted.size());
  for (const Technique x : techniquesUpTo(lum.length, lum.families)) {
    const Image img = session.techniqueImage(x, false);
    std::vector<float> y(lum.pixelCount());
    for (size_t i = 0; i < y.size(); ++i) y[i] = luminance(Spectrum(img.rgb[3 * i], img.rgb[3 * i + 1], img.rgb[3 * i + 2]));
    lum.weighted[x.index()] = std::move(y);
    if (s.techniqueMaps) lum.sampleable[x.index()] = session.sampleableLuminance(x);
    if (s.varianceMaps) lum.variance[x.index()] = session.techniqueVariance(x);
  }
  return lum;
}

}  // namespace pathlab
