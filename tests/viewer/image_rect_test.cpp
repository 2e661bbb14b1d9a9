// Fitting the image into the room the panels leave (ui/display/image_rect.h): the largest rectangle of the
// camera's aspect, centred, never larger than the room.
#include "ui/display/image_rect.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab::ui {
namespace {

TEST(ImageRect, WideRoomPillarboxesCentred) {
  const PixelRect r = fitAspect({{100, 0}, {1000, 500}}, 1.f);
  EXPECT_EQ(r.size, Vec2i(500, 500));
  EXPECT_EQ(r.origin, Vec2i(100 + 250, 0));
}

TEST(ImageRect, TallRoomLetterboxesCentred) {
  // The room lecture mode leaves at 1280 x 720 (a 760-pixel panel): veach-mis is 1.5 wide.
  const PixelRect r = fitAspect({{760, 0}, {520, 720}}, 1.5f);
  EXPECT_EQ(r.size, Vec2i(520, 347));  // 346.67 rounds to 347
  EXPECT_EQ(r.origin, Vec2i(760, (720 - 347) / 2));
}

TEST(ImageRect, OddBarSplitsWithTheExtraPixelAfter) {
  const PixelRect r = fitAspect({{0, 0}, {101, 100}}, 1.f);
  EXPECT_EQ(r.origin, Vec2i(0, 0));
  EXPECT_EQ(r.size, Vec2i(100, 100));
  const PixelRect s = fitAspect({{0, 0}, {103, 100}}, 1.f);
  EXPECT_EQ(s.origin, Vec2i(1, 0));
}

TEST(ImageRect, AspectWithinOnePixelAndInsideTheRoom) {
  for (const float aspect : {0.5f, 1.f, 1.5f, 16.f / 9.f, 3.f})
    for (const Vec2i size : {Vec2i(1280, 720), Vec2i(1920, 1080), Vec2i(800, 1000), Vec2i(517, 333), Vec2i(3, 2)}) {
      const PixelRect room{{7, 11}, size};
      const PixelRect r = fitAspect(room, aspect);
      EXPECT_LE(std::abs(static_cast<float>(r.size.x) - aspect * static_cast<float>(r.size.y)), std::max(1.f, aspect))
          << aspect << " in " << size.x << "x" << size.y;
      // One side fills the room; the other fits in it; the bars on either side differ by <= 1.
      EXPECT_TRUE(r.size.x == size.x || r.size.y == size.y);
      EXPECT_GE(r.origin.x, room.origin.x);
      EXPECT_GE(r.origin.y, room.origin.y);
      EXPECT_LE(r.origin.x + r.size.x, room.origin.x + size.x);
      EXPECT_LE(r.origin.y + r.size.y, room.origin.y + size.y);
      const int left = r.origin.x - room.origin.x, right = room.origin.x + size.x - r.origin.x - r.size.x;
      const int top = r.origin.y - room.origin.y, bottom = room.origin.y + size.y - r.origin.y - r.size.y;
      EXPECT_LE(std::abs(left - right), 1);
      EXPECT_LE(std::abs(top - bottom), 1);
    }
}

TEST(ImageRect, NoAspectOrNoRoomIsTheRoom) {
  const PixelRect room{{5, 6}, {300, 200}};
  EXPECT_EQ(fitAspect(room, std::nullopt), room);
  const PixelRect empty{{5, 6}, {0, 200}};
  EXPECT_EQ(fitAspect(empty, 1.5f), empty);
}

TEST(ImageRect, ContainsIsHalfOpen) {
  const PixelRect r{{10, 20}, {30, 40}};
  EXPECT_TRUE(r.contains({10.f, 20.f}));
  EXPECT_TRUE(r.contains({39.9f, 59.9f}));
  EXPECT_FALSE(r.contains({40.f, 30.f}));
  EXPECT_FALSE(r.contains({9.9f, 30.f}));
}

}  // namespace
}  // namespace pathlab::ui
