// Per-technique rows and cells from the counters (see the header).
#include "core/metrics/technique_table.h"

#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>

namespace pathlab {

namespace {

constexpr std::array<TechniqueColumnInfo, 12> kColumns = {{
    {TechniqueColumn::Name, "(s,t)", "the walks, then each technique (s light, t camera vertices) tried"},
    {TechniqueColumn::Tried, "tried", "connections tried (walks: subpaths traced)"},
    {TechniqueColumn::Zero, "zero", "connections with no contribution before any shadow ray"},
    {TechniqueColumn::Blocked, "blocked", "connections whose shadow ray was occluded"},
    {TechniqueColumn::BlockedShare, "% blocked", "blocked, as a share of the connections tried"},
    {TechniqueColumn::Contributed, "contrib.", "connections with a non-zero unweighted contribution"},
    {TechniqueColumn::Discarded, "discarded", "contributions refused as NaN, Inf or negative"},
    {TechniqueColumn::Rays, "rays", "shadow rays, plus its own subpaths' rays under --connect endpoints (walks: closest-hit rays)"},
    {TechniqueColumn::RaysPerSecond, "rays/s", "rays per second of render time"},
    {TechniqueColumn::RayShare, "% rays", "share of every ray of the render"},
    {TechniqueColumn::TimeShare, "% time", "share of the timed work: connect + MIS weight, the walks per subpath"},
    {TechniqueColumn::TimePerTry, "ns/try", "time per try over the timed samples (one camera sample in eight)"},
}};

double sortKey(const TechniqueRow& r, TechniqueColumn column) {
  switch (column) {
    case TechniqueColumn::Name: return static_cast<double>(r.order);
    case TechniqueColumn::Tried: return static_cast<double>(r.tried);
    case TechniqueColumn::Zero: return static_cast<double>(r.zero);
    case TechniqueColumn::Blocked: return static_cast<double>(r.blocked);
    case TechniqueColumn::BlockedShare:
      return r.tried > 0 ? static_cast<double>(r.blocked) / static_cast<double>(r.tried) : 0.0;
    case TechniqueColumn::Contributed: return static_cast<double>(r.contributed);
    case TechniqueColumn::Discarded: return static_cast<double>(r.discarded);
    case TechniqueColumn::Rays: return static_cast<double>(r.rays);
    case TechniqueColumn::RaysPerSecond: return r.raysPerSecond;
    case TechniqueColumn::RayShare: return r.rayShare;
    case TechniqueColumn::TimeShare: return r.timeShare;
    case TechniqueColumn::TimePerTry: return r.nanosecondsPerTry;
  }
  return 0.0;
}

}  // namespace

std::span<const TechniqueColumnInfo> techniqueColumns() { return kColumns; }

std::string compactCount(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f}M", v / 1e6);
  if (v >= 1e4) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

std::vector<TechniqueRow> techniqueRows(const Counters& c, int maxLength, double seconds) {
  std::vector<TechniqueRow> rows;
  const double totalRays = static_cast<double>(c.totalRays());
  const double timed = static_cast<double>(c.timedNanoseconds());
  // Time per try is over the timed samples: scale the tries to them (timing may have been on for
  // part of the render only).
  const double timedFraction =
      c.cameraSamples > 0 ? static_cast<double>(c.timedSamples) / static_cast<double>(c.cameraSamples) : 0.0;
  auto finish = [&](TechniqueRow& r, uint64_t ns) {
    r.raysPerSecond = seconds > 0.0 ? static_cast<double>(r.rays) / seconds : 0.0;
    r.rayShare = totalRays > 0.0 ? static_cast<double>(r.rays) / totalRays : 0.0;
    r.timeShare = timed > 0.0 ? static_cast<double>(ns) / timed : 0.0;
    const double timedTries = static_cast<double>(r.tried) * timedFraction;
    r.nanosecondsPerTry = timedTries > 0.0 ? static_cast<double>(ns) / timedTries : 0.0;
    r.order = static_cast<int>(rows.size());
    rows.push_back(std::move(r));
  };
  if (c.cameraWalk.rays + c.lightWalk.rays > 0)
    for (const auto& [name, walk] : {std::pair{"camera walks", c.cameraWalk}, std::pair{"light walks", c.lightWalk}}) {
      TechniqueRow r{name, true};
      r.tried = c.cameraSamples;
      r.rays = walk.rays;
      finish(r, walk.nanoseconds);
    }
  // Vertex merging's shared work, per camera sample like the walks: the pass's store (its light
  // walks, grid and MIS terms) and the range searches (the merges' own work is in their rows).
  if (c.mergePass.rays + c.mergePass.nanoseconds + c.mergeSearch.nanoseconds > 0)
    for (const auto& [name, work] : {std::pair{"merge pass", c.mergePass}, std::pair{"merge searches", c.mergeSearch}}) {
      TechniqueRow r{name, true};
      r.tried = c.cameraSamples;
      r.rays = work.rays;
      finish(r, work.nanoseconds);
    }
  // A family that never ran (merges without a merging integrator) has no tried row and no line.
  auto add = [&](std::string name, Technique x, const TechniqueCounters& tc) {
    if (tc.tried == 0) return;
    TechniqueRow r{std::move(name), false, x.s, x.t, x.kind};
    r.tried = tc.tried;
    r.zero = tc.zero;
    r.blocked = tc.blocked;
    r.contributed = tc.contributed;
    r.discarded = tc.discarded.total();
    r.rays = tc.shadowRays + tc.walkRays;
    finish(r, tc.nanoseconds);
  };
  for (const Technique x : techniquesUpTo(std::min(maxLength, kCountedLength), TechniqueFamilies::All))
    add(techniqueLabel(x), x, c.technique(x));
  if (maxLength > kCountedLength) add(fmt::format("k>{}", kCountedLength), Technique{-1, -1}, c.techniques[kCountedTechniques]);
  return rows;
}

void sortRows(std::vector<TechniqueRow>& rows, TechniqueColumn column, bool descending) {
  std::stable_sort(rows.begin(), rows.end(), [&](const TechniqueRow& a, const TechniqueRow& b) {
    return descending ? sortKey(a, column) > sortKey(b, column) : sortKey(a, column) < sortKey(b, column);
  });
}

std::string techniqueCell(const TechniqueRow& r, TechniqueColumn column, bool timed) {
  const bool connection = !r.walk;
  switch (column) {
    case TechniqueColumn::Name: return r.name;
    case TechniqueColumn::Tried: return compactCount(static_cast<double>(r.tried));
    case TechniqueColumn::Zero: return connection ? compactCount(static_cast<double>(r.zero)) : "";
    case TechniqueColumn::Blocked: return connection ? compactCount(static_cast<double>(r.blocked)) : "";
    case TechniqueColumn::BlockedShare:
      return !connection ? "" : r.tried > 0 ? fmt::format("{:.0f}%", 100.0 * sortKey(r, column)) : "-";
    case TechniqueColumn::Contributed: return connection ? compactCount(static_cast<double>(r.contributed)) : "";
    case TechniqueColumn::Discarded: return connection ? compactCount(static_cast<double>(r.discarded)) : "";
    case TechniqueColumn::Rays: return compactCount(static_cast<double>(r.rays));
    case TechniqueColumn::RaysPerSecond: return compactCount(r.raysPerSecond);
    case TechniqueColumn::RayShare: return fmt::format("{:.1f}", 100.0 * r.rayShare);
    case TechniqueColumn::TimeShare: return timed ? fmt::format("{:.1f}", 100.0 * r.timeShare) : "-";
    case TechniqueColumn::TimePerTry: return timed ? fmt::format("{:.0f}", r.nanosecondsPerTry) : "-";
  }
  return "";
}

std::string techniqueTableText(const std::vector<TechniqueRow>& rows, bool timed) {
  std::vector<size_t> widths;
  for (const TechniqueColumnInfo& c : kColumns) {
    size_t w = std::string(c.header).size();
    for (const TechniqueRow& r : rows) w = std::max(w, techniqueCell(r, c.column, timed).size());
    widths.push_back(w);
  }
  std::string out;
  auto line = [&](auto cellOf) {
    for (size_t i = 0; i < kColumns.size(); ++i)
      out += i == 0 ? fmt::format("{:<{}}", cellOf(kColumns[i]), widths[i])
                    : fmt::format("  {:>{}}", cellOf(kColumns[i]), widths[i]);
    out += '\n';
  };
  line([](const TechniqueColumnInfo& c) { return std::string(c.header); });
  for (const TechniqueRow& r : rows) line([&](const TechniqueColumnInfo& c) { return techniqueCell(r, c.column, timed); });
  return out;
}

}  // namespace pathlab
