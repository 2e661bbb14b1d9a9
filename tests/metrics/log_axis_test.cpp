// Log axes of the plots (`pathlab converge`'s SVG and the viewer's live error plot): whole decades
// around the data, tick labels.
#include "core/metrics/log_axis.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pathlab {
namespace {

TEST(LogAxis, WholeDecadesAroundTheData) {
  const LogAxis a = LogAxis::fit(0.03, 47.0);
  EXPECT_DOUBLE_EQ(a.lo(), 0.01);
  EXPECT_DOUBLE_EQ(a.hi(), 100.0);
  EXPECT_NEAR(a.position(0.01), 0.0, 1e-12);
  EXPECT_NEAR(a.position(1.0), 0.5, 1e-12);
  EXPECT_NEAR(a.position(100.0), 1.0, 1e-12);
  // Within one decade: still a decade wide, and 2 and 5 are labelled.
  const LogAxis b = LogAxis::fit(2.0, 3.0);
  EXPECT_DOUBLE_EQ(b.lo(), 1.0);
  EXPECT_DOUBLE_EQ(b.hi(), 10.0);
  std::vector<std::string> labels;
  for (const LogTick& t : b.ticks())
    if (!t.label.empty()) labels.push_back(t.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"1", "2", "5", "10"}));
  // Exactly a power of ten stays on its decade.
  EXPECT_DOUBLE_EQ(LogAxis::fit(1e-3, 1e-1).lo(), 1e-3);
  EXPECT_DOUBLE_EQ(LogAxis::fit(1e-3, 1e-1).hi(), 1e-1);
  // Many decades: every other one labelled (the last always).
  const LogAxis c = LogAxis::fit(1e-8, 1.0);
  int labelled = 0;
  for (const LogTick& t : c.ticks()) labelled += t.major && !t.label.empty();
  EXPECT_EQ(labelled, 5);
}

TEST(LogAxis, ShortLabels) {
  EXPECT_EQ(tickLabel(0.01), "0.01");
  EXPECT_EQ(tickLabel(0.5), "0.5");
  EXPECT_EQ(tickLabel(1.0), "1");
  EXPECT_EQ(tickLabel(20.0), "20");
  EXPECT_EQ(tickLabel(1000.0), "1000");
  EXPECT_EQ(tickLabel(1e-5), "1e-5");
  EXPECT_EQ(tickLabel(2e6), "2e6");
  EXPECT_EQ(tickLabel(3.16e-4), "3e-4");
  EXPECT_EQ(tickLabel(9.9e-4), "1e-3");
}

}  // namespace
}  // namespace pathlab
