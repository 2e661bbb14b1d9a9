// The inspection of one sample as text and as JSON (core/render/inspection_report.h).
#include "core/render/inspection_report.h"

#include "core/bpt/bidir_tracer.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <cmath>

namespace pathlab {

namespace {

const char* kindName(TechniqueKind k) {
  return k == TechniqueKind::Merge ? "merge" : k == TechniqueKind::Equiangular ? "equiangular" : "connection";
}

const char* kindName(TracedVertexKind k) {
  switch (k) {
    case TracedVertexKind::Camera: return "camera";
    case TracedVertexKind::Light: return "light";
    case TracedVertexKind::Surface: return "surface";
    case TracedVertexKind::Medium: return "medium";
  }
  return "surface";
}

const char* kindName(VertexType t) {
  return t == VertexType::Camera ? "camera" : t == VertexType::Light ? "light" : t == VertexType::Medium ? "medium" : "surface";
}

nlohmann::json vec(Vec3 v) { return {v.x, v.y, v.z}; }

// C(s,t) is printed (s,t), as ever; a merge M(s,t), an equiangular technique E(1,t).
std::string techniqueName(TechniqueKind kind, int s, int t) { return techniqueLabel(Technique{s, t, kind}); }
nlohmann::json rgb(Spectrum s) { return {s.r, s.g, s.b}; }

// The path a technique formed, under every technique of its length (the seed's "one path, every
// technique"): the density each would sample it with, the edge it connects, its weights; under
// variance-aware MIS also each technique's factor where the path lands and its weight with them.
void printTechniquesOnPath(std::ostream& out, const std::vector<TechniqueOnPath>& every, bool varianceAware) {
  if (every.empty()) return;
  out << fmt::format("{:>12}  this path under every technique: {:>11} {:>9} {:>9} {:>9}{}  {}\n", "", "p_A(x)",
                     "balance", "power", "uniform",
                     varianceAware ? fmt::format(" {:>9} {:>9}", "factor", "var-aware") : std::string(), "connects");
  for (const TechniqueOnPath& x : every) {
    const std::string name = x.kind == TechniqueKind::Equiangular ? fmt::format("E({},{}) equiangular", x.s, x.t)
                                                                  : techniqueName(x.kind, x.s, x.t);
    const bool merge = x.kind == TechniqueKind::Merge;
    const std::string edge = merge                   ? fmt::format("merges at x{}", x.mergedVertex)
                             : x.connectionEdge < 0 ? std::string("nothing: hits the emitter")
                                                    : fmt::format("x{}-x{}", x.connectionEdge, x.connectionEdge + 1);
    if (!x.possible) {
      const std::string why =
          merge ? fmt::format("x{} is no surface vertex a merge can take (a delta lobe, or in a medium)", x.mergedVertex)
          : x.connectionEdge < 0
              ? std::string("its emitter cannot be hit by a ray (point, spot, directional light)")
          : x.t == 1 ? fmt::format("x{} scatters by a delta lobe, or the camera is orthographic "
                                   "(a delta direction)", x.connectionEdge)
                     : fmt::format("x{} or x{} scatters by a delta lobe", x.connectionEdge, x.connectionEdge + 1);
      out << fmt::format("{:>12}  {:>32} {:>11}  cannot: {}\n", "", name, "0", why);
      continue;
    }
    out << fmt::format("{:>12}  {:>32} {:>11.4e} {:>9.4f} {:>9.4f} {:>9.4f}{}  {}{}\n", "", name, x.pdfA, x.balance,
                       x.power, x.uniform,
                       varianceAware ? fmt::format(" {:>9.4g} {:>9.4f}", x.factor, x.varianceAware) : std::string(), edge,
                       x.enabled ? "" : "  (disabled)");
  }
}

// A merge's two vertices, how far apart, and the pass's radius.
void printMerged(std::ostream& out, const MergedVertices& m) {
  out << fmt::format("{:>12}  merges light vertex ({:.4g}, {:.4g}, {:.4g}) and camera vertex ({:.4g}, {:.4g}, {:.4g}): "
                     "{:.4g} apart, radius {:.4g}\n",
                     "", m.light.x, m.light.y, m.light.z, m.camera.x, m.camera.y, m.camera.z,
                     glm::length(m.light - m.camera), m.radius);
}

void printPath(std::ostream& out, const TracedPath& path) {
  for (size_t i = 0; i < path.size(); ++i) {
    // x0's next-event density, where the light choice depends on x1 and so differs.
    const std::string nee = i == 0 && path.x0Nee != path.pFromLight[0]
                                ? fmt::format("  (by next-event estimation {:.4e})", path.x0Nee)
                                : std::string();
    out << fmt::format("{:>12}  x{} {:<8} ({:.4g}, {:.4g}, {:.4g})  p from light {:.4e}{}  p from camera {:.4e}{}\n",
                       "", i, kindName(path.kind[i]), path.p[i].x, path.p[i].y, path.p[i].z, path.pFromLight[i], nee,
                       path.pFromCamera[i], path.delta[i] ? "  delta" : "");
  }
}

nlohmann::json subpathJson(const std::vector<PathVertex>& subpath) {
  nlohmann::json out = nlohmann::json::array();
  for (const PathVertex& v : subpath) {
    out.push_back({{"p", vec(v.p)},
                   {"kind", kindName(v.type)},
                   {"delta", v.isDelta || v.isDeltaPosition},
                   {"pdfFwdA", v.pdfFwdA},
                   {"pdfRevA", v.pdfRevA}});
    // A light subpath's x0: its density were next-event estimation to choose it for x1.
    if (v.type == VertexType::Light) out.back()["pdfNeeA"] = v.pdfNeeA;
  }
  return out;
}

}  // namespace

// A Metropolis chain's state: which chain, its technique and target, what it adds where, and the
// primary numbers its path was made from.
void printChainState(std::ostream& out, const RenderSettings& settings, const SampleInspection& in) {
  const MltChainState& c = *in.chain;
  const bool multiplexed = settings.mlt.variant == MltVariant::Multiplexed;
  out << fmt::format("chain {} of {} ({}{}) after {} pass{}: ", c.chain, in.chains, mltVariantName(settings.mlt.variant),
                     multiplexed ? fmt::format(", paths of {} edges", c.length) : std::string(), in.sample,
                     in.sample == 1 ? "" : "es");
  if (multiplexed) out << fmt::format("technique ({},{}), ", c.technique.s, c.technique.t);
  out << fmt::format("target f = {:.6g}\n", c.f);
  if (multiplexed)
    out << "  (f is the luminance of the technique's MIS-weighted contribution times the number of enabled "
           "techniques of its length)\n";
  for (const MltChainState::Contribution& x : c.contributions)
    out << fmt::format("  contribution F = ({:.4g}, {:.4g}, {:.4g}) at raster {:.2f},{:.2f} (pixel {},{})\n", x.L.r, x.L.g,
                       x.L.b, x.pRaster.x, x.pRaster.y, static_cast<int>(std::floor(x.pRaster.x)),
                       static_cast<int>(std::floor(x.pRaster.y)));
  if (c.contributions.empty()) out << "  no contribution (a state of f = 0)\n";
  else out << "  (each mutation the chain spends here adds b F / f to the image, b its length's normalisation)\n";
  static const char* kStreamNames[PrimarySamples::kStreams] = {"camera", "light", "connection"};
  out << "primary numbers the path read, stream by stream:\n";
  for (int k = 0; k < PrimarySamples::kStreams; ++k) {
    out << fmt::format("{:>12}:", kStreamNames[k]);
    if (c.numbers[k].empty()) out << " none";
    for (const float u : c.numbers[k]) out << fmt::format(" {:.6f}", u);
    out << "\n";
  }
}

void printInspection(std::ostream& out, const RenderSettings& settings, const SampleInspection& in, bool paths) {
  const Spectrum L = in.cameraEstimate;
  if (in.chain) printChainState(out, settings, in);
  else
    out << fmt::format("pixel {},{} sample {} ({}): camera-side estimate ({:g}, {:g}, {:g})\n", in.x, in.y, in.sample,
                       integratorName(settings.integrator), L.r, L.g, L.b);
  if (settings.integrator == IntegratorKind::Pt) return;
  const SampleTrace& trace = in.trace;
  out << fmt::format("camera subpath {} vertices, light subpath {} vertices\n", trace.cameraVertices,
                     trace.lightVertices);
  out << fmt::format("{:>8} {:>36} {:>10} {:>36} {:>16} {}\n", "(s,t)", "unweighted", "weight", "weighted", "raster", "");
  for (size_t i = 0; i < trace.records.size(); ++i) {
    const TechniqueResult& t = trace.records[i];
    const Spectrum w = t.unweighted * t.weight;
    out << fmt::format("{:>8} {:>36} {:>10.4g} {:>36} {:>16} {}\n", techniqueName(t.kind, t.s, t.t),
                       fmt::format("({:.4g}, {:.4g}, {:.4g})", t.unweighted.r, t.unweighted.g, t.unweighted.b), t.weight,
                       fmt::format("({:.4g}, {:.4g}, {:.4g})", w.r, w.g, w.b),
                       fmt::format("{:.1f},{:.1f}", t.pRaster.x, t.pRaster.y),
                       t.blocked() ? "blocked" : isBlack(t.unweighted) ? "zero" : t.inImage ? "" : "not in the image");
    if (t.kind == TechniqueKind::Merge) printMerged(out, t.merged);
    if (paths && i < trace.paths.size()) printPath(out, trace.paths[i]);
    if (i < trace.onPath.size() && (paths || !t.blocked())) printTechniquesOnPath(out, trace.onPath[i], settings.mis.heuristic == MisHeuristic::VarianceAware);
    if (i < in.optimalBeta.size() && !in.optimalBeta[i].empty()) {
      // --mis optimal: what the image added to this contribution, and the coefficients it came from.
      const Spectrum c = in.optimalCorrection[i];
      out << fmt::format("         optimal MIS correction ({:.4g}, {:.4g}, {:.4g}) = beta_s - sum_k beta_k w_k; beta by s':",
                         c.r, c.g, c.b);
      for (const Spectrum& b : in.optimalBeta[i]) out << fmt::format(" {:.4g}", luminance(b));
      out << " (luminance)\n";
    }
  }
}

nlohmann::json inspectionJson(const RenderSettings& settings, const SampleInspection& in) {
  const SampleTrace& trace = in.trace;
  nlohmann::json j;
  j["pixel"] = {in.x, in.y};
  j["sample"] = in.sample;
  if (in.chain) {
    // A Metropolis chain's state (docs/cli.md): `sample` is the passes it had run.
    const MltChainState& c = *in.chain;
    nlohmann::json chain;
    chain["index"] = c.chain;
    chain["chains"] = in.chains;
    chain["variant"] = mltVariantName(settings.mlt.variant);
    chain["length"] = c.length;
    if (settings.mlt.variant == MltVariant::Multiplexed) chain["technique"] = {c.technique.s, c.technique.t};
    chain["f"] = c.f;
    nlohmann::json contributions = nlohmann::json::array();
    for (const MltChainState::Contribution& x : c.contributions)
      contributions.push_back({{"raster", {x.pRaster.x, x.pRaster.y}}, {"value", rgb(x.L)}});
    chain["contributions"] = contributions;
    chain["primaryNumbers"] = {{"camera", c.numbers[0]}, {"light", c.numbers[1]}, {"connection", c.numbers[2]}};
    j["chain"] = chain;
  }
  j["seed"] = settings.seed;
  j["integrator"] = integratorName(settings.integrator);
  j["heuristic"] = misHeuristicName(settings.mis.heuristic);
  j["beta"] = settings.mis.beta;
  j["minConnection"] = settings.mis.minConnection;
  j["connect"] = connectStrategyName(settings.connect);
  // The sample-count factor of the weights (Veach 1997 eq. 9.13: p_s is multiplied by n_s, the
  // samples of technique s per camera sample): light subpaths per camera sample for the t = 1
  // techniques. With 1 it drops out of every weight.
  j["lightTracingSampleRatio"] = lightTracingRatio();
  // --light-paths F (core/bpt/light_paths.h): the techniques that walk a light subpath (t = 1 and
  // s >= 2) draw F samples per camera sample, so their n_s is F in every weight (times the ratio
  // above for t = 1).
  j["lightPaths"] = settings.lightPaths;
  // The merges' sample count (Georgiev et al. 2012 eq. 11): every light subpath of the pass serves
  // every camera sample, so a merge's p is multiplied by N, the pass's light subpaths, in every
  // weight (eta = pi r^2 N, merge_mis.h).
  if (covers(enabledTechniques(settings).families(), TechniqueKind::Merge))
    j["mergeSampleCount"] = lightSubpathsPerPass(static_cast<uint64_t>(settings.width) * static_cast<uint64_t>(settings.height));
  j["cameraEstimate"] = rgb(in.cameraEstimate);
  j["cameraSubpath"] = subpathJson(trace.cameraSubpath);
  j["lightSubpath"] = subpathJson(trace.lightSubpath);
  const TechniqueSet enabled = enabledTechniques(settings);
  nlohmann::json techniques = nlohmann::json::array();
  for (size_t i = 0; i < trace.records.size(); ++i) {
    const TechniqueResult& r = trace.records[i];
    nlohmann::json t;
    t["kind"] = kindName(r.kind);
    t["s"] = r.s;
    t["t"] = r.t;
    t["enabled"] = enabled.contains(r.technique());
    t["blocked"] = r.blocked();
    t["contribution"] = rgb(r.unweighted);
    t["weight"] = r.weight;
    t["inImage"] = r.inImage;
    t["raster"] = {r.pRaster.x, r.pRaster.y};
    if (r.kind == TechniqueKind::Merge) {
      // y(s-1) and z(t-1), taken as one vertex within the pass's radius; the path runs through
      // y(s-1) (merge_mis.h).
      t["lightVertex"] = vec(r.merged.light);
      t["cameraVertex"] = vec(r.merged.camera);
      t["cameraNormal"] = vec(r.merged.cameraNormal);
      t["distance"] = glm::length(r.merged.light - r.merged.camera);
      t["radius"] = r.merged.radius;
    }
    nlohmann::json path = nlohmann::json::array(), vertices = nlohmann::json::array();
    if (i < trace.paths.size())
      for (size_t v = 0; v < trace.paths[i].size(); ++v) {
        const TracedPath& p = trace.paths[i];
        path.push_back(vec(p.p[v]));
        vertices.push_back({{"p", vec(p.p[v])},
                            {"kind", kindName(p.kind[v])},
                            {"delta", p.delta[v] != 0},
                            {"deltaPosition", p.deltaPosition[v] != 0},
                            {"pdfFromLightA", p.pFromLight[v]},
                            {"pdfFromCameraA", p.pFromCamera[v]}});
        // x0 as technique (1, t) samples it: next-event estimation chose its light for x1.
        if (v == 0) vertices.back()["pdfFromLightNeeA"] = p.x0Nee;
      }
    t["path"] = path;
    t["vertices"] = vertices;
    nlohmann::json densities = nlohmann::json::array();
    if (i < trace.onPath.size())
      for (const TechniqueOnPath& x : trace.onPath[i])
        densities.push_back({{"kind", kindName(x.kind)},
                             {"s", x.s},
                             {"t", x.t},
                             {"pdfA", x.pdfA},
                             {"possible", x.possible},
                             {"enabled", x.enabled},
                             {"counted", x.counted},
                             {"connectionEdge", x.connectionEdge},
                             {"mergedVertex", x.mergedVertex},
                             {"factor", x.factor},
                             {"weights",
                              {{"balance", x.balance},
                               {"power", x.power},
                               {"uniform", x.uniform},
                               {"variance-aware", x.varianceAware}}}});
    t["densities"] = densities;
    // This technique's own weights under each heuristic (its entry of `densities`).
    if (const TechniqueOnPath* found = i < trace.onPath.size() ? findOnPath(trace.onPath[i], r.technique()) : nullptr) {
      const TechniqueOnPath& own = *found;
      t["weights"] = {{"balance", own.balance},
                      {"power", own.power},
                      {"uniform", own.uniform},
                      {"variance-aware", own.varianceAware}};
      t["factor"] = own.factor;
    }
    // --mis optimal: the correction the image added and the coefficients of the length by s'.
    if (i < in.optimalBeta.size() && !in.optimalBeta[i].empty()) {
      nlohmann::json beta = nlohmann::json::array();
      for (const Spectrum& b : in.optimalBeta[i]) beta.push_back(rgb(b));
      t["optimal"] = {{"correction", rgb(in.optimalCorrection[i])}, {"beta", beta}};
    }
    techniques.push_back(t);
  }
  j["techniques"] = techniques;
  return j;
}

}  // namespace pathlab
