// Image means over passes and over seeds.
#include "tests/support/image_means.h"

#include <gtest/gtest.h>


namespace pathlab::test {

MeanEstimate passMeans(const Scene& scene, const RenderSettings& settings, int passes, int channel) {
  RenderSession session(scene, settings);
  RunningStats stats;
  double previousTotal = 0.0;
  for (int pass = 1; pass <= passes; ++pass) {
    session.renderPass();
    const Image img = session.image();
    double sum = 0.0;
    for (size_t i = static_cast<size_t>(channel); i < img.rgb.size(); i += 3) sum += img.rgb[i];
    const double total = sum / static_cast<double>(img.width * img.height) * pass;
    stats.add(total - previousTotal);
    previousTotal = total;
  }
  EXPECT_EQ(session.counters().discarded(), 0u);
  return stats.estimate();
}

MeanEstimate seedMeans(const Scene& scene, RenderSettings settings, int seeds, int passes, uint64_t firstSeed) {
  RunningStats stats;
  for (int seed = 0; seed < seeds; ++seed) {
    settings.seed = firstSeed + static_cast<uint64_t>(seed);
    RenderSession session(scene, settings);
    for (int i = 0; i < passes; ++i) session.renderPass();
    EXPECT_EQ(session.counters().discarded(), 0u);
    double sum = 0.0;
    const Image img = session.image();
    for (float v : img.rgb) sum += v;
    stats.add(sum / static_cast<double>(img.rgb.size()));
  }
  return stats.estimate();
}

}  // namespace pathlab::test
