// Dominant, share and cannot-sample maps from the technique pyramid's luminances.
#include "core/maps/technique_maps.h"

#include <algorithm>
#include <stdexcept>

namespace pathlab {

std::vector<float> TechniqueLuminance::image(int k) const {
  std::vector<float> sum(pixelCount(), 0.f);
  const TechniqueRange range = k > 0 ? techniquesOfLength(k, families) : techniquesUpTo(length, families);
  for (const Technique x : range) {
    if (!has(x)) continue;
    const std::vector<float>& w = weighted[x.index()];
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += w[i];
  }
  return sum;
}

DominantMap dominantMap(const TechniqueLuminance& lum, int k) {
  if (k < 0 || k > lum.length) throw std::invalid_argument("dominant map: no such length");
  DominantMap m{lum.width, lum.height, std::vector<int>(lum.pixelCount(), kDominantEmpty),
                std::vector<float>(lum.pixelCount(), 0.f)};
  const std::vector<float> image = lum.image(k);
  const TechniqueRange range = k > 0 ? techniquesOfLength(k, lum.families) : techniquesUpTo(lum.length, lum.families);
  for (size_t i = 0; i < m.technique.size(); ++i) {
    if (!(image[i] > 0.f)) continue;
    float best = -1.f, second = -1.f;
    int winner = kDominantEmpty;
    for (const Technique x : range) {
      const float v = lum.weighted[x.index()][i];
      if (v > best) {
        second = best;
        best = v;
        winner = static_cast<int>(x.index());
      } else if (v > second) {
        second = v;
      }
    }
    if (!(best > 0.f)) continue;
    m.technique[i] = second >= (1.f - kTieTolerance) * best ? kDominantTie : winner;
    m.share[i] = std::min(best / image[i], 1.f);
  }
  return m;
}

std::vector<float> shareMap(const TechniqueLuminance& lum, Technique x) {
  if (!lum.has(x)) throw std::invalid_argument("share map: technique outside the pyramid");
  const std::vector<float> image = lum.image();
  const std::vector<float>& w = lum.weighted[x.index()];
  std::vector<float> share(image.size(), -1.f);
  for (size_t i = 0; i < share.size(); ++i)
    if (image[i] > 0.f) share[i] = std::clamp(w[i] / image[i], 0.f, 1.f);
  return share;
}

std::vector<float> familyShareMap(const TechniqueLuminance& lum, TechniqueKind kind) {
  const TechniqueFamilies family = kind == TechniqueKind::Merge ? TechniqueFamilies::Merges : TechniqueFamilies::Connections;
  if (!covers(lum.families, kind)) throw std::invalid_argument("share map: the pyramid keeps no techniques of that family");
  const std::vector<float> image = lum.image();
  std::vector<double> sum(image.size(), 0.0);
  for (const Technique x : techniquesUpTo(lum.length, family)) {
    if (!lum.has(x)) continue;
    const std::vector<float>& w = lum.weighted[x.index()];
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += w[i];
  }
  std::vector<float> share(image.size(), -1.f);
  for (size_t i = 0; i < share.size(); ++i)
    if (image[i] > 0.f) share[i] = std::clamp(static_cast<float>(sum[i] / image[i]), 0.f, 1.f);
  return share;
}

CannotSampleMap cannotSampleMap(const TechniqueLuminance& lum, Technique x) {
  if (!lum.has(x) || x.index() >= lum.sampleable.size() || lum.sampleable[x.index()].empty())
    throw std::invalid_argument("cannot-sample map: the pyramid keeps no sampleable films for this technique");
  const size_t n = lum.pixelCount();
  CannotSampleMap m{lum.width, lum.height, std::vector<Reach>(n, Reach::Empty), std::vector<float>(n, -1.f),
                    std::vector<float>(n, -1.f)};
  const std::vector<float> image = lum.image(x.length());
  const std::vector<float>& reachable = lum.sampleable[x.index()];
  const std::vector<float>& w = lum.weighted[x.index()];
  for (size_t i = 0; i < n; ++i) {
    if (!(image[i] > 0.f)) continue;
    // The reachable part is a sum over a subset of the same weighted contributions as the image,
    // so it lies in [0, image] up to rounding.
    m.unreachable[i] = std::clamp(1.f - reachable[i] / image[i], 0.f, 1.f);
    m.shareOfLength[i] = std::clamp(w[i] / image[i], 0.f, 1.f);
    m.reach[i] = !(reachable[i] > 0.f)                       ? Reach::Impossible
                 : w[i] < kWeightedAwayShare * reachable[i] ? Reach::WeightedAway
                                                             : Reach::Sampled;
  }
  return m;
}

DominantMap dominantVarianceMap(const TechniqueLuminance& lum) {
  if (lum.variance.empty()) return {};
  TechniqueLuminance v;
  v.width = lum.width, v.height = lum.height, v.length = lum.length, v.families = lum.families;
  v.weighted = lum.variance;  // the variances in the estimates' place: the largest wins
  return dominantMap(v, 0);
}

}  // namespace pathlab
