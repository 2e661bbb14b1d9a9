// An outlier's sample replayed, its record found, its density against the best.
#include "core/render/outlier_replay.h"

#include "core/render/inspection_report.h"

#include <cmath>

namespace pathlab {

int outlierRecord(const SampleTrace& trace, const Outlier& o) {
  int record = -1;
  double closest = INFINITY;
  for (size_t i = 0; i < trace.records.size(); ++i) {
    const TechniqueResult& t = trace.records[i];
    if (t.technique().index() != o.technique.index() || t.outcome != TechniqueOutcome::Contributed) continue;
    const double d = std::abs(static_cast<double>(luminance(t.unweighted * t.imageWeight)) - o.luminance);
    if (d < closest) closest = d, record = static_cast<int>(i);
  }
  return record;
}

ReplayedOutlier replayOutlier(const RenderSession& session, const Outlier& o) {
  ReplayedOutlier r;
  r.o = o;
  r.inspection = inspectSample(session, o.id.x, o.id.y, o.id.sample);
  r.record = outlierRecord(r.inspection.trace, o);
  if (r.record >= 0 && static_cast<size_t>(r.record) < r.inspection.trace.onPath.size()) {
    const std::vector<TechniqueOnPath>& every = r.inspection.trace.onPath[static_cast<size_t>(r.record)];
    double best = 0.0;
    for (const TechniqueOnPath& x : every)
      if (x.counted && x.pdfA > best) best = x.pdfA, r.best = x.technique();
    if (const TechniqueOnPath* own = findOnPath(every, o.technique); own && best > 0.0) r.densityRatio = own->pdfA / best;
  }
  return r;
}

double outlierShareOfPixel(const Outlier& o, const Image& image, uint64_t spp) {
  const int px = static_cast<int>(std::floor(o.pRaster.x)), py = static_cast<int>(std::floor(o.pRaster.y));
  if (spp == 0 || px < 0 || py < 0 || px >= image.width || py >= image.height) return 0.0;
  const Vec3 c = image.at(px, py);
  const double pixel = luminance(Spectrum(c.x, c.y, c.z));
  return pixel > 0.0 ? static_cast<double>(o.luminance) / static_cast<double>(spp) / pixel : 0.0;
}

namespace {
nlohmann::json techniqueJson(Technique x) {
  return {{"kind", x.isMerge() ? "merge" : x.isEquiangular() ? "equiangular" : "connection"}, {"s", x.s}, {"t", x.t}};
}
}  // namespace

nlohmann::json outlierJson(const RenderSettings& settings, const ReplayedOutlier& r, double shareOfPixel) {
  nlohmann::json x;
  x["luminance"] = r.o.luminance;
  x["value"] = {r.o.value.r, r.o.value.g, r.o.value.b};
  x["pixel"] = {r.o.id.x, r.o.id.y};
  x["sample"] = r.o.id.sample;
  x["technique"] = techniqueJson(r.o.technique);
  x["raster"] = {r.o.pRaster.x, r.o.pRaster.y};
  x["shareOfPixel"] = shareOfPixel;
  x["densityRatio"] = r.densityRatio;
  x["bestTechnique"] = techniqueJson(r.best);
  // The technique's record as `inspect --json` writes it: its path, vertex densities, the path
  // under every technique of its length and its weights.
  if (r.record >= 0) x["record"] = inspectionJson(settings, r.inspection)["techniques"][static_cast<size_t>(r.record)];
  return x;
}

}  // namespace pathlab
