// SplatBuffer: a work item's splats, added to the pass's sums in their order.
#include "core/film/splat_buffer.h"

namespace pathlab {

void SplatBuffer::addTo(SplatSums* sums, Film& film, TechniqueFilms* pyramid) {
  if (sums) {
    sums->add(image_);
  } else {
    film.addSplats(image_);
  }
  if (pyramid) {
    for (const TechniqueSplat& x : technique_) pyramid->add(Technique{x.s, 1}, x.pRaster, x.weighted, x.unweighted);
    for (const SampleableSplat& x : sampleable_) pyramid->addSampleable(x.k, x.sampleableBy, x.pRaster, true, x.weightedLuminance);
  }
  clear();
}

void SplatBuffer::clear() {
  image_.clear();
  technique_.clear();
  sampleable_.clear();
}

}  // namespace pathlab
