// The per-technique counter table of a render, built once for both front ends: `pathlab render
// --stats` prints it as text, the viewer's convergence panel draws the same rows and columns with
// ImGui (sortable). Rows: the camera and light walks, then each technique (s, t) that was tried,
// in index order (techniques longer than kCountedLength share one row).
#pragma once

#include "core/counters/counters.h"

#include <span>
#include <string>
#include <vector>

namespace pathlab {

struct TechniqueRow {
  std::string name;    // "camera walks", "light walks", "merge pass", "merge searches", "(s,t)", "M(s,t)", "k>12"
  bool walk = false;   // a walk: tried counts subpaths, and it has no connection outcomes
  int s = -1, t = -1;  // -1 for the walks and the shared row
  TechniqueKind kind = TechniqueKind::Connection;
  int order = 0;       // position in techniqueRows: the Name column sorts by it
  uint64_t tried = 0, zero = 0, blocked = 0, contributed = 0, discarded = 0, rays = 0;
  double raysPerSecond = 0.0;
  double rayShare = 0.0;           // of every ray of the render
  double timeShare = 0.0;          // of the timed walks and connections (0 while timing was off)
  double nanosecondsPerTry = 0.0;  // over the timed samples only
};

enum class TechniqueColumn {
  Name, Tried, Zero, Blocked, BlockedShare, Contributed, Discarded, Rays, RaysPerSecond, RayShare, TimeShare, TimePerTry
};

struct TechniqueColumnInfo {
  TechniqueColumn column;
  const char* header;
  const char* help;  // one line for a tooltip
};

// Every column, in the order both front ends show them.
std::span<const TechniqueColumnInfo> techniqueColumns();

// The walks (when the bidirectional walks traced anything), then every technique up to maxLength
// that was tried. seconds: the render time the counters were gathered in.
std::vector<TechniqueRow> techniqueRows(const Counters& counters, int maxLength, double seconds);
// Sorted by a column; ties and Name keep the order of techniqueRows.
void sortRows(std::vector<TechniqueRow>& rows, TechniqueColumn column, bool descending);
// The text of one cell (counts above 10^4 as "12.3k", "4.56M"; shares in percent); `timed`: some
// samples were timed (Counters::timedSamples > 0), else the time columns show "-".
std::string techniqueCell(const TechniqueRow& row, TechniqueColumn column, bool timed);
// A count as both front ends print it: exact below 10^4, then "12.3k", "4.56M", "1.23G".
std::string compactCount(double v);
// The whole table as aligned text (names to the left, numbers to the right), a header line and
// one line a row.
std::string techniqueTableText(const std::vector<TechniqueRow>& rows, bool timed);

}  // namespace pathlab
