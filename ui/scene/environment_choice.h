// What the viewer lights a scene with besides the file's own lights: the command line's
// --environment SPEC, --environment-strength and --environment-rotation as one value the
// Environment section edits, and the EnvironmentDesc it becomes when a scene is (re)loaded.
#pragma once

#include "core/lights/environment_desc.h"
#include "core/lights/light_selection.h"

#include <memory>
#include <optional>
#include <string>

namespace pathlab::ui {

struct EnvironmentChoice {
  // FILE.exr, FILE.hdr or R,G,B as --environment takes it; empty: none (the file's own lights,
  // or the default light for a file without any).
  std::string spec;
  float strength = 1.f;
  float rotationDegrees = 0.f;
  // How next-event estimation chooses among the lights (--light-sampler): built into the Scene's
  // LightSet, so a change reloads the scene as a relight does.
  LightSelection lightSelection = LightSelection::Auto;
  bool operator==(const EnvironmentChoice&) const = default;
};

// One edit of the choice, from the panel's widgets or a script (ui/input/input_script.h); unset fields
// keep their value. A spec of "none" (or empty) removes the environment.
struct EnvironmentEdit {
  std::optional<std::string> spec;
  std::optional<float> strength;
  std::optional<float> rotationDegrees;
  std::optional<LightSelection> lightSelection;
  bool empty() const { return !spec && !strength && !rotationDegrees && !lightSelection; }
};
void apply(const EnvironmentEdit& edit, EnvironmentChoice& choice);

// The choice the command line made (`desc`: LoadOptions::environment, null for none).
EnvironmentChoice choiceOf(const EnvironmentDesc* desc, LightSelection lightSelection = LightSelection::Auto);
// The environment a scene is loaded with (null for none). The map is read from choice.spec unless
// `read` already holds it (then only strength and rotation change: no file is read again).
// Throws EnvironmentError naming the file and the problem.
std::shared_ptr<const EnvironmentDesc> environmentOf(const EnvironmentChoice& choice,
                                                     const std::shared_ptr<const EnvironmentDesc>& read);
// A dropped .exr or .hdr lights the scene; any other file opens as a scene.
bool isEnvironmentFile(const std::string& path);
// A uniform radiance as the spec --environment takes ("R,G,B").
std::string colourSpec(const Vec3& radiance);
// "none", or the spec with its strength and rotation, for messages and the panel.
std::string describe(const EnvironmentChoice& choice);

}  // namespace pathlab::ui
