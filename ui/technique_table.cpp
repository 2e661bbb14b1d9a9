// Per-technique rows from the counters (see the header).
#include "ui/technique_table.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::ui {

std::vector<TechniqueRow> techniqueRows(const Counters& c, int maxLength, double seconds) {
  std::vector<TechniqueRow> rows;
  const double totalRays = static_cast<double>(c.totalRays());
  const double timed = static_cast<double>(c.timedNanoseconds());
  // Time per try is over the timed samples: scale the tries to them (timing may have been on for
  // part of the generation only).
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
  if (c.cameraWalk.rays + c.lightWalk.rays > 0) {
    TechniqueRow camera{"camera walks"};
    camera.tried = c.cameraSamples;
    camera.rays = c.cameraWalk.rays;
    finish(camera, c.cameraWalk.nanoseconds);
    TechniqueRow light{"light walks"};
    light.tried = c.cameraSamples;
    light.rays = c.lightWalk.rays;
    finish(light, c.lightWalk.nanoseconds);
  }
  auto add = [&](std::string name, int s, int t, const TechniqueCounters& tc) {
    if (tc.tried == 0) return;
    TechniqueRow r{std::move(name), s, t};
    r.tried = tc.tried;
    r.rays = tc.shadowRays;
    r.blocked = tc.blocked;
    r.contributed = tc.contributed;
    r.discarded = tc.discarded.total();
    finish(r, tc.nanoseconds);
  };
  for (const auto [s, t] : techniquesUpTo(std::min(maxLength, kCountedLength)))
    add(fmt::format("({},{})", s, t), s, t, c.technique(s, t));
  if (maxLength > kCountedLength) add(fmt::format("k>{}", kCountedLength), -1, -1, c.techniques[kCountedTechniques]);
  return rows;
}

void sortRows(std::vector<TechniqueRow>& rows, TechniqueColumn column, bool descending) {
  auto key = [&](const TechniqueRow& r) -> double {
    switch (column) {
      case TechniqueColumn::Name: return static_cast<double>(r.order);
      case TechniqueColumn::Tried: return static_cast<double>(r.tried);
      case TechniqueColumn::Rays: return static_cast<double>(r.rays);
      case TechniqueColumn::RaysPerSecond: return r.raysPerSecond;
      case TechniqueColumn::RayShare: return r.rayShare;
      case TechniqueColumn::TimeShare: return r.timeShare;
      case TechniqueColumn::TimePerTry: return r.nanosecondsPerTry;
      case TechniqueColumn::Contributed: return static_cast<double>(r.contributed);
      case TechniqueColumn::Blocked: return static_cast<double>(r.blocked);
    }
    return 0.0;
  };
  std::stable_sort(rows.begin(), rows.end(), [&](const TechniqueRow& a, const TechniqueRow& b) {
    return descending ? key(a) > key(b) : key(a) < key(b);
  });
}

}  // namespace pathlab::ui
