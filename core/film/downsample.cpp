// Box downsampling by area: output pixel (i, j) averages input rows/columns [floor(i*f), floor((i+1)*f)).
#include "core/film/downsample.h"

#include <algorithm>
#include <vector>

namespace pathlab {

Image downsample(const Image& image, int maxSide) {
  const int longer = std::max(image.width, image.height);
  if (maxSide < 1 || longer <= maxSide) return image;
  const double f = static_cast<double>(longer) / static_cast<double>(maxSide);
  const int w = std::max(1, static_cast<int>(image.width / f)), h = std::max(1, static_cast<int>(image.height / f));
  Image out{w, h, std::vector<float>(3 * static_cast<size_t>(w) * static_cast<size_t>(h), 0.f)};
  auto span = [](int i, int n, int inSize) {
    const int a = static_cast<int>(static_cast<double>(i) * inSize / n);
    const int b = std::max(a + 1, static_cast<int>(static_cast<double>(i + 1) * inSize / n));
    return std::pair{a, std::min(b, inSize)};
  };
  for (int j = 0; j < h; ++j) {
    const auto [y0, y1] = span(j, h, image.height);
    for (int i = 0; i < w; ++i) {
      const auto [x0, x1] = span(i, w, image.width);
      double sum[3] = {0.0, 0.0, 0.0};
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const size_t k = 3 * (static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x));
          for (int c = 0; c < 3; ++c) sum[c] += image.rgb[k + static_cast<size_t>(c)];
        }
      const double n = static_cast<double>((y1 - y0) * (x1 - x0));
      const size_t o = 3 * (static_cast<size_t>(j) * static_cast<size_t>(w) + static_cast<size_t>(i));
      for (int c = 0; c < 3; ++c) out.rgb[o + static_cast<size_t>(c)] = static_cast<float>(sum[c] / n);
    }
  }
  return out;
}

std::vector<TechniqueThumbnail> techniqueThumbnails(int maxLength, int maxSide, const TechniqueImageSource& image,
                                                    TechniqueFamilies families) {
  std::vector<TechniqueThumbnail> thumbnails;
  thumbnails.reserve(Technique::countUpTo(maxLength, families));
  for (const Technique x : techniquesUpTo(maxLength, families))
    thumbnails.push_back({x.s, x.t, x.kind, downsample(image(x, false), maxSide), downsample(image(x, true), maxSide)});
  return thumbnails;
}

}  // namespace pathlab
