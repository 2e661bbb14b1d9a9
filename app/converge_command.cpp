// `pathlab converge`: every option checked before any work, the reference loaded or rendered (and
// cached by hash), the configurations rendered one after another, the results written.
#include "app/converge_command.h"

#include "app/job.h"
#include "app/output_check.h"
#include "app/progress.h"
#include "core/camera/image_size.h"
#include "core/bpt/bidir_tracer.h"
#include "core/converge/convergence.h"
#include "core/converge/convergence_report.h"
#include "core/converge/reference_key.h"
#include "core/film/image_io.h"
#include "core/io/text_file.h"
#include "core/metrics/loglog_plot.h"
#include "core/scene/gltf_loader.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

namespace pathlab::app {

namespace fs = std::filesystem;

namespace {

constexpr int kDefaultSide = 256;
constexpr double kDefaultConvergeSeconds = 10.0;
constexpr int kReferenceFactor = 10;
constexpr const char* kOutputs[] = {"convergence.csv", "convergence.svg", "efficiency.md"};

// The reference must not share random streams with the configurations it judges (the bpt
// configuration would otherwise repeat the reference's first passes exactly and look too good):
// its seed is offset by an odd 64-bit constant (the golden ratio's bits).
constexpr uint64_t kReferenceSeedOffset = 0x9E3779B97F4A7C15ull;

// Before any work: the directory can be created or written (so can the cached reference), and
// each result can be written into it.
void checkOutputDir(const ConvergeOptions& o) {
  checkOutputDirectory(o.outputDir);
  const fs::path dir(o.outputDir);
  if (!fs::is_directory(dir)) return;
  for (const char* name : kOutputs) {
    const fs::path path = dir / name;
    checkOutputWritable(path.string());
    if (!o.force && fs::exists(path))
      throw std::runtime_error(path.string() + ": file exists (pass --force to overwrite the results in " + o.outputDir +
                               ")");
  }
}

// Runs one configuration on every rank of the job, with a progress bar on the leader's stderr.
ConvergenceCurve runWithProgress(const Scene& scene, const ConvergenceConfig& config, const Image* reference,
                                 const ConvergenceBudget& budget, Job& job, CheckpointExchange& exchange,
                                 const PixelMask& mask = {}) {
  std::atomic<uint64_t> passes{0};
  const auto start = std::chrono::steady_clock::now();
  std::optional<ProgressBar> bar;
  if (job.leader())
    bar.emplace([&] {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const uint64_t n = passes.load(std::memory_order_relaxed);
      const double done = budget.seconds > 0 ? elapsed / budget.seconds
                                             : static_cast<double>(n) / static_cast<double>(job.passesOf(budget.spp));
      // Between checkpoints the leader knows only its own passes.
      return std::pair{done, fmt::format("{}: {} spp{}", config.label, n,
                                         job.size() > 1 ? fmt::format(" on rank 0 of {}", job.size()) : "")};
    });
  return runConvergence(scene, config, reference, budget, {}, &passes, &exchange, mask);
}

// Under MPI: every rank's samples and rays over the slowest rank's time.
void printSummary(const ConvergenceCurve& curve) {
  const Checkpoint& c = curve.checkpoints.back();
  std::string error = c.error ? fmt::format("relMSE {:.4g}, ", c.error->relMse) : "";
  const std::string twoBuffer =
      std::isfinite(c.twoBuffer.relMse) ? fmt::format("two-buffer relMSE {:.4g}, ", c.twoBuffer.relMse) : "";
  std::cerr << fmt::format("{}: {} spp{} in {:.2f} s, {}{}{} samples/s, {} rays/s\n", curve.label,
                           c.spp, curve.processes > 1 ? fmt::format(" ({} ranks)", curve.processes) : "", c.seconds,
                           error, twoBuffer,
                           humanCount(static_cast<double>(c.cameraSamples) / c.seconds),
                           humanCount(static_cast<double>(c.rays) / c.seconds));
}

}  // namespace

void addConvergeCommand(CLI::App& app, ConvergeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "converge", "Render several configurations for the same time, record their error against a reference, "
                  "and write convergence.csv, convergence.svg (log-log relMSE against time) and efficiency.md");
  addSceneArgument(cmd, o.scene.path);
  cmd->add_option("-o,--output", o.outputDir, "Output directory (created if missing)")->required();
  auto* reference = cmd->add_option("--reference", o.reference,
                  "Reference image (.exr or .pfm); without it one is rendered with bpt (balance heuristic) and "
                  "cached in the output directory as reference-<hash>.exr");
  cmd->add_option("--configs", o.configs,
                  "';'-separated configurations INTEGRATOR[:key=value,...], keys mis, beta, min-connection, techniques, max-length "
                  "(e.g. \"bpt;pt;lt;bpt:mis=power;bpt:techniques=s=1;k=1\")")
      ->capture_default_str();
  addSampleBudgetOptions(cmd, o.budget,
                         {2, "Render each configuration for this many samples per pixel",
                          "Render each configuration for this many seconds (default 10)"});
  auto* refSpp = cmd->add_option("--reference-spp", o.referenceSpp, "Samples per pixel of a rendered reference")
                     ->check(CLI::Range(2, kMaxSpp));
  auto* refTime = cmd->add_option("--reference-time", o.referenceSeconds,
                                   "Seconds of a rendered reference (default 10 times the per-configuration budget)")
                      ->check(CLI::Range(0.001, 30.0 * 24 * 3600))
                      ->excludes(refSpp);
  reference->excludes(refSpp)->excludes(refTime);
  cmd->add_option("--mask", o.mask,
                  "Measure the error only where this image (.exr or .pfm, of the images' size) is at least "
                  "--mask-threshold in some channel: a region such as a caustic (e.g. the merges' share map of "
                  "render --technique-maps)");
  cmd->add_option("--mask-threshold", o.maskThreshold, "The value from which a --mask pixel counts")
      ->check(CLI::Range(1e-6, 1e6))
      ->capture_default_str();
  cmd->add_option("--checkpoint-factor", o.checkpointFactor,
                  "Checkpoints are spaced geometrically in time (or spp) by this factor")
      ->check(CLI::Range(1.01, 100.0))
      ->capture_default_str();
  cmd->add_option("--clock", o.clock,
                  "Clock of --time, the CSV, the plot and the table: wall, or cpu (the process's CPU time: fair "
                  "on a loaded machine; use it with --threads 1)")
      ->check(CLI::IsMember({"wall", "cpu"}))
      ->capture_default_str();
  addImageSizeOptions(cmd, o.size, {kMaxImageSide, kDefaultSide, "the reference's, or "});
  cmd->add_option("--max-length", o.maxLength, "Maximum path length in edges (a configuration may override it)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--rr,!--no-rr", o.russianRoulette, "Russian roulette from the second scattering on, delta bounces always continued (default on)");
  cmd->add_option("--seed", o.seed, "Seed of every configuration's random streams");
  addThreadsOption(cmd, o.threads);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
  addForceFlag(cmd, o.force, "convergence.csv, convergence.svg and efficiency.md");
}

