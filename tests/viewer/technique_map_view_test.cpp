// `view --technique-map`: the map names parse to the view they say, merges included ("share:M2,3"),
// and a merge chosen where the pyramid keeps none falls back to a connection; the variance maps
// colour a technique's variance on a log scale and name the noisiest technique.
#include "ui/estimator/technique_map_view.h"

#include "core/maps/map_colours.h"

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

TEST(TechniqueMapView, VarianceMapsParseAndColourTheVariances) {
  const MapView v = parseMapView("variance:0,3");
  EXPECT_EQ(v.kind, MapKind::Variance);
  EXPECT_EQ(mapViewName(v), "variance of (0,3)");
  const MapView d = parseMapView("variance-dominant");
  EXPECT_EQ(d.kind, MapKind::VarianceDominant);
  EXPECT_THROW(parseMapView("variance:"), std::invalid_argument);
  TechniqueLuminance lum;
  lum.width = 3;
  lum.height = 1;
  lum.length = 2;
  lum.weighted.resize(Technique::countUpTo(2));
  for (const Technique x : techniquesUpTo(2)) lum.weighted[x.index()] = {1.f, 1.f, 1.f};
  EXPECT_EQ(mapImage(lum, v).width, 0);  // no variances kept: nothing to show
  lum.variance.resize(lum.weighted.size());
  for (const Technique x : techniquesUpTo(2)) lum.variance[x.index()] = {0.f, 0.f, 0.f};
  lum.variance[Technique{0, 2}.index()] = {0.f, 1e-4f, 1.f};
  lum.variance[Technique{1, 1}.index()] = {0.f, 1.f, 1e-4f};
  // Black without variance, the scale's top yellow and four decades below it dark.
  const Image c = mapImage(lum, parseMapView("variance:0,2"));
  ASSERT_EQ(c.width, 3);
  EXPECT_EQ(c.at(0, 0), Vec3(0.f));
  EXPECT_LT(glm::length(c.at(2, 0) - viridis(1.f)), 1e-4f);
  EXPECT_LT(glm::length(c.at(1, 0) - viridis(0.f)), 1e-4f);
  // The noisiest technique, pixel by pixel.
  const DominantMap m = dominantVarianceMap(lum);
  EXPECT_EQ(m.technique[0], kDominantEmpty);
  EXPECT_EQ(m.technique[1], static_cast<int>(Technique{1, 1}.index()));
  EXPECT_EQ(m.technique[2], static_cast<int>(Technique{0, 2}.index()));
  EXPECT_NEAR(m.share[2], 1.f / 1.0001f, 1e-5f);
}

}  // namespace
}  // namespace pathlab::ui
