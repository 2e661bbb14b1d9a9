// A replayed sample with merges (`pathlab inspect`, the path inspector): its merges are the
// render's bit for bit (the pass's store is traced again), and each merge's inspection names its
// two vertices and the radius, and lists its path under every technique of its length,
// connections and merges, whose weights sum to one and follow from the listed densities.
#include "core/bpt/bidir_tracer.h"
#include "core/render/inspection_report.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

const Scene& mergeInspectionSpheres() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  return scene;
}

// --integrator vcm (bpm: the merges alone) on a small image, with a radius large enough that most
// camera vertices find light vertices to merge with.
RenderSettings mergeInspectionSettings(const std::string& techniques, MisHeuristic heuristic = MisHeuristic::Balance) {
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse(techniques);
  s.mergeRadius = 0.05f;
  s.mergeNonCaustic = 1.f;  // every light vertex kept: merges in every pixel
  s.mis.heuristic = heuristic;
  s.seed = 17;
  return s;
}

const char* heuristicKey(MisHeuristic h) {
  return h == MisHeuristic::Power ? "power" : h == MisHeuristic::Uniform ? "uniform" : "balance";
}

// A merge's inspection in JSON: kind, both vertices within the radius, the render's weight, and the
// path's techniques of both families whose weights sum to one and are recomputed from their
// densities (n p over the counted ones; n = N, the pass's light subpaths, for a merge).
TEST(MergeInspection, JsonOfAMergeNamesItsVerticesAndItsTechniquesWeightsSumToOne) {
  for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    const RenderSettings settings = mergeInspectionSettings("all;m=all", h);
    const RenderSession session(mergeInspectionSpheres(), settings);
    const double N = static_cast<double>(settings.width * settings.height);
    int merges = 0, connections = 0;
    for (int y = 4; y < settings.height && merges < 40; y += 3)
      for (int x = 2; x < settings.width && merges < 40; x += 3) {
        const nlohmann::json j = inspectionJson(settings, inspectSample(session, x, y, 0));
        ASSERT_EQ(j["mergeSampleCount"].get<double>(), N);
        for (const nlohmann::json& t : j["techniques"]) {
          const std::vector<nlohmann::json> every = t["densities"];
          if (every.empty()) continue;  // nothing formed
          const bool merge = t["kind"] == "merge";
          const int k = t["s"].get<int>() + t["t"].get<int>() - (merge ? 2 : 1);
          // Every technique of the length: k + 1 connections, then k - 1 merges.
          ASSERT_EQ(every.size(), static_cast<size_t>(2 * k));
          double sum = 0.0, denominator = 0.0;
          int counted = 0;
          const double beta = h == MisHeuristic::Power ? settings.mis.beta : 1.0;
          for (const nlohmann::json& x : every) {
            sum += x["weights"][heuristicKey(h)].get<double>();
            if (!x["counted"].get<bool>()) continue;
            const double n = x["kind"] == "merge" ? N : 1.0;
            denominator += std::pow(n * x["pdfA"].get<double>(), beta);
            ++counted;
          }
          if (!(t["weight"].get<double>() > 0.0)) continue;  // a path no enabled technique weighs
          EXPECT_NEAR(sum, 1.0, 1e-4) << t.dump();
          // The own entry is the render's weight, and follows from the densities listed: for a
          // merge, those of its merged path (merge_mis.h mergedPathDensities: z's BSDF and density
          // at the merged vertex), on which the render weighs it.
          const nlohmann::json& self = every[static_cast<size_t>(merge ? k - 1 + t["s"].get<int>() : t["s"].get<int>())];
          ASSERT_EQ(self["kind"], t["kind"]);
          const nlohmann::json& own = t["weights"];
          // The render's O(1) weight against the listing's explicit one (float sums: a few ulps
          // for a connection, the recursion's rounding for a merge).
          const double tolerance = merge ? 1e-4 : 1e-5;
          EXPECT_NEAR(own[heuristicKey(h)].get<double>(), t["weight"].get<double>(), tolerance * t["weight"].get<double>())
              << t.dump();
          const double n = merge ? N : 1.0;
          EXPECT_NEAR(std::pow(n * self["pdfA"].get<double>(), beta) / denominator, t["weight"].get<double>(),
                      std::max(tolerance, 1e-4) * t["weight"].get<double>())
              << t.dump();
          if (!merge) {
            ++connections;
            continue;
          }
          ++merges;
          const double r = t["radius"].get<double>();
          EXPECT_GT(r, 0.0);
          EXPECT_LE(t["distance"].get<double>(), r * (1.0 + 1e-5));
          const std::vector<float> light = t["lightVertex"], camera = t["cameraVertex"];
          EXPECT_NEAR(std::hypot(light[0] - camera[0], light[1] - camera[1], light[2] - camera[2]),
                      t["distance"].get<double>(), 1e-5);
          // The path runs through the light vertex: its x_{s-1}.
          const int s = t["s"].get<int>();
          const std::vector<float> merged = t["path"][static_cast<size_t>(s - 1)];
          EXPECT_EQ(merged, light);
          EXPECT_EQ(t["path"].size(), static_cast<size_t>(k + 1));
          EXPECT_EQ(self["mergedVertex"].get<int>(), s - 1);
          EXPECT_TRUE(t["contribution"].is_array());
        }
      }
    EXPECT_GE(merges, 40) << heuristicKey(h);
    EXPECT_GE(connections, 40) << heuristicKey(h);
  }
}