namespace {

// The reference rendered when none is given: bpt with the balance heuristic, for --reference-time
// or --reference-spp if given, else ten times the budget of a configuration.
struct ReferenceRun {
  ConvergenceConfig config;
  ConvergenceBudget budget;
  std::string budgetText;  // in the cache key and the table's note
};

ReferenceRun referenceRun(const ConvergeOptions& o, const RenderSettings& base, const ConvergenceBudget& budget) {
  ReferenceRun r{{"reference (bpt, balance)", base}, {}, {}};
  r.config.settings.integrator = IntegratorKind::Bpt;
  r.config.settings.seed = base.seed + kReferenceSeedOffset;
  r.budget.factor = 1e9;  // only the first and last checkpoints
  r.budget.clock = budget.clock;
  if (o.referenceSpp > 0 || (o.referenceSeconds <= 0 && budget.spp > 0)) {
    r.budget.spp = o.referenceSpp > 0 ? static_cast<uint64_t>(o.referenceSpp) : kReferenceFactor * budget.spp;
    r.budgetText = fmt::format("spp={}", r.budget.spp);
  } else {
    r.budget.seconds = o.referenceSeconds > 0 ? o.referenceSeconds : kReferenceFactor * budget.seconds;
    r.budgetText = fmt::format("{}={}", budget.clock == ClockKind::Cpu ? "cputime" : "time", r.budget.seconds);
  }
  return r;
}

// The cached reference of these settings; the environment lights the reference too, so one
// rendered under another is not reused.
fs::path cachedReferencePath(const ConvergeOptions& o, const ReferenceRun& r) {
  const std::string key =
      referenceKey(o.scene.path, r.config.settings, r.budgetText + environmentKeyText(o.scene.load));
  return fs::path(o.outputDir) / fmt::format("reference-{}.exr", key);
}

// Everything before the first pass. The outputs and the reference are the leader's alone: it
// checks the directory and reads a given or cached reference.
struct PreparedConverge {
  RenderSettings base;
  std::vector<ConvergenceConfig> configs;
  ConvergenceBudget budget;
  std::unique_ptr<Scene> scene;
  Image reference;  // given, or cached (the leader's)
  PixelMask mask;   // --mask (the leader's; empty: every pixel)
};

// --mask: the pixels whose largest channel is at least `threshold`, in an image of the render's size.
PixelMask readMask(const std::string& path, double threshold, int width, int height) {
  const Image image = readImage(path);
  if (image.width != width || image.height != height)
    throw std::runtime_error(fmt::format("{}: the mask is {} x {}, the images {} x {}", path, image.width, image.height,
                                         width, height));
  PixelMask mask(static_cast<size_t>(width) * static_cast<size_t>(height));
  size_t count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const float v = std::max({image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]});
    mask[i] = v >= threshold ? 1 : 0;  // NaN counts as outside
    count += mask[i];
  }
  if (count == 0)
    throw std::runtime_error(fmt::format("{}: the mask selects no pixel (none at {:g} or more)", path, threshold));
  return mask;
}

