// `pathlab render`: load, check every option before any work, render passes until the sample or
// time budget is spent, write the image atomically, print a summary.
#include "app/render_command.h"

#include "app/progress.h"
#include "core/film/image_io.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <chrono>
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
void checkOutputWritable(const std::string& output, bool force) {
  imageFormatOf(output);  // fails early on an unknown extension
  const std::filesystem::path dir = std::filesystem::path(output).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throw std::runtime_error(output + ": the directory " + dir.string() + " does not exist");
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

}  // namespace

void addRenderCommand(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a glTF scene headless to an image file");
  cmd->add_option("scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("-o,--output", o.output, "Output image: .exr and .pfm store float radiance, .png is tone mapped (sRGB)")
      ->required();
  auto* spp = cmd->add_option("--spp", o.spp, "Samples per pixel (default 64 when --time is not given)")
                  ->check(CLI::Range(1, kMaxSpp));
  cmd->add_option("--time", o.seconds, "Render for this many seconds of wall time instead of a sample count")
      ->check(CLI::Range(0.001, 7.0 * 24 * 3600))
      ->excludes(spp);
  cmd->add_option("--width", o.settings.width, "Image width in pixels")->check(CLI::Range(1, kMaxImageSide));
  cmd->add_option("--height", o.settings.height, "Image height in pixels")->check(CLI::Range(1, kMaxImageSide));
  cmd->add_option("--max-length", o.settings.maxLength,
                  "Maximum path length in edges (1: emitters seen directly, 2: direct lighting)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--integrator", o.settings.integrator,
                  "Estimator: bpt (bidirectional, default), pt (path tracer), lt (light tracing: the t = 1 techniques)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, IntegratorKind>{{"pt", IntegratorKind::Pt}, {"bpt", IntegratorKind::Bpt},
                                                {"lt", IntegratorKind::Lt}},
          CLI::ignore_case));
  cmd->add_option("--mis", o.settings.mis.heuristic, "MIS heuristic of bpt: balance, power or uniform")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, MisHeuristic>{{"balance", MisHeuristic::Balance}, {"power", MisHeuristic::Power},
                                              {"uniform", MisHeuristic::Uniform}},
          CLI::ignore_case));
  cmd->add_option("--beta", o.settings.mis.beta, "Exponent of the power heuristic")->check(CLI::Range(0.01f, 100.f));
  cmd->add_option("--techniques", o.settings.techniques,
                  "Enabled (s,t) techniques of bpt: ';'-separated S,T | s=S | t=T | k=K | all");
  cmd->add_flag("--rr,!--no-rr", o.settings.russianRoulette,
                "Russian roulette from the third edge on (default on)");
  cmd->add_option("--threads", o.threads, "Worker threads (0: all hardware threads)")->check(CLI::Range(0, 1024));
  cmd->add_option("--seed", o.settings.seed, "Seed of every random stream (samples are keyed by seed, pixel, index)");
  cmd->add_option("--exposure", o.exposure, "Exposure in stops applied to PNG output")->check(CLI::Range(-40.f, 40.f));
  cmd->add_option("--aperture", o.settings.lens.apertureRadius, "Thin-lens aperture radius in scene units (0: pinhole)")
      ->check(CLI::Range(0.f, 1e6f));
  cmd->add_option("--focus-distance", o.settings.lens.focusDistance, "Thin-lens focus distance in scene units")
      ->check(CLI::Range(1e-6f, 1e9f));
  cmd->add_flag("-f,--force", o.force, "Overwrite the output file if it exists");
}

int runRender(const RenderOptions& o) {
  if (static_cast<long long>(o.settings.width) * o.settings.height > kMaxPixels)
    throw std::runtime_error(fmt::format("--width x --height = {} x {} is more than {} pixels", o.settings.width,
                                         o.settings.height, kMaxPixels));
  if (o.settings.integrator != IntegratorKind::Pt) {
    const TechniqueSet techniques = techniquesOf(o.settings);  // throws on a bad SPEC
    for (int k : techniques.uncoveredLengths())
      std::cerr << fmt::format("pathlab: warning: no enabled technique samples paths of length {}\n", k);
  }
  checkOutputWritable(o.output, o.force);
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  const auto loadStart = std::chrono::steady_clock::now();
  Scene scene(loadGltf(o.scene));
  for (const std::string& w : scene.warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
  std::cerr << fmt::format("{}: {} triangles, {} lights, loaded in {:.2f} s\n", o.scene, scene.triangleCount(),
                           scene.lights().size(), loadSeconds);

  RenderSession session(scene, o.settings);
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

  const Counters& c = session.counters();
  std::cerr << fmt::format(
      "{}: {} spp ({}) in {:.2f} s, {} samples/s, {} rays/s, {} discarded samples (NaN {}, Inf {}, negative {})\n",
      o.output, session.passes(), integratorName(o.settings.integrator), seconds,
      humanCount(static_cast<double>(c.cameraSamples) / seconds), humanCount(static_cast<double>(c.totalRays()) / seconds),
      c.discarded(), c.discardedNaN, c.discardedInf, c.discardedNegative);
  return 0;
}

}  // namespace pathlab::app
