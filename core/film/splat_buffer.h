// One work item's light-tracing splats (t = 1) in their order of arrival, for the image and for
// the technique pyramid: a render thread records them while it renders the item, and the render
// session adds them to the pass's sums in the items' fixed order (pass_tiles.h), so that no sum
// depends on which thread rendered what or when it finished (RenderSession::renderPass).
#pragma once

#include "core/film/film.h"
#include "core/film/splat_sums.h"
#include "core/film/technique_films.h"

#include <cstdint>
#include <span>
#include <vector>

namespace pathlab {

class SplatBuffer {
 public:
  SplatBuffer(int width, int height) : width_(width), height_(height) {}

  // The same door and the same pixel as Film::splat.
  bool splat(Vec2 pRaster, const Spectrum& v) {
    if (!isValidContribution(v)) return false;
    const std::optional<size_t> pixel = filmPixel(pRaster, width_, height_);
    if (!pixel) return true;  // off the film: no pixel measures it
    image_.push_back(Splat{static_cast<uint32_t>(*pixel), v});
    return true;
  }
  // TechniqueFilms::add of technique (s, 1) and TechniqueFilms::addSampleable of a splat of a
  // path of length k, recorded for addTo.
  void splatTechnique(int s, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted) {
    technique_.push_back(TechniqueSplat{s, pRaster, weighted, unweighted});
  }
  void splatSampleable(int k, uint64_t sampleableBy, Vec2 pRaster, double weightedLuminance) {
    sampleable_.push_back(SampleableSplat{k, pRaster, sampleableBy, weightedLuminance});
  }

  // Adds the recorded splats, each kind in its order, to `sums` (or straight to `film`'s doubles
  // when null) and to `pyramid` (if any), then clears them.
  void addTo(SplatSums* sums, Film& film, TechniqueFilms* pyramid);
  void clear();  // keeps the capacity, for the next item
  // The image splats recorded so far, in their order (a Metropolis chain's, summed by its length).
  std::span<const Splat> imageSplats() const { return image_; }

 private:
  struct TechniqueSplat {
    int s;
    Vec2 pRaster;
    Spectrum weighted, unweighted;
  };
  struct SampleableSplat {
    int k;
    Vec2 pRaster;
    uint64_t sampleableBy;
    double weightedLuminance;
  };
  int width_, height_;
  std::vector<Splat> image_;
  std::vector<TechniqueSplat> technique_;
  std::vector<SampleableSplat> sampleable_;
};

}  // namespace pathlab
