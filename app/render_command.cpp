// `pathlab render`: load, check every option before any work, render passes until the sample or
// time budget is spent, write the image atomically, print a summary.
#include "app/render_command.h"

#include "app/job.h"
#include "app/output_check.h"
#include "app/progress.h"
#include "app/pyramid_output.h"
#include "app/technique_maps_output.h"
#include "app/variance_maps_output.h"
#include "core/bpt/optimal_mis.h"
#include "core/maps/map_colours.h"
#include "core/camera/image_size.h"
#include "core/film/image_io.h"
#include "core/metrics/technique_table.h"
#include "core/render/inspection_report.h"
#include "core/render/render_session.h"
#include "core/sampling/technique_label.h"
#include "core/scene/gltf_loader.h"

#include <fmt/core.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <unistd.h>

namespace pathlab::app {

namespace {

constexpr long long kMaxPixels = 64LL * 1024 * 1024;
constexpr int kDefaultSpp = 64;

// Nothing the user made is overwritten without asking: ask on a terminal, refuse otherwise.
void checkOutput(const std::string& output, bool force) {
  checkOutputWritable(output);
  imageFormatOf(output);  // fails early on an unknown extension
  if (force || !std::filesystem::exists(output)) return;
  if (isatty(STDIN_FILENO)) {
    std::cerr << output << " exists. Overwrite? [y/N] " << std::flush;
    std::string answer;
    std::getline(std::cin, answer);
    if (answer == "y" || answer == "Y" || answer == "yes") return;
  }
  refuseExisting(output, false);
}

// Per-technique counters (core/metrics/technique_table.h, the viewer's table): every walk and
// technique with --stats, otherwise only the techniques that discarded contributions (so a NaN
// source is named without asking).
void printTechniqueCounters(const Counters& c, int maxLength, double seconds, bool all) {
  std::vector<TechniqueRow> rows = techniqueRows(c, maxLength, seconds);
  if (!all) std::erase_if(rows, [](const TechniqueRow& r) { return r.discarded == 0; });
  if (!rows.empty()) std::cerr << techniqueTableText(rows, c.timedSamples > 0);
}

struct ReplayRequest {
  int x = 0, y = 0;
  uint64_t sample = 0;
};

void checkPixels(const RenderSettings& settings) {
  if (static_cast<long long>(settings.width) * settings.height > kMaxPixels)
    throw std::runtime_error(fmt::format("--width x --height = {} x {} is more than {} pixels", settings.width,
                                         settings.height, kMaxPixels));
}

ReplayRequest parseReplay(const std::string& text, const RenderSettings& settings) {
  ReplayRequest r;
  long long x = -1, y = -1, sample = -1;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lld,%lld,%lld%c", &x, &y, &sample, &extra) != 3)
    throw std::invalid_argument(fmt::format("--replay: '{}' is not X,Y,SAMPLE", text));
  if (x < 0 || y < 0 || x >= settings.width || y >= settings.height || sample < 0)
    throw std::invalid_argument(fmt::format("--replay: pixel {},{} sample {} is outside the {} x {} image", x, y, sample,
                                            settings.width, settings.height));
  // Sample N of --light-paths auto ran at the F that passes 0 .. N-1 chose (inspect renders them).
  if (settings.lightPathsAuto && sample >= kLightPathPilotPasses)
    throw std::invalid_argument(fmt::format("--replay sample {} under --light-paths auto ran at the light subpaths the "
                                            "passes before it chose: use `pathlab inspect --light-paths auto --pixel "
                                            "{},{} --sample {}`, which renders them first",
                                            sample, x, y, sample));
  // Sample N of --mis optimal was corrected with coefficients of passes 0 .. N-1 (inspect renders them).
  if (settings.mis.heuristic == MisHeuristic::Optimal && sample >= kOptimalMisPilotPasses)
    throw std::invalid_argument(fmt::format("--replay sample {} under --mis optimal was corrected with coefficients of "
                                            "the passes before it: use `pathlab inspect --mis optimal --pixel {},{} "
                                            "--sample {}`, which renders them first",
                                            sample, x, y, sample));
  r.x = static_cast<int>(x);
  r.y = static_cast<int>(y);
  r.sample = static_cast<uint64_t>(sample);
  return r;
}

// One sample, exactly as the render computed it, technique by technique (stdout).
int runReplay(const RenderSession& session, const ReplayRequest& r) {
  printInspection(std::cout, session.settings(), inspectSample(session, r.x, r.y, r.sample), false);
  return 0;
}

}  // namespace

void addRenderEstimateOptions(CLI::App* cmd, RenderOptions& o) {
  addImageSizeOptions(cmd, o.size, {kMaxImageSide, kDefaultLongestSide});
  addEstimatorOptions(cmd, o.estimator);
  cmd->add_option("--pyramid", o.estimator.settings.pyramidLength,
                  "Also write every technique (s,t) up to this length, weighted and unweighted, and two mosaics "
                  "(rows: length, columns: s) next to the output")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_option("--technique-maps", o.techniqueMaps,
                  "Also write the technique maps up to this length next to the output: the dominant technique, "
                  "each technique's share of the image and where each cannot sample (EXR and PNG)")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_option("--variance-maps", o.varianceMaps,
                  "Also write the variance maps up to this length next to the output: each technique's variance "
                  "of a pass's estimate per pixel, and the technique with the most variance (EXR and PNG)")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_flag("--chain-density", o.chainDensity,
                "mlt: also write where the chains spent their time next to the output (OUT-chain-density.exr, 1 = "
                "an even spread, and a PNG on a log scale); the image is b times it, length by length");
  addThreadsOption(cmd, o.threads);
  cmd->add_flag("--check-mis", o.estimator.settings.checkMis,
                "Check on every path that the enabled techniques' MIS weights sum to one (on in debug builds)");
}

void finishRenderEstimate(RenderOptions& o) {
  finishEstimatorOptions(o.estimator);
  // The maps read the pyramid's films (and their sampleable parts); --pyramid still decides which
  // pyramid images are written.
  if (o.techniqueMaps > 0) {
    RenderSettings& s = o.estimator.settings;
    if (s.integrator == IntegratorKind::Pt)
      throw std::runtime_error("--technique-maps needs the bidirectional tracer (--integrator bpt or lt)");
    if (o.techniqueMaps > s.maxLength)
      throw std::runtime_error(
          fmt::format("--technique-maps {} is longer than the maximum path length {}", o.techniqueMaps, s.maxLength));
    s.pyramidLength = std::max(s.pyramidLength, o.techniqueMaps);
    s.techniqueMaps = true;
  }
  // The variance maps read the pyramid's second moments across passes.
  if (o.varianceMaps > 0) {
    RenderSettings& s = o.estimator.settings;
    if (s.integrator == IntegratorKind::Pt || s.integrator == IntegratorKind::Mlt)
      throw std::runtime_error(fmt::format("--variance-maps needs independent bidirectional samples (--integrator bpt, "
                                           "lt, vcm, bpm or ppm), not {}",
                                           integratorName(s.integrator)));
    if (o.varianceMaps > s.maxLength)
      throw std::runtime_error(
          fmt::format("--variance-maps {} is longer than the maximum path length {}", o.varianceMaps, s.maxLength));
    s.pyramidLength = std::max(s.pyramidLength, o.varianceMaps);
    s.varianceMaps = true;
  }
  // Until the camera's aspect is known, a side not given may be as large as allowed.
  RenderSettings& settings = o.estimator.settings;
  settings.width = o.size.width > 0 ? o.size.width : kMaxImageSide;
  settings.height = o.size.height > 0 ? o.size.height : kMaxImageSide;
}

void checkRequestedPixels(const RenderOptions& o) {
  if (o.size.width > 0 && o.size.height > 0) checkPixels(o.estimator.settings);
}

void sizeRenderForScene(RenderOptions& o, const CameraDesc& camera) {
  RenderSettings& settings = o.estimator.settings;
  // The image has the camera's shape, so nothing the camera frames is cropped (image_size.h).
  const Vec2i size = o.size.sizeFor(cameraAspect(settings.camera, camera), kDefaultLongestSide);
  settings.width = size.x;
  settings.height = size.y;
  checkPixels(settings);
}

void addRenderCommand(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF scene headless to an image file");
  addSceneArgument(cmd, o.scene.path);
  auto* output =
      cmd->add_option("-o,--output", o.output, "Output image: .exr and .pfm store float radiance, .png is tone mapped (sRGB)");
  cmd->add_option("--replay", o.replay,
                  "Replay sample SAMPLE of pixel X,Y with the same options and print every technique's part")
      ->excludes(output);
  addSampleBudgetOptions(cmd, o.budget,
                         {1, "Samples per pixel (default 64 when --time is not given)",
                          "Render for this many seconds of wall time instead of a sample count"});
  cmd->add_option("--mutations-per-pixel", o.mutationsPerPixel,
                  "mlt: mutations per pixel on average, over all chains (--spp's place; default 64 when --time is not "
                  "given)")
      ->check(CLI::Range(1, 1 << 24))
      ->excludes("--spp")
      ->excludes("--time");
  addRenderEstimateOptions(cmd, o);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
  cmd->add_option("--exposure", o.exposure, "Exposure in stops applied to PNG output")->check(CLI::Range(-40.f, 40.f));
  cmd->add_flag("--stats", o.stats, "Print per-technique counters: connections tried, zero, blocked, contributing, discarded, shadow rays "
                "and share of all rays, share of the timed work (connect + MIS weight; the walks too)");
  addForceFlag(cmd, o.force, "the output file if it exists");
}

namespace {

// The chains' normalisation and how they moved, after a Metropolis render: b with its standard
// error (the image's brightness is off by about b's relative error, which the large steps keep
// lowering), the acceptance over all, of large steps, and per path length.
std::string metropolisSummary(const Metropolis& m, const RenderSettings& s) {
  const MltStats& stats = m.stats();
  const double b = m.normalisation();
  const std::vector<int> chains = m.chainsByLength();
  int chainCount = 0;
  for (int n : chains) chainCount += n;
  std::string out = fmt::format(
      "mlt ({}): b = {:.6g} +- {:.2g} ({:.2f} %, from {} bootstrap samples{} and the large steps), {} chains; "
      "{} proposals, {:.1f} % accepted, large steps {:.1f} % of them and {:.1f} % accepted\n",
      mltVariantName(s.mlt.variant), b, m.normalisationError(), b > 0 ? 100.0 * m.normalisationError() / b : 0.0,
      s.mlt.bootstrap, s.mlt.variant == MltVariant::Multiplexed ? " per length" : "", chainCount, stats.proposed,
      100.0 * stats.acceptance(),
      stats.proposed ? 100.0 * static_cast<double>(stats.largeProposed) / static_cast<double>(stats.proposed) : 0.0,
      stats.largeProposed ? 100.0 * static_cast<double>(stats.largeAccepted) / static_cast<double>(stats.largeProposed)
                          : 0.0);
  // (Not m.summary(), which also computes the chains' density image.)
  const int directLength = m.directSamples() > 0 ? s.mlt.directLength : 0;
  if (directLength > 0)
    out += fmt::format("  paths of up to {} edges by BPT beside the chains: {} samples per pixel\n", directLength,
                       m.directSamples());
  if (s.mlt.variant == MltVariant::Multiplexed) {
    out += "  length  chains  acceptance\n";
    for (size_t k = 1; k < chains.size(); ++k) {
      if (static_cast<int>(k) <= directLength) {
        out += fmt::format("  {:>6}  {:>6}  {:>11}\n", k, "BPT", "-");
        continue;
      }
      const uint64_t p = k < stats.proposedByLength.size() ? stats.proposedByLength[k] : 0;
      const uint64_t a = k < stats.acceptedByLength.size() ? stats.acceptedByLength[k] : 0;
      out += fmt::format("  {:>6}  {:>6}  {:>9.1f} %\n", k, chains[k], p ? 100.0 * static_cast<double>(a) / static_cast<double>(p) : 0.0);
    }
  }
  return out;
}

// The per-technique files of these families (pyramid, technique and variance maps) are new or
// --force'd.
void checkTechniqueOutputs(const RenderOptions& o, int pyramidOutput, TechniqueFamilies families) {
  if (pyramidOutput > 0)
    for (const std::string& path : pyramidPaths(o.output, pyramidOutput, families)) checkOutput(path, o.force);
  if (o.techniqueMaps > 0)
    for (const std::string& path : techniqueMapPaths(o.output, o.techniqueMaps, families)) checkOutput(path, o.force);
  if (o.varianceMaps > 0)
    for (const std::string& path : varianceMapPaths(o.output, o.varianceMaps, families)) checkOutput(path, o.force);
}

// Everything a render needs before its first pass.
struct PreparedRender {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<RenderSession> session;
  std::optional<ReplayRequest> replay;
  int pyramidOutput = 0;
};

// Options checked, outputs checked (by the leader, which alone writes them), the scene loaded and
// the session built: every failure before the first pass happens here, on any rank.
PreparedRender prepareRender(RenderOptions& o, const Job& job) {
  std::ostream& log = job.log();
  PreparedRender p;
  // --pyramid decides which pyramid images are written; the technique maps may keep a longer one.
  p.pyramidOutput = o.estimator.settings.pyramidLength;
  finishRenderEstimate(o);
  RenderSettings& settings = o.estimator.settings;
  // A Metropolis pass is one mutation per pixel on average: --mutations-per-pixel counts them.
  if (o.mutationsPerPixel > 0) {
    if (settings.integrator != IntegratorKind::Mlt)
      throw std::runtime_error(fmt::format("--mutations-per-pixel applies to --integrator mlt, not {} (use --spp)",
                                           integratorName(settings.integrator)));
    o.budget.spp = o.mutationsPerPixel;
  }
  if (o.chainDensity && settings.integrator != IntegratorKind::Mlt)
    throw std::runtime_error(fmt::format("--chain-density shows the Metropolis chains: use it with --integrator mlt, "
                                         "not {}",
                                         integratorName(settings.integrator)));
  if (settings.integrator == IntegratorKind::Mlt && !o.replay.empty())
    throw std::runtime_error("--replay replays one independent sample: a Metropolis chain's mutations are not (use bpt)");
  if (o.output.empty() && o.replay.empty())
    throw std::runtime_error("render needs an output image (-o OUT) or --replay X,Y,SAMPLE");
  if (!o.replay.empty() && job.size() > 1)
    throw std::runtime_error("--replay recomputes one sample: run it as one process, without mpirun");
  // Each rank renders every N-th pass: its factors would come from its own passes only.
  if (settings.mis.heuristic == MisHeuristic::VarianceAware && job.size() > 1)
    throw std::runtime_error("--mis variance-aware estimates its factors from one process's passes: run it as one "
                             "process, without mpirun");
  if (settings.mis.heuristic == MisHeuristic::Optimal && job.size() > 1)
    throw std::runtime_error("--mis optimal estimates its coefficients from one process's passes: run it as one "
                             "process, without mpirun");
  if (settings.lightPathsAuto && job.size() > 1)
    throw std::runtime_error("--light-paths auto chooses from one process's passes: run it as one process, without "
                             "mpirun");
  // A too large --width x --height is refused before any work.
  checkRequestedPixels(o);
  if (settings.integrator != IntegratorKind::Pt) {
    const TechniqueSet techniques = enabledTechniques(settings);
    for (int k : techniques.uncoveredLengths(settings.maxLength))
      log << fmt::format("pathlab: warning: no enabled technique samples paths of length {}\n", k);
    if (settings.isolate && !settings.isolate->unweighted && !techniques.contains(settings.isolate->technique()))
      log << fmt::format("pathlab: warning: technique {} is not enabled, so its weighted share is zero\n",
                         techniqueLabel(settings.isolate->technique()));
  }
  if (!o.replay.empty()) p.replay = parseReplay(o.replay, settings);
  if (!p.replay && job.leader()) {
    checkOutput(o.output, o.force);
    checkTechniqueOutputs(o, p.pyramidOutput, without(TechniqueFamilies::Connections | enabledTechniques(settings).families(),
                                                      TechniqueFamilies::Equiangular));
    if (o.chainDensity)
      for (const char* ext : {".exr", ".png"}) checkOutput(besideOutput(o.output, std::string("-chain-density") + ext), o.force);
  }

  const auto loadStart = std::chrono::steady_clock::now();
  p.scene = std::make_unique<Scene>(readScene(o.scene));
  const Scene& scene = *p.scene;
  sizeRenderForScene(o, scene.cameraDesc());
  if (p.replay) p.replay = parseReplay(o.replay, settings);
  printWarnings(log, scene, settings);
  // The equiangular techniques' outputs once the scene says they are sampled (a medium they can
  // sample); the others' were checked before loading it.
  if (!p.replay && job.leader() && covers(pyramidFamilies(settings, scene), TechniqueKind::Equiangular))
    checkTechniqueOutputs(o, p.pyramidOutput, TechniqueFamilies::Equiangular);
  const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
  // This rank's share of the passes (Job::passSchedule): all of them for one process. Before the
  // summary line: settings the scene's camera refuses (light tracing through an orthographic
  // camera) are then the only line.
  p.session = std::make_unique<RenderSession>(scene, settings, job.passSchedule());
  log << fmt::format("{}: {} triangles, {} lights, {:.1f} MB of geometry, loaded in {:.2f} s\n", o.scene.path,
                     scene.triangleCount(), scene.lights().size(), double(scene.geometryBytes()) / 1e6, loadSeconds);
  return p;
}

}  // namespace

int runRender(RenderOptions o, Job& job) {
  const ThreadLimit threadLimit(o.threads);
  // Every rank prepares, then all agree before the first collective of the render (a rank that
  // could not build its film stops the job too).
  PreparedRender prepared = prepareOnEveryRank<PreparedRender>(
      job, [&] { return prepareRender(o, job); },
      [](PreparedRender& p) { return p.session ? shapeOf(*p.session) : uint64_t{0}; });
  RenderSession& session = *prepared.session;
  const RenderSettings& settings = session.settings();
  if (prepared.replay) return runReplay(session, *prepared.replay);

  session.setTiming(o.stats);  // two clock reads a connection: only when the shares are printed
  const bool timed = o.budget.seconds > 0.0;
  const uint64_t targetSpp = timed ? 0 : static_cast<uint64_t>(o.budget.spp > 0 ? o.budget.spp : kDefaultSpp);
  // Metropolis over ranks: every rank runs every pass with its share of the chains, after the
  // ranks' bootstrap samples are pooled (the first pass's collective).
  const bool metropolis = session.metropolis() != nullptr;
  if (metropolis) session.metropolis()->setBootstrapExchange([&job](std::span<double> w) { job.sumEverywhere(w); });
  const uint64_t ranks = static_cast<uint64_t>(job.size());
  // --spp is the job's: this rank renders its share of the pass indices below it (Metropolis: all
  // of them); --time holds for every rank (each starts its clock as the agreement returns).
  const uint64_t ownPasses = metropolis ? targetSpp : job.passesOf(targetSpp);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  JobTotals totals;
  {
    // One progress bar for the whole job, on the leader: the passes of every rank it has heard of.
    const double pixels = static_cast<double>(session.film().pixelCount());
    std::optional<ProgressBar> bar;
    if (job.leader())
      bar.emplace([&] {
        const double passFraction = static_cast<double>(session.pixelsDoneInPass()) / pixels;
        const uint64_t passes = metropolis ? job.jobPasses() / ranks : job.jobPasses();
        const double done = timed ? elapsed() / o.budget.seconds
                                  : (static_cast<double>(passes) + passFraction) / static_cast<double>(targetSpp);
        return std::pair{done, fmt::format("{} spp  {:.1f} s", passes, elapsed())};
      });
    while (timed ? (session.passes() == 0 || elapsed() < o.budget.seconds) : session.passes() < ownPasses) {
      session.renderPass();
      job.notePasses(session.passes());
    }
    totals = job.combine(session, elapsed());
  }
  if (!job.leader()) return 0;
  const double seconds = totals.slowestSeconds;
  // A Metropolis pass is one mutation a pixel of the job's, each rank running its chains' share.
  const uint64_t jobSpp = metropolis ? (totals.passes + ranks / 2) / ranks : totals.passes;
  writeImage(o.output, session.image(), o.exposure);
  if (prepared.pyramidOutput > 0) writePyramid(o.output, session, o.exposure, prepared.pyramidOutput);
  if (o.techniqueMaps > 0) writeTechniqueMaps(o.output, session, o.techniqueMaps);
  if (o.varianceMaps > 0) writeVarianceMaps(o.output, session, o.varianceMaps);
  if (o.chainDensity) {
    // Every rank's chains' (their histograms were added): the values, and viridis on a log scale.
    const Metropolis& m = *session.metropolis();
    std::vector<float> density = m.chainDensity();
    density.resize(session.film().pixelCount(), 0.f);  // no chains (every length by BPT): zero
    writeImage(besideOutput(o.output, "-chain-density.exr"), grey(density, settings.width, settings.height));
    writeImage(besideOutput(o.output, "-chain-density.png"),
               displayToLinear(densityColours(density, settings.width, settings.height)));
  }

  // Under MPI: every rank's samples, rays and discards, over the slowest rank's time.
  const Counters& c = session.counters();
  std::cerr << fmt::format(
      "{}: {} spp ({}{}) in {:.2f} s, {} samples/s, {} rays/s, {} discarded samples (NaN {}, Inf {}, negative {})\n",
      o.output, jobSpp, integratorName(settings.integrator),
      job.size() > 1 ? fmt::format(", {} ranks", job.size()) : "", seconds,
      humanCount(static_cast<double>(c.cameraSamples) / seconds), humanCount(static_cast<double>(c.totalRays()) / seconds),
      c.discarded(), c.discardedCounts().nan, c.discardedCounts().inf, c.discardedCounts().negative);
  if (job.size() > 1)
    std::cerr << fmt::format("{} ranks: their sums were added into rank 0 in {:.3f} s\n",
                             job.size(), totals.reduceSeconds);
  if (settings.integrator != IntegratorKind::Pt) printTechniqueCounters(c, settings.maxLength, seconds, o.stats);
  if (const Metropolis* m = session.metropolis()) std::cerr << metropolisSummary(*m, settings);
  if (const LightPathChoice* choice = session.lightPathChoice()) std::cerr << choice->summary();
  if (settings.checkMis)
    std::cerr << fmt::format("MIS check: {} of {} paths whose weights do not sum to one\n", c.misPartitionFailures,
                             c.misPartitionChecks);
  for (size_t i = 0; i < c.discardExampleCount; ++i) {
    const DiscardExample& e = c.discardExamples[i];
    std::cerr << fmt::format("discarded ({:g}, {:g}, {:g}) at pixel {},{} sample {}{}: rerun with the same options and "
                             "--replay {},{},{}\n",
                             e.value.r, e.value.g, e.value.b, e.x, e.y, e.sample,
                             e.s >= 0 ? fmt::format(" technique ({},{})", e.s, e.t) : std::string(), e.x, e.y, e.sample);
  }
  return 0;
}

}  // namespace pathlab::app
