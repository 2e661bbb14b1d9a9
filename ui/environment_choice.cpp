// The viewer's environment choice and the EnvironmentDesc it becomes (see environment_choice.h).
#include "ui/environment_choice.h"

#include "core/lights/environment_file.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace pathlab::ui {

void apply(const EnvironmentEdit& edit, EnvironmentChoice& choice) {
  if (edit.spec) choice.spec = *edit.spec == "none" ? std::string() : *edit.spec;
  if (edit.strength) choice.strength = std::max(*edit.strength, 0.f);
  if (edit.rotationDegrees) choice.rotationDegrees = *edit.rotationDegrees;
}

EnvironmentChoice choiceOf(const EnvironmentDesc* desc) {
  if (!desc) return {};
  return {desc->source, desc->strength, desc->rotationDegrees};
}

std::shared_ptr<const EnvironmentDesc> environmentOf(const EnvironmentChoice& choice,
                                                     const std::shared_ptr<const EnvironmentDesc>& read) {
  if (choice.spec.empty()) return nullptr;
  // Strength and rotation are applied by the light, not baked into the texels: a map read once
  // serves every slider position.
  auto desc = std::make_shared<EnvironmentDesc>(read && read->source == choice.spec ? *read : readEnvironment(choice.spec));
  desc->strength = choice.strength;
  desc->rotationDegrees = choice.rotationDegrees;
  return desc;
}

bool isEnvironmentFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr" || ext == ".hdr";
}

std::string colourSpec(const Vec3& radiance) {
  return fmt::format("{:g},{:g},{:g}", radiance.r, radiance.g, radiance.b);
}

std::string describe(const EnvironmentChoice& choice) {
  if (choice.spec.empty()) return "none";
  return fmt::format("{} (strength {:g}, rotation {:g} deg)", choice.spec, choice.strength, choice.rotationDegrees);
}

}  // namespace pathlab::ui
