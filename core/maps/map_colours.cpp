// Map colouring: palette, viridis, hatching.
#include "core/maps/map_colours.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pathlab {

Vec3 viridis(float t) {
  t = std::clamp(t, 0.f, 1.f);
  const Vec3 c0(0.2777273272234177f, 0.005407344544966578f, 0.3340998053353061f);
  const Vec3 c1(0.1050930431085774f, 1.404613529898575f, 1.384590162594685f);
  const Vec3 c2(-0.3308618287255563f, 0.214847559468213f, 0.09509516302823659f);
  const Vec3 c3(-4.634230498983486f, -5.799100973351585f, -19.33244095627987f);
  const Vec3 c4(6.228269936347081f, 14.17993336680509f, 56.69055260068105f);
  const Vec3 c5(4.776384997670288f, -13.74514537774601f, -65.35303263337234f);
  const Vec3 c6(-5.435455855934631f, 4.645852612178535f, 26.3124352495832f);
  return c0 + t * (c1 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * c6)))));
}

Vec3 techniqueColour(Technique x) {
  static constexpr std::array<uint32_t, kTechniquePaletteSize> kKelly = {
      0xF3C300, 0x875692, 0xF38400, 0xA1CAF1, 0xBE0032, 0xC2B280, 0x848482, 0x008856, 0xE68FAC, 0x0067A5,
      0xF99379, 0x604E97, 0xF6A600, 0xB3446C, 0xDCD300, 0x882D17, 0x8DB600, 0x654522, 0xE25822, 0x2B3D26};
  // By the index within the family, so a connection's colour does not depend on whether merges
  // exist; merges start half the palette away from the connections of the same number, the
  // equiangular techniques a quarter (E(1, k) beside C(1, k) in a fog: distinct colours).
  const size_t offset = x.isMerge() ? kKelly.size() / 2 : x.isEquiangular() ? kKelly.size() / 4 + 2 : 0;
  const uint32_t c = kKelly[(x.familyIndex() + offset) % kKelly.size()];
  return Vec3(static_cast<float>(c >> 16 & 255), static_cast<float>(c >> 8 & 255), static_cast<float>(c & 255)) / 255.f;
}

Vec3 techniqueColourAt(Technique x, int /*px*/, int py) {
  const Vec3 c = techniqueColour(x);
  return x.isMerge() && onMergeStripe(py) ? c * (1.f - kMergeStripeDarkening) : c;
}

namespace {

Image blank(int width, int height) {
  return Image{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f)};
}

void put(Image& img, size_t i, const Vec3& c) {
  img.rgb[3 * i] = c.r;
  img.rgb[3 * i + 1] = c.g;
  img.rgb[3 * i + 2] = c.b;
}

}  // namespace

Image dominantColours(const DominantMap& m) {
  Image img = blank(m.width, m.height);
  for (int y = 0; y < m.height; ++y)
    for (int px = 0; px < m.width; ++px) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m.width) + static_cast<size_t>(px);
      const int x = m.technique[i];
      put(img, i, x == kDominantEmpty ? kEmptyColour
                  : x == kDominantTie ? kTieColour
                                      : techniqueColourAt(Technique::fromIndex(static_cast<size_t>(x)), px, y));
    }
  return img;
}

Image shareColours(const std::vector<float>& share, int width, int height) {
  Image img = blank(width, height);
  for (size_t i = 0; i < share.size(); ++i) put(img, i, share[i] < 0.f ? kEmptyColour : viridis(share[i]));
  return img;
}

Image cannotSampleColours(const CannotSampleMap& m) {
  Image img = blank(m.width, m.height);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(m.width) + static_cast<size_t>(x);
      if (m.reach[i] == Reach::Empty) continue;  // kEmptyColour
      const Vec3 base = viridis(m.shareOfLength[i]);
      put(img, i, onHatch(x, y) ? glm::mix(base, kHatchColour, m.unreachable[i]) : base);
    }
  return img;
}

Image displayToLinear(Image display) {
  for (float& c : display.rgb) {
    c = std::clamp(c, 0.f, 1.f);
    c = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  return display;
}

Image densityColours(const std::vector<float>& density, int width, int height) {
  Image out{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f)};
  const size_t n = std::min(density.size(), static_cast<size_t>(width) * static_cast<size_t>(height));
  for (size_t p = 0; p < n; ++p) {
    const float d = density[p];
    const Vec3 c = d > 0.f ? viridis((std::log10(d) + kDensityDecades) / (2.f * kDensityDecades)) : kEmptyColour;
    for (int i = 0; i < 3; ++i) out.rgb[3 * p + static_cast<size_t>(i)] = c[i];
  }
  return out;
}

Image varianceColours(const std::vector<float>& variance, int width, int height, float largest) {
  Image out{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f)};
  const size_t n = std::min(variance.size(), static_cast<size_t>(width) * static_cast<size_t>(height));
  for (size_t p = 0; p < n; ++p) {
    const float v = variance[p];
    const Vec3 c = v > 0.f && largest > 0.f ? viridis(1.f + std::log10(v / largest) / kVarianceDecades) : kEmptyColour;
    for (int i = 0; i < 3; ++i) out.rgb[3 * p + static_cast<size_t>(i)] = c[i];
  }
  return out;
}

float varianceScaleTop(const TechniqueLuminance& lum) {
  std::vector<float> all;
  for (const std::vector<float>& v : lum.variance)
    for (const float x : v)
      if (x > 0.f) all.push_back(x);
  if (all.empty()) return 0.f;
  const auto top = all.begin() + static_cast<std::ptrdiff_t>(0.999 * static_cast<double>(all.size() - 1));
  std::nth_element(all.begin(), top, all.end());
  return *top;
}

}  // namespace pathlab
