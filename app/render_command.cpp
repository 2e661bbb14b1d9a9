// `pathlab render`: load, check every option before any work, render passes until the sample or
// time budget is spent, write the image atomically, print a summary.
#include "app/render_command.h"

#include "app/output_check.h"
#include "app/progress.h"
#include "app/pyramid_output.h"
#include "app/technique_maps_output.h"
#include "core/camera/image_size.h"
#include "core/film/image_io.h"
#include "core/metrics/technique_table.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <thread>
#include <unistd.h>

namespace pathlab::app {

namespace {

constexpr int kMaxImageSide = 16384;
constexpr long long kMaxPixels = 64LL * 1024 * 1024;
constexpr int kMaxSpp = 1 << 24;
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
  throw std::runtime_error(output + ": file exists (pass --force to overwrite it)");
}

std::string humanCount(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f}M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
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

ReplayRequest parseReplay(const std::string& text, const RenderSettings& settings) {
  ReplayRequest r;
  long long x = -1, y = -1, sample = -1;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%lld,%lld,%lld%c", &x, &y, &sample, &extra) != 3)
    throw std::invalid_argument(fmt::format("--replay: '{}' is not X,Y,SAMPLE", text));
  if (x < 0 || y < 0 || x >= settings.width || y >= settings.height || sample < 0)
    throw std::invalid_argument(fmt::format("--replay: pixel {},{} sample {} is outside the {} x {} image", x, y, sample,
                                            settings.width, settings.height));
  r.x = static_cast<int>(x);
  r.y = static_cast<int>(y);
  r.sample = static_cast<uint64_t>(sample);
  return r;
}

// The path a technique formed, under every technique of its length (the seed's "one path, every
// technique"): the density each would sample it with, the edge it connects, its weights.
void printTechniquesOnPath(const std::vector<TechniqueOnPath>& every) {
  if (every.empty()) return;
  std::cout << fmt::format("{:>12}  this path under every technique: {:>11} {:>9} {:>9} {:>9}  {}\n", "", "p_A(x)",
                           "balance", "power", "uniform", "connects");
  for (const TechniqueOnPath& x : every) {
    const std::string name = fmt::format("({},{})", x.s, x.t);
    const std::string edge = x.connectionEdge < 0 ? std::string("nothing: hits the emitter")
                                                  : fmt::format("x{}-x{}", x.connectionEdge, x.connectionEdge + 1);
    if (!x.possible) {
      const std::string why = x.connectionEdge < 0
                                  ? std::string("its emitter cannot be hit by a ray (point, spot, directional light)")
                                  : fmt::format("x{} or x{} scatters by a delta lobe", x.connectionEdge, x.connectionEdge + 1);
      std::cout << fmt::format("{:>12}  {:>32} {:>11}  cannot: {}\n", "", name, "0", why);
      continue;
    }
    std::cout << fmt::format("{:>12}  {:>32} {:>11.4e} {:>9.4f} {:>9.4f} {:>9.4f}  {}{}\n", "", name, x.pdfA,
                             x.balance, x.power, x.uniform, edge, x.enabled ? "" : "  (disabled)");
  }
}

// One sample, exactly as the render computed it, technique by technique (stdout).
int runReplay(const RenderSession& session, const ReplayRequest& r) {
  Counters counters;
  SampleTrace trace;
  Film splats(session.settings().width, session.settings().height);
  const Spectrum L = session.replaySample(r.x, r.y, r.sample, counters, &splats, &trace);
  std::cout << fmt::format("pixel {},{} sample {} ({}): camera-side estimate ({:g}, {:g}, {:g})\n", r.x, r.y, r.sample,
                           integratorName(session.settings().integrator), L.r, L.g, L.b);
  if (session.settings().integrator == IntegratorKind::Pt) return 0;
  std::cout << fmt::format("camera subpath {} vertices, light subpath {} vertices\n", trace.cameraVertices,
                           trace.lightVertices);
  std::cout << fmt::format("{:>8} {:>36} {:>10} {:>36} {:>16} {}\n", "(s,t)", "unweighted", "weight", "weighted",
                           "raster", "");
  for (size_t i = 0; i < trace.records.size(); ++i) {
    const TechniqueResult& t = trace.records[i];
    const Spectrum w = t.unweighted * t.weight;
    std::cout << fmt::format("{:>8} {:>36} {:>10.4g} {:>36} {:>16} {}\n", fmt::format("({},{})", t.s, t.t),
                             fmt::format("({:.4g}, {:.4g}, {:.4g})", t.unweighted.r, t.unweighted.g, t.unweighted.b),
                             t.weight, fmt::format("({:.4g}, {:.4g}, {:.4g})", w.r, w.g, w.b),
                             fmt::format("{:.1f},{:.1f}", t.pRaster.x, t.pRaster.y),
                             t.blocked() ? "blocked" : isBlack(t.unweighted) ? "zero" : t.inImage ? "" : "not in the image");
    if (i < trace.onPath.size()) printTechniquesOnPath(trace.onPath[i]);
  }
  return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF scene headless to an image file");
  cmd->add_option("scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  auto* output =
      cmd->add_option("-o,--output", o.output, "Output image: .exr and .pfm store float radiance, .png is tone mapped (sRGB)");
  cmd->add_option("--replay", o.replay,
                  "Replay sample SAMPLE of pixel X,Y with the same options and print every technique's part")
      ->excludes(output);
  auto* spp = cmd->add_option("--spp", o.spp, "Samples per pixel (default 64 when --time is not given)")
                  ->check(CLI::Range(1, kMaxSpp));
  cmd->add_option("--time", o.seconds, "Render for this many seconds of wall time instead of a sample count")
      ->check(CLI::Range(0.001, 7.0 * 24 * 3600))
      ->excludes(spp);
  cmd->add_option("--width", o.width, "Image width in pixels (default: the camera's aspect, longest side 512)")
      ->check(CLI::Range(1, kMaxImageSide));
  cmd->add_option("--height", o.height, "Image height in pixels (default: the camera's aspect, longest side 512)")
      ->check(CLI::Range(1, kMaxImageSide));
  addEstimatorOptions(cmd, o.estimator);
  cmd->add_option("--pyramid", o.estimator.settings.pyramidLength,
                  "Also write every technique (s,t) up to this length, weighted and unweighted, and two mosaics "
                  "(rows: length, columns: s) next to the output")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_option("--technique-maps", o.techniqueMaps,
                  "Also write the technique maps up to this length next to the output: the dominant technique, "
                  "each technique's share of the image and where each cannot sample (EXR and PNG)")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_option("--threads", o.threads, "Worker threads (0: all hardware threads)")->check(CLI::Range(0, 1024));
  cmd->add_option("--max-triangles", o.load.maxTriangles, "Refuse scenes that instance more triangles than this")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  addEnvironmentOptions(cmd, o.environment);
  cmd->add_option("--exposure", o.exposure, "Exposure in stops applied to PNG output")->check(CLI::Range(-40.f, 40.f));
  cmd->add_flag("--check-mis", o.estimator.settings.checkMis,
                "Check on every path that the enabled techniques' MIS weights sum to one (on in debug builds)");
  cmd->add_flag("--stats", o.stats, "Print per-technique counters: connections tried, zero, blocked, contributing, discarded, shadow rays "
                "and share of all rays, share of the timed work (connect + MIS weight; the walks too)");
  cmd->add_flag("-f,--force", o.force, "Overwrite the output file if it exists");
}

int runRender(RenderOptions o) {
  finishEstimatorOptions(o.estimator);
  // The maps read the pyramid's films (and their sampleable parts); --pyramid still decides which
  // pyramid images are written.
  const int pyramidOutput = o.estimator.settings.pyramidLength;
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
  RenderSettings& settings = o.estimator.settings;
  if (o.output.empty() && o.replay.empty())
    throw std::runtime_error("render needs an output image (-o OUT) or --replay X,Y,SAMPLE");
  // Until the camera's aspect is known, a side not given may be as large as allowed: the syntax of
  // --replay and a too large --width x --height are still refused before any work.
  settings.width = o.width > 0 ? o.width : kMaxImageSide;
  settings.height = o.height > 0 ? o.height : kMaxImageSide;
  auto checkPixels = [&] {
    if (static_cast<long long>(settings.width) * settings.height > kMaxPixels)
      throw std::runtime_error(fmt::format("--width x --height = {} x {} is more than {} pixels", settings.width,
                                           settings.height, kMaxPixels));
  };
  if (o.width > 0 && o.height > 0) checkPixels();
  if (settings.integrator != IntegratorKind::Pt) {
    const TechniqueSet techniques = enabledTechniques(settings);
    for (int k : techniques.uncoveredLengths(settings.maxLength))
      std::cerr << fmt::format("pathlab: warning: no enabled technique samples paths of length {}\n", k);
    if (settings.isolate && !settings.isolate->unweighted &&
        !techniques.contains(settings.isolate->s, settings.isolate->t))
      std::cerr << fmt::format("pathlab: warning: technique ({},{}) is not enabled, so its weighted share is zero\n",
                               settings.isolate->s, settings.isolate->t);
  }
  std::optional<ReplayRequest> replay;
  if (!o.replay.empty()) replay = parseReplay(o.replay, settings);
  if (!replay) checkOutput(o.output, o.force);
  if (!replay && pyramidOutput > 0)
    for (const std::string& path : pyramidPaths(o.output, pyramidOutput)) checkOutput(path, o.force);
  if (!replay && o.techniqueMaps > 0)
    for (const std::string& path : techniqueMapPaths(o.output, o.techniqueMaps)) checkOutput(path, o.force);
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  const auto loadStart = std::chrono::steady_clock::now();
  finishEnvironmentOptions(o.environment, o.load);
  Scene scene(loadGltf(o.scene, o.load));
  // The image has the camera's shape, so nothing the camera frames is cropped (image_size.h).
  const Vec2i size = imageSizeForAspect(cameraAspect(settings.camera, scene.cameraDesc()),
                                        o.width > 0 ? std::optional(o.width) : std::nullopt,
                                        o.height > 0 ? std::optional(o.height) : std::nullopt);
  settings.width = size.x;
  settings.height = size.y;
  checkPixels();
  if (replay) replay = parseReplay(o.replay, settings);
  for (const std::string& w : scene.warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  if (const std::string w = misOffWarning(scene, settings); !w.empty()) std::cerr << "pathlab: warning: " << w << "\n";
  if (const std::string w = biasInjectionWarning(settings); !w.empty()) std::cerr << "pathlab: warning: " << w << "\n";
  const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
  std::cerr << fmt::format("{}: {} triangles, {} lights, {:.1f} MB of geometry, loaded in {:.2f} s\n", o.scene,
                           scene.triangleCount(), scene.lights().size(), double(scene.geometryBytes()) / 1e6,
                           loadSeconds);

  RenderSession session(scene, settings);
  if (replay) return runReplay(session, *replay);
  session.setTiming(o.stats);  // two clock reads a connection: only when the shares are printed
  const bool timed = o.seconds > 0.0;
  const uint64_t targetSpp = timed ? 0 : static_cast<uint64_t>(o.spp > 0 ? o.spp : kDefaultSpp);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  {
    const double pixels = static_cast<double>(session.film().pixelCount());
    ProgressBar bar([&] {
      const double passFraction = static_cast<double>(session.pixelsDoneInPass()) / pixels;
      const double done = timed ? elapsed() / o.seconds
                                : (static_cast<double>(session.passes()) + passFraction) / static_cast<double>(targetSpp);
      return std::pair{done, fmt::format("{} spp  {:.1f} s", session.passes(), elapsed())};
    });
    while (timed ? (session.passes() == 0 || elapsed() < o.seconds) : session.passes() < targetSpp)
      session.renderPass();
  }
  const double seconds = elapsed();
  writeImage(o.output, session.image(), o.exposure);
  if (pyramidOutput > 0) writePyramid(o.output, session, o.exposure, pyramidOutput);
  if (o.techniqueMaps > 0) writeTechniqueMaps(o.output, session, o.techniqueMaps);

  const Counters& c = session.counters();
  std::cerr << fmt::format(
      "{}: {} spp ({}) in {:.2f} s, {} samples/s, {} rays/s, {} discarded samples (NaN {}, Inf {}, negative {})\n",
      o.output, session.passes(), integratorName(settings.integrator), seconds,
      humanCount(static_cast<double>(c.cameraSamples) / seconds), humanCount(static_cast<double>(c.totalRays()) / seconds),
      c.discarded(), c.discardedCounts().nan, c.discardedCounts().inf, c.discardedCounts().negative);
  if (settings.integrator != IntegratorKind::Pt) printTechniqueCounters(c, settings.maxLength, seconds, o.stats);
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
