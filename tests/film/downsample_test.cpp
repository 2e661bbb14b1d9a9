// Tests of the box downsampling behind the viewer's thumbnails and of the technique pyramid's
// thumbnails built from it.
#include "core/film/downsample.h"

#include <gtest/gtest.h>

#include <vector>

namespace pathlab {
namespace {

// A width x height image whose red channel is the pixel's column, green its row, blue `value`.
Image ramp(int width, int height, float value = 0.f) {
  Image image{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t k = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
      image.rgb[k] = static_cast<float>(x);
      image.rgb[k + 1] = static_cast<float>(y);
      image.rgb[k + 2] = value;
    }
  return image;
}

TEST(Downsample, EachPixelIsTheMeanOfItsFootprint) {
  const Image small = downsample(ramp(8, 4), 4);  // factor 2: 2 x 2 footprints
  ASSERT_EQ(small.width, 4);
  ASSERT_EQ(small.height, 2);
  EXPECT_FLOAT_EQ(small.rgb[0], 0.5f);            // columns 0 and 1
  EXPECT_FLOAT_EQ(small.rgb[3 * (4 + 3)], 6.5f);  // pixel (3, 1): columns 6 and 7 ...
  EXPECT_FLOAT_EQ(small.rgb[3 * (4 + 3) + 1], 2.5f);  // ... rows 2 and 3
  const Image same = downsample(ramp(8, 4), 8);  // small enough already
  EXPECT_EQ(same.rgb, ramp(8, 4).rgb);
}

TEST(Downsample, TechniqueThumbnailsInIndexOrderWeightedThenUnweighted) {
  std::vector<std::pair<Technique, bool>> asked;
  const std::vector<TechniqueThumbnail> thumbs = techniqueThumbnails(2, 3, [&](Technique x, bool unweighted) {
    asked.emplace_back(x, unweighted);
    return ramp(12, 6, static_cast<float>(x.index()) + (unweighted ? 0.5f : 0.f));
  });
  ASSERT_EQ(thumbs.size(), 5u);  // (0,2) (1,1) (0,3) (1,2) (2,1)
  ASSERT_EQ(asked.size(), 10u);
  for (size_t i = 0; i < thumbs.size(); ++i) {
    const Technique x{thumbs[i].s, thumbs[i].t};
    EXPECT_EQ(x.index(), i);
    EXPECT_EQ(asked[2 * i], std::pair(x, false));
    EXPECT_EQ(asked[2 * i + 1], std::pair(x, true));
    EXPECT_EQ(thumbs[i].weighted.width, 3);
    EXPECT_EQ(thumbs[i].unweighted.height, 1);  // 12 x 6 to a longer side of 3
    EXPECT_FLOAT_EQ(thumbs[i].weighted.rgb[2], static_cast<float>(i));
    EXPECT_FLOAT_EQ(thumbs[i].unweighted.rgb[2], static_cast<float>(i) + 0.5f);
  }
  EXPECT_TRUE(techniqueThumbnails(0, 3, [](Technique, bool) { return ramp(2, 2); }).empty());
}

}  // namespace
}  // namespace pathlab