// The render's merges, replayed: a bpm render of one pass (merges only, no splats) has in each
// pixel exactly the replayed sample's estimate, and a vcm render's pyramid has in each pixel and
// merge technique exactly the replayed sample's merge records of that technique, weighted and
// unweighted (the same sums of the same floats in the same order: EXPECT_EQ, not near).
TEST(MergeInspection, ReplayedMergesAreTheRendersBitForBit) {
  const Scene& scene = mergeInspectionSpheres();
  {
    RenderSettings bpm = mergeInspectionSettings("m=all");
    RenderSession session(scene, bpm);
    session.renderPass();
    const Image image = session.image();
    int lit = 0;
    for (int y = 0; y < bpm.height; ++y)
      for (int x = 0; x < bpm.width; ++x) {
        Counters c;
        const Spectrum L = session.replaySample(x, y, 0, c);
        for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(image.at(x, y)[ch], static_cast<float>(static_cast<double>(L[ch]) * 1.0)) << x << "," << y;
        lit += isBlack(L) ? 0 : 1;
      }
    EXPECT_GT(lit, bpm.width * bpm.height / 2);
  }
  // The second pass (radius r_2 < r_1, a store of its own) of a session, through the pyramid.
  RenderSettings vcm = mergeInspectionSettings("all;m=all");
  vcm.pyramidLength = vcm.maxLength;
  RenderSession session(scene, vcm, PassSchedule{1, 1});
  session.renderPass();
  std::vector<std::pair<Image, Image>> pyramid;  // weighted, unweighted, by merge
  for (const Technique m : techniquesUpTo(vcm.maxLength, TechniqueFamilies::Merges))
    pyramid.emplace_back(session.techniqueImage(m, false), session.techniqueImage(m, true));
  int merges = 0;
  for (int y = 0; y < vcm.height; y += 2)
    for (int x = 0; x < vcm.width; x += 2) {
      Counters c;
      SampleTrace trace;
      session.replaySample(x, y, 1, c, nullptr, &trace);
      size_t i = 0;
      for (const Technique m : techniquesUpTo(vcm.maxLength, TechniqueFamilies::Merges)) {
        DVec3 w(0.0), u(0.0);
        for (const TechniqueResult& r : trace.records)
          if (r.technique() == m && r.outcome == TechniqueOutcome::Contributed) {
            w += DVec3(r.unweighted * r.weight);
            u += DVec3(r.unweighted);
            ++merges;
          }
        for (int ch = 0; ch < 3; ++ch) {
          ASSERT_EQ(pyramid[i].first.at(x, y)[ch], static_cast<float>(w[ch])) << x << "," << y;
          ASSERT_EQ(pyramid[i].second.at(x, y)[ch], static_cast<float>(u[ch])) << x << "," << y;
        }
        ++i;
      }
    }
  EXPECT_GT(merges, 100);
}

}  // namespace
}  // namespace pathlab
