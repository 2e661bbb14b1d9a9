// --environment and friends: registration and reading the map before the scene loads.
#include "app/environment_options.h"

#include "core/lights/environment_file.h"

#include <fmt/core.h>

namespace pathlab::app {

void addEnvironmentOptions(CLI::App* cmd, EnvironmentOptions& o) {
  auto* environment = cmd->add_option(
      "--environment", o.spec,
      "Light the scene with an environment: an equirectangular (lat-long) map FILE.exr or FILE.hdr, or a "
      "constant radiance R,G,B");
  cmd->add_option("--environment-strength", o.strength, "Scale the environment's radiance (default 1)")
      ->check(CLI::Range(0.f, 1e6f))
      ->needs(environment);
  cmd->add_option("--environment-rotation", o.rotationDegrees,
                  "Turn the environment about the vertical (+y) axis by this many degrees")
      ->check(CLI::Range(-3600.f, 3600.f))
      ->needs(environment);
  cmd->add_flag("--no-default-light", o.noDefaultLight,
                "Refuse a file without lights instead of lighting it with a uniform white environment of radiance 1");
  cmd->add_option("--light-sampler", o.lightSampler,
                  "How next-event estimation chooses a light: bvh (by what each can send to the receiving point, a "
                  "light BVH), power (in proportion to power), auto (bvh when the scene has more than one emitter; "
                  "the default). Light subpaths always start by power")
      ->check(CLI::IsMember({"auto", "power", "bvh"}));
}

void finishEnvironmentOptions(const EnvironmentOptions& o, LoadOptions& load) {
  load.defaultLight = !o.noDefaultLight;
  load.lightSelection = parseLightSelection(o.lightSampler).value_or(LightSelection::Auto);
  if (o.spec.empty()) return;
  auto desc = std::make_shared<EnvironmentDesc>(readEnvironment(o.spec));
  desc->strength = o.strength;
  desc->rotationDegrees = o.rotationDegrees;
  load.environment = std::move(desc);
}

std::string environmentKeyText(const LoadOptions& load) {
  if (!load.environment) return "";
  const EnvironmentDesc& e = *load.environment;
  uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a, 64 bit
  auto add = [&](const void* data, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
  };
  add(e.texels.data(), e.texels.size() * sizeof(Spectrum));
  add(&e.constant, sizeof(Spectrum));
  return fmt::format(";environment={}x{},strength={},rotation={},radiance={:016x}", e.width, e.height, e.strength,
                     e.rotationDegrees, hash);
}

}  // namespace pathlab::app
