// `pathlab outliers`: the options, the render with its tally, each outlier replayed, text and JSON.
#include "app/outliers_command.h"

#include "app/inspect_command.h"
#include "app/output_check.h"
#include "app/progress.h"
#include "core/camera/image_size.h"
#include "core/io/text_file.h"
#include "core/render/inspection_report.h"
#include "core/render/outlier_replay.h"
#include "core/render/render_session.h"
#include "core/render/sample_inspection.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>

namespace pathlab::app {

namespace {

constexpr uint64_t kMaxOutlierSpp = 1 << 16;
constexpr int kMaxOutliers = 1000;

// One outlier replayed (core/render/outlier_replay.h) and its share of the pixel it landed in.
struct ListedOutlier : ReplayedOutlier {
  double shareOfPixel = 0.0;
};

}  // namespace

void addOutliersCommand(CLI::App& app, OutliersOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "outliers", "Render and list the brightest weighted contributions (the fireflies): each one's pixel, sample, "
                  "technique and path, and how much less likely its technique was to sample it than the best "
                  "enabled one (text, and JSON with --json)");
  addSceneArgument(cmd, o.scene.path);
  cmd->add_option("--spp", o.spp, fmt::format("Samples per pixel to render (default 16, at most {})", kMaxOutlierSpp));
  cmd->add_option("--top", o.top, fmt::format("How many to keep (default 10, at most {})", kMaxOutliers));
  cmd->add_option("--json", o.json, "Also write the list as JSON to this file");
  addImageSizeOptions(cmd, o.size, {kMaxImageSide, kDefaultLongestSide});
  addEstimatorOptions(cmd, o.estimator);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
  addThreadsOption(cmd, o.threads);
  addForceFlag(cmd, o.force, "the JSON file if it exists");
}

int runOutliers(OutliersOptions o) {
  const ThreadLimit threadLimit(o.threads);
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt || settings.integrator == IntegratorKind::Mlt)
    throw std::invalid_argument(fmt::format("outliers ranks independent bidirectional samples by technique: use "
                                            "--integrator bpt, lt, vcm, bpm or ppm, not {}",
                                            integratorName(settings.integrator)));
  if (o.spp < 1 || o.spp > kMaxOutlierSpp)
    throw std::invalid_argument(fmt::format("--spp {} is outside 1..{}", o.spp, kMaxOutlierSpp));
  if (o.top < 1 || o.top > kMaxOutliers)
    throw std::invalid_argument(fmt::format("--top {} is outside 1..{}", o.top, kMaxOutliers));
  const std::unique_ptr<Scene> loaded = loadSceneToInspect(o.scene, o.size, settings, o.json, o.force);
  const Scene& scene = *loaded;
  RenderSession session(scene, settings);
  session.setOutlierCount(o.top);
  const auto start = std::chrono::steady_clock::now();
  {
    const double pixels = static_cast<double>(session.film().pixelCount());
    ProgressBar bar([&] {
      const double done = (static_cast<double>(session.passes()) +
                           static_cast<double>(session.pixelsDoneInPass()) / pixels) / static_cast<double>(o.spp);
      return std::pair{done, fmt::format("{} spp", session.passes())};
    });
    while (session.passes() < o.spp) session.renderPass();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Image image = session.image();
  std::vector<ListedOutlier> list;
  for (const Outlier& x : session.outliers()) {
    ListedOutlier l{replayOutlier(session, x)};
    l.shareOfPixel = outlierShareOfPixel(x, image, o.spp);
    list.push_back(std::move(l));
  }

  std::cout << fmt::format("the {} brightest weighted contributions of {} x {} x {} spp ({}; {:.1f} s)\n", list.size(),
                           settings.width, settings.height, o.spp, integratorName(settings.integrator), seconds);
  std::cout << fmt::format("{:>4} {:>11} {:>11} {:>9} {:>8} {:>7} {:>11} {:>9} {:>10}  {}\n", "rank", "luminance",
                           "of pixel", "pixel", "sample", "(s,t)", "lands", "weight", "p / best", "best");
  for (size_t i = 0; i < list.size(); ++i) {
    const ListedOutlier& r = list[i];
    const float weight = r.record >= 0 ? r.inspection.trace.records[static_cast<size_t>(r.record)].imageWeight : 0.f;
    std::cout << fmt::format("{:>4} {:>11.4g} {:>10.1f}% {:>9} {:>8} {:>7} {:>11} {:>9.4f} {:>10.3g}  {}\n", i + 1,
                             r.o.luminance, 100.0 * r.shareOfPixel, fmt::format("{},{}", r.o.id.x, r.o.id.y),
                             r.o.id.sample, techniqueLabel(r.o.technique),
                             fmt::format("{:.1f},{:.1f}", r.o.pRaster.x, r.o.pRaster.y), weight, r.densityRatio,
                             techniqueLabel(r.best));
  }
  std::cout << "(p / best: the density of the technique that sampled the path over the largest density among the "
               "enabled techniques able to sample it; `pathlab inspect --pixel X,Y --sample N` shows the whole "
               "sample)\n";
  if (!o.json.empty()) {
    nlohmann::json j;
    j["scene"] = o.scene.path;
    j["width"] = settings.width;
    j["height"] = settings.height;
    j["spp"] = o.spp;
    j["seed"] = settings.seed;
    j["integrator"] = integratorName(settings.integrator);
    j["heuristic"] = misHeuristicName(settings.mis.heuristic);
    j["beta"] = settings.mis.beta;
    j["lightTracingSampleRatio"] = lightTracingRatio();
    nlohmann::json outliers = nlohmann::json::array();
    for (const ListedOutlier& r : list) outliers.push_back(outlierJson(settings, r, r.shareOfPixel));
    j["outliers"] = outliers;
    writeTextAtomically(o.json, j.dump(2) + "\n");
    std::cerr << "wrote " << o.json << "\n";
  }
  return 0;
}

}  // namespace pathlab::app
