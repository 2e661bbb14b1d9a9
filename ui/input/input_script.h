// Scripted input for tests and reproducible screenshots: key presses and mouse drags at given
// frames, fed to Dear ImGui as if they came from the window. ImGui 1.86 has no input queue, so
// each step writes io.KeysDown / io.MousePos / io.MouseDown for one frame (../shared/TOOLCHAIN.md).
//
// SCRIPT: ';'-separated events "FRAME:key=NAME", "FRAME:drag=X0,Y0>X1,Y1" (window pixels, left
// button; "Shift+drag=..." pans), "FRAME:click=X,Y" (a left click: a drag that does not move;
// with the path inspector on it picks the pixel), "FRAME:drop=PATH" (a file dropped on the window),
// "FRAME:resize=W,H" (the window resized), "FRAME:environment=SPEC" (FILE.exr, FILE.hdr, R,G,B or
// none), "FRAME:strength=S" and "FRAME:rotation=DEG" (what the Environment section's fields and
// sliders set), "FRAME:light-sampler=auto|power|bvh" (its next-event lights), "FRAME:outlier=K"
// (row K, from 1, of the outlier list opened, as a click on it does) or "FRAME:wait=SPP" (that frame waits until the current
// image has SPP samples per pixel: scripts that compare configurations run the same on a loaded
// machine). NAME is a
// key of the shortcut table ("3", "M", "Space", "F1", "Ctrl+S", "PageDown", "]") or a fly key
// W A S D Q E (held for 10 frames). Every listed press counts: a key listed again while it is
// still down (the next frame, or the same frame) is pressed again on the first frame after it is
// released, so "5:key=]; 6:key=]" presses ] on frames 5 and 7.
#pragma once

#include "core/math/types.h"
#include "ui/scene/environment_choice.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pathlab::ui {

struct InputEvent {
  enum class Kind { Key, Drag, Drop, Resize, Wait, Environment, Outlier } kind = Kind::Key;
  int frame = 0;
  int key = 0;        // GLFW key code
  bool ctrl = false;  // Key: with Ctrl
  bool shift = false; // Drag: with Shift (pan)
  int holdFrames = 1; // Key: frames the key stays down
  Vec2 from{0.f}, to{0.f};  // Drag; Resize: `to` is the size
  std::string path;   // Drop
  uint64_t spp = 0;   // Wait
  int row = 0;        // Outlier: from 1
  EnvironmentEdit environment;
};

// Throws std::invalid_argument naming the bad event.
std::vector<InputEvent> parseInputScript(const std::string& script);

// What the script does to the input of one frame.
struct FrameInput {
  std::vector<int> keysDown;
  bool ctrl = false, shift = false;
  bool hasMouse = false;
  Vec2 mouse{0.f};
  bool mouseDown = false;
  std::vector<std::string> dropped;
  std::optional<Vec2i> resize;
  std::optional<uint64_t> waitSpp;
  std::optional<int> openOutlier;  // the outlier list's row, from 1
  EnvironmentEdit environment;
};

// A drag takes four frames from its start: move to the start, press, move to the end, release.
FrameInput inputAt(const std::vector<InputEvent>& events, int frame);

}  // namespace pathlab::ui
