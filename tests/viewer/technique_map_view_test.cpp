// `view --technique-map`: the map names parse to the view they say, merges included ("share:M2,3"),
// and a merge chosen where the pyramid keeps none falls back to a connection.
#include "ui/estimator/technique_map_view.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace pathlab::ui {
namespace {

TEST(TechniqueMapView, ParsesConnectionsAndMerges) {
  const MapView share = parseMapView("share:1,2");
  EXPECT_EQ(share.kind, MapKind::Share);
  EXPECT_EQ(share.technique, (Technique{1, 2}));
  const MapView merge = parseMapView("cannot:M2,3");
  EXPECT_EQ(merge.kind, MapKind::CannotSample);
  EXPECT_EQ(merge.technique, Technique::merge(2, 3));
  EXPECT_EQ(merge.length, std::max(3, Technique::merge(2, 3).length()));
  EXPECT_EQ(mapViewName(merge), "where M(2,3) cannot sample");
  EXPECT_EQ(parseMapView("dominant:4").dominantLength, 4);
  for (const char* bad : {"share:M1,3", "share:M2", "cannot:X2,2", "share:2,2x", "dominant:0"})
    EXPECT_THROW(parseMapView(bad), std::invalid_argument) << bad;
}

TEST(TechniqueMapView, AMergeWithoutMergesInThePyramidFallsBack) {
  TechniqueLuminance lum;
  lum.width = 2;
  lum.height = 1;
  lum.length = 2;
  lum.weighted.resize(Technique::countUpTo(2));
  for (const Technique x : techniquesUpTo(2)) lum.weighted[x.index()] = {1.f, 0.f};
  MapView v = parseMapView("share:M2,2");
  EXPECT_NO_THROW(mapImage(lum, v));
  EXPECT_EQ(mapImage(lum, v).width, 2);
}

}  // namespace
}  // namespace pathlab::ui