void setImageSize(PreparedConverge& p, int width, int height) {
  p.base.width = width;
  p.base.height = height;
  for (ConvergenceConfig& c : p.configs) {
    c.settings.width = width;
    c.settings.height = height;
  }
}

PreparedConverge prepareConverge(ConvergeOptions& o, const Job& job) {
  std::ostream& log = job.log();
  // Every check before any work: configurations, output directory, reference, budget.
  PreparedConverge p;
  p.base.maxLength = o.maxLength;
  p.base.russianRoulette = o.russianRoulette;
  p.base.seed = o.seed;
  p.base.width = o.size.width > 0 ? o.size.width : kDefaultSide;
  p.base.height = o.size.height > 0 ? o.size.height : kDefaultSide;
  if (static_cast<long long>(p.base.width) * p.base.height > 16LL * 1024 * 1024)
    throw std::runtime_error(
        fmt::format("--width x --height = {} x {} is more than 16M pixels", p.base.width, p.base.height));
  p.configs = parseConvergenceConfigs(o.configs, p.base);
  for (const ConvergenceConfig& c : p.configs)
    if (c.settings.integrator == IntegratorKind::Mlt && job.size() > 1)
      throw std::runtime_error(fmt::format("configuration '{}': Metropolis runs over MPI ranks in `pathlab render` "
                                           "only; run this convergence as one process, without mpirun",
                                           c.label));
    else if (c.settings.mis.heuristic == MisHeuristic::VarianceAware && job.size() > 1)
      throw std::runtime_error(fmt::format("configuration '{}': variance-aware MIS estimates its factors from one "
                                           "process's passes; run this convergence as one process, without mpirun",
                                           c.label));
    else if (c.settings.mis.heuristic == MisHeuristic::Optimal && job.size() > 1)
      throw std::runtime_error(fmt::format("configuration '{}': optimal MIS estimates its coefficients from one "
                                           "process's passes; run this convergence as one process, without mpirun",
                                           c.label));
    else if (c.settings.lightPathsAuto && job.size() > 1)
      throw std::runtime_error(fmt::format("configuration '{}': --light-paths auto chooses from one process's "
                                           "passes; run this convergence as one process, without mpirun",
                                           c.label));
  for (const ConvergenceConfig& c : p.configs)
    if (c.settings.integrator != IntegratorKind::Pt)
      for (int k : enabledTechniques(c.settings).uncoveredLengths(c.settings.maxLength))
        log << fmt::format("pathlab: warning: '{}' has no enabled technique for paths of length {} (biased)\n", c.label,
                           k);
  if (job.leader()) checkOutputDir(o);

  if (!o.reference.empty() && job.leader()) {
    p.reference = readImage(o.reference);
    if ((o.size.width > 0 && o.size.width != p.reference.width) ||
        (o.size.height > 0 && o.size.height != p.reference.height))
      throw std::runtime_error(fmt::format("{}: the reference is {} x {}, not the {} x {} asked for", o.reference,
                                           p.reference.width, p.reference.height, p.base.width, p.base.height));
    setImageSize(p, p.reference.width, p.reference.height);
  }
  p.budget.factor = o.checkpointFactor;
  p.budget.clock = o.clock == "cpu" ? ClockKind::Cpu : ClockKind::Wall;
  if (o.budget.spp > 0) p.budget.spp = static_cast<uint64_t>(o.budget.spp);
  else p.budget.seconds = o.budget.seconds > 0 ? o.budget.seconds : kDefaultConvergeSeconds;

  p.scene = std::make_unique<Scene>(readScene(o.scene));
  if (o.reference.empty() && (o.size.width == 0 || o.size.height == 0)) {
    // As `render`: the image has the camera's shape (longest side 256 unless given), never cropped.
    const Vec2i size = o.size.sizeFor(cameraAspect(std::nullopt, p.scene->cameraDesc()), kDefaultSide);
    setImageSize(p, size.x, size.y);
  }
  for (const std::string& w : p.scene->warnings()) log << "pathlab: warning: " << w << "\n";
  // Before any rendering: a configuration the scene's camera refuses (light tracing through an
  // orthographic camera) stops the run now, not after the reference and the others.
  for (const ConvergenceConfig& c : p.configs) {
    try {
      validateSettingsForCamera(c.settings, p.scene->cameraDesc());
      validateSettingsForScene(c.settings, *p.scene);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("configuration '{}': {}", c.label, e.what()));
    }
  }
  for (const ConvergenceConfig& c : p.configs) {
    if (const std::string w = misOffWarning(*p.scene, c.settings); !w.empty())
      log << fmt::format("pathlab: warning: '{}': {}\n", c.label, w);
    if (const std::string w = mediumSamplingWarning(*p.scene, c.settings); !w.empty())
      log << fmt::format("pathlab: warning: '{}': {}\n", c.label, w);
  }
  if (job.leader() && o.reference.empty()) {
    const fs::path cached = cachedReferencePath(o, referenceRun(o, p.base, p.budget));
    if (fs::exists(cached)) p.reference = readImage(cached.string());
  }
  if (job.leader() && !o.mask.empty()) p.mask = readMask(o.mask, o.maskThreshold, p.base.width, p.base.height);
  return p;
}

}  // namespace

