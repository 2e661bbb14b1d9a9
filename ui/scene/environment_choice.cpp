// The viewer's environment choice and the EnvironmentDesc it becomes (see environment_choice.h).
#include "ui/scene/environment_choice.h"

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
  if (edit.lightSelection) choice.lightSelection = *edit.lightSelection;
}

EnvironmentChoice choiceOf(const EnvironmentDesc* desc, LightSelection lightSelection) {
  EnvironmentChoice choice;
  if (desc) choice = {desc->source, desc->strength, desc->rotationDegrees};
  choice.lightSelection = lightSelection;
  return choice;
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
  const std::string lights = choice.lightSelection == LightSelection::Auto
                                 ? std::string()
                                 : fmt::format("; next-event lights by {}", lightSelectionName(choice.lightSelection));
  if (choice.spec.empty()) return "none" + lights;
  return fmt::format("{} (strength {:g}, rotation {:g} deg){}", choice.spec, choice.strength, choice.rotationDegrees,
                     lights);
}

}  // namespace pathlab::ui
