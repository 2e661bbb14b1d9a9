// The rows of the viewer's per-technique table as plain logic (no ImGui): for each walk and each
// technique (s, t) that was tried, its rays, its share of all rays and of the timed work, and its
// connections' outcome, from one generation's Counters.
#pragma once

#include "core/metrics/counters.h"

#include <string>
#include <vector>

namespace pathlab::ui {

struct TechniqueRow {
  std::string name;  // "(s,t)", "camera walks", "light walks", "k>12"
  int s = -1, t = -1;  // -1 for the walks and the shared bucket
  int order = 0;       // position in techniqueRows: the Name column sorts by it
  uint64_t tried = 0, rays = 0, blocked = 0, contributed = 0, discarded = 0;
  double raysPerSecond = 0.0;
  double rayShare = 0.0;   // of every ray of the generation
  double timeShare = 0.0;  // of the timed walks and connections (0 while timing was off)
  double nanosecondsPerTry = 0.0;  // over the timed samples only
};

enum class TechniqueColumn { Name, Tried, Rays, RaysPerSecond, RayShare, TimeShare, TimePerTry, Contributed, Blocked };

// Walks first (bidirectional counters only), then every technique tried up to maxLength in the
// order of the grid. seconds: the render time the counters were gathered in.
std::vector<TechniqueRow> techniqueRows(const Counters& counters, int maxLength, double seconds);
// Sorted by a column; ties and Name keep the order of techniqueRows.
void sortRows(std::vector<TechniqueRow>& rows, TechniqueColumn column, bool descending);

}  // namespace pathlab::ui