int runConverge(ConvergeOptions o, Job& job) {
  std::ostream& log = job.log();
  const ThreadLimit threadLimit(o.threads);
  PreparedConverge p = prepareOnEveryRank<PreparedConverge>(
      job, [&] { return prepareConverge(o, job); }, [](const PreparedConverge&) { return uint64_t{0}; });
  // The leader alone read the reference: its size, and whether one has to be rendered, are its.
  uint64_t shared[3] = {static_cast<uint64_t>(p.base.width), static_cast<uint64_t>(p.base.height),
                        p.reference.rgb.empty() ? 1u : 0u};
  job.shareLeaders(shared);
  setImageSize(p, static_cast<int>(shared[0]), static_cast<int>(shared[1]));
  const bool renderReference = shared[2] != 0;
  const Scene& scene = *p.scene;
  const ConvergenceBudget& budget = p.budget;
  const std::unique_ptr<CheckpointExchange> exchange = job.checkpointExchange();
  const fs::path dir(o.outputDir);
  // Only once every rank is ready: a refused run leaves no directory behind.
  if (job.leader()) fs::create_directories(dir);

  std::string referenceNote = fmt::format("Reference: `{}`.", o.reference);  // under the table
  if (o.reference.empty()) {
    const ReferenceRun ref = referenceRun(o, p.base, budget);
    const fs::path cached = job.leader() ? cachedReferencePath(o, ref) : fs::path();
    if (!renderReference) {
      log << fmt::format("reference: reusing {}\n", cached.string());
      referenceNote = fmt::format("Reference: `{}`, bpt (balance heuristic), {} (cached).", cached.filename().string(),
                                  ref.budgetText);
    } else {
      log << fmt::format("reference: rendering {} with bpt (balance heuristic)\n", ref.budgetText);
      const ConvergenceCurve curve = runWithProgress(scene, ref.config, nullptr, ref.budget, job, *exchange);
      if (job.leader()) {
        printSummary(curve);
        writeImage(cached.string(), curve.image);
        p.reference = curve.image;
        log << fmt::format("reference: wrote {}\n", cached.string());
        // The reference's own error adds to every relMSE measured against it: a floor, given here.
        referenceNote = fmt::format(
            "Reference: `{}`, bpt (balance heuristic), {} spp in {:.3g} s; its own two-buffer relMSE {:.3g} is a "
            "floor under every relMSE above.",
            cached.filename().string(), curve.checkpoints.back().spp, curve.checkpoints.back().seconds,
            curve.checkpoints.back().twoBuffer.relMse);
      }
    }
  }

  // The error is the leader's to compute: the other ranks render without the reference.
  const Image* reference = job.leader() ? &p.reference : nullptr;
  std::vector<ConvergenceCurve> curves;
  for (const ConvergenceConfig& c : p.configs) {
    curves.push_back(runWithProgress(scene, c, reference, budget, job, *exchange, p.mask));
    if (job.leader()) printSummary(curves.back());
  }
  if (!job.leader()) return 0;

  LogLogPlot plot;
  const bool cpu = budget.clock == ClockKind::Cpu;
  plot.title = fmt::format("{}: relative MSE against {}", fs::path(o.scene.path).filename().string(),
                           cpu ? "CPU time" : "render time");
  plot.xLabel = cpu ? "CPU time (s)" : "render time (s)";
  plot.yLabel = "relMSE";
  for (const ConvergenceCurve& curve : curves) {
    PlotSeries series{curve.label, {}};
    for (const Checkpoint& c : curve.checkpoints) series.points.emplace_back(c.seconds, c.error->relMse);
    plot.series.push_back(std::move(series));
  }
  const std::string ranksNote =
      job.size() > 1 ? fmt::format(" Each configuration rendered by {} MPI ranks together; times are the slowest rank's.",
                                   job.size())
                     : "";
  const std::string maskNote =
      p.mask.empty() ? std::string()
                     : fmt::format(" Errors measured inside the mask `{}` (values from {:g}) only: {} of the {} pixels.",
                                   o.mask, o.maskThreshold, std::count(p.mask.begin(), p.mask.end(), uint8_t{1}),
                                   p.mask.size());
  const std::string table =
      efficiencyMarkdown(efficiencyRows(curves), cpu ? "CPU time (s)" : "time (s)") + "\n" + referenceNote +
      fmt::format(" Images of {} x {} pixels.{}{}\n", p.base.width, p.base.height, ranksNote, maskNote);
  writeTextAtomically((dir / "convergence.csv").string(), convergenceCsv(curves));
  writeTextAtomically((dir / "convergence.svg").string(), renderSvg(plot));
  writeTextAtomically((dir / "efficiency.md").string(), table);
  std::cout << table;
  std::cerr << fmt::format("wrote {}, {} and {}\n", (dir / "convergence.csv").string(), (dir / "convergence.svg").string(),
                           (dir / "efficiency.md").string());
  return 0;
}

}  // namespace pathlab::app
