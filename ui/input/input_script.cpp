// Parsing and replaying scripted input (see input_script.h).
#include "ui/input/input_script.h"

#include "ui/input/shortcuts.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace pathlab::ui {

namespace {

constexpr int kFlyHoldFrames = 10;

bool parseKey(const std::string& name, InputEvent& e) {
  for (const Shortcut& s : shortcuts())
    if (name == s.keyName) {
      e.key = s.key;
      e.ctrl = s.ctrl;
      return true;
    }
  if (name.size() == 1 && std::string("WASDQE").find(name[0]) != std::string::npos) {
    e.key = name[0];  // GLFW letter codes are their upper-case ASCII
    e.holdFrames = kFlyHoldFrames;
    return true;
  }
  return false;
}

}  // namespace

std::vector<InputEvent> parseInputScript(const std::string& script) {
  std::vector<InputEvent> events;
  size_t start = 0;
  while (start < script.size()) {
    const size_t end = std::min(script.find(';', start), script.size());
    const std::string item = script.substr(start, end - start);
    start = end + 1;
    if (item.empty()) continue;
    auto bad = [&](const char* why) { return std::invalid_argument("--script: '" + item + "': " + why); };
    InputEvent e;
    const size_t colon = item.find(':');
    if (colon == std::string::npos) throw bad("expected FRAME:key=NAME, FRAME:drag=X0,Y0>X1,Y1, FRAME:click=X,Y, FRAME:drop=PATH, FRAME:resize=W,H, FRAME:environment=SPEC, FRAME:strength=S, FRAME:rotation=DEG, FRAME:light-sampler=auto|power|bvh or FRAME:wait=SPP");
    try {
      size_t used = 0;
      e.frame = std::stoi(item.substr(0, colon), &used);
      if (used != colon || e.frame < 0) throw std::invalid_argument("frame");
    } catch (const std::exception&) {
      throw bad("the frame is not a non-negative integer");
    }
    std::string action = item.substr(colon + 1);
    if (action.rfind("wait=", 0) == 0) {
      unsigned long long spp = 0;
      char tail;
      if (std::sscanf(action.c_str() + 5, "%llu%c", &spp, &tail) != 1 || spp < 1 || spp > (1ull << 24))
        throw bad("expected wait=SPP with SPP in 1..16777216");
      e.kind = InputEvent::Kind::Wait;
      e.spp = spp;
    } else if (action.rfind("resize=", 0) == 0) {
      int w = 0, h = 0;
      char tail;
      if (std::sscanf(action.c_str() + 7, "%d,%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
        throw bad("expected resize=W,H with sizes in 1..16384");
      e.kind = InputEvent::Kind::Resize;
      e.to = {static_cast<float>(w), static_cast<float>(h)};
    } else if (action.rfind("environment=", 0) == 0) {
      e.kind = InputEvent::Kind::Environment;
      e.environment.spec = action.substr(12);
      if (e.environment.spec->empty()) throw bad("expected environment=FILE.exr|FILE.hdr|R,G,B|none");
    } else if (action.rfind("light-sampler=", 0) == 0) {
      e.kind = InputEvent::Kind::Environment;
      e.environment.lightSelection = parseLightSelection(action.substr(14));
      if (!e.environment.lightSelection) throw bad("expected light-sampler=auto|power|bvh");
    } else if (action.rfind("strength=", 0) == 0 || action.rfind("rotation=", 0) == 0) {
      const bool strength = action[0] == 's';
      float v = 0.f;
      char tail;
      if (std::sscanf(action.c_str() + 9, "%f%c", &v, &tail) != 1 || !std::isfinite(v) || (strength && v < 0.f))
        throw bad(strength ? "expected strength=S with S a non-negative number" : "expected rotation=DEG");
      e.kind = InputEvent::Kind::Environment;
      (strength ? e.environment.strength : e.environment.rotationDegrees) = v;
    } else if (action.rfind("outlier=", 0) == 0) {
      int row = 0;
      char tail;
      if (std::sscanf(action.c_str() + 8, "%d%c", &row, &tail) != 1 || row < 1 || row > 100000)
        throw bad("expected outlier=K with K a row of the outlier list, from 1");
      e.kind = InputEvent::Kind::Outlier;
      e.row = row;
    } else if (action.rfind("drop=", 0) == 0) {
      e.kind = InputEvent::Kind::Drop;
      e.path = action.substr(5);
      if (e.path.empty()) throw bad("no file to drop");
    } else if (action.rfind("key=", 0) == 0) {
      e.kind = InputEvent::Kind::Key;
      if (!parseKey(action.substr(4), e)) throw bad("unknown key (see the help panel, F1)");
    } else {
      if (action.rfind("Shift+", 0) == 0) e.shift = true, action = action.substr(6);
      float x0, y0, x1, y1;
      char tail;
      // A click is a drag that does not move (the inspector picks the pixel under it).
      const bool click = action.rfind("click=", 0) == 0 &&
                         std::sscanf(action.c_str() + 6, "%f,%f%c", &x0, &y0, &tail) == 2;
      if (click) x1 = x0, y1 = y0;
      if (!click && (action.rfind("drag=", 0) != 0 ||
                     std::sscanf(action.c_str() + 5, "%f,%f>%f,%f%c", &x0, &y0, &x1, &y1, &tail) != 4))
        throw bad("expected key=NAME, drag=X0,Y0>X1,Y1, click=X,Y, drop=PATH, resize=W,H or wait=SPP");
      if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
        throw bad("drag positions must be finite numbers");
      e.kind = InputEvent::Kind::Drag;
      e.from = {x0, y0};
      e.to = {x1, y1};
    }
    events.push_back(e);
  }
  // ImGui counts a press when a key goes down: the same key listed on consecutive frames (or twice
  // on one) would stay down and count once. Each later press of a key moves to the frame after
  // the previous one's release, so every listed press counts (in the order listed per frame).
  std::vector<size_t> keys;
  for (size_t i = 0; i < events.size(); ++i)
    if (events[i].kind == InputEvent::Kind::Key) keys.push_back(i);
  std::stable_sort(keys.begin(), keys.end(), [&](size_t a, size_t b) { return events[a].frame < events[b].frame; });
  std::map<std::pair<int, bool>, int> released;  // (key, ctrl) -> first frame it is up again
  for (const size_t i : keys) {
    InputEvent& e = events[i];
    const auto id = std::make_pair(e.key, e.ctrl);
    if (const auto it = released.find(id); it != released.end() && e.frame <= it->second) e.frame = it->second + 1;
    released[id] = e.frame + e.holdFrames;
  }
  return events;
}

FrameInput inputAt(const std::vector<InputEvent>& events, int frame) {
  FrameInput in;
  for (const InputEvent& e : events) {
    const int step = frame - e.frame;
    if (e.kind == InputEvent::Kind::Wait) {
      if (step == 0) in.waitSpp = e.spp;
    } else if (e.kind == InputEvent::Kind::Outlier) {
      if (step == 0) in.openOutlier = e.row;
    } else if (e.kind == InputEvent::Kind::Resize) {
      if (step == 0) in.resize = Vec2i(e.to);
    } else if (e.kind == InputEvent::Kind::Drop) {
      if (step == 0) in.dropped.push_back(e.path);
    } else if (e.kind == InputEvent::Kind::Environment) {
      if (step == 0) {
        const EnvironmentEdit& x = e.environment;
        if (x.spec) in.environment.spec = x.spec;
        if (x.strength) in.environment.strength = x.strength;
        if (x.rotationDegrees) in.environment.rotationDegrees = x.rotationDegrees;
        if (x.lightSelection) in.environment.lightSelection = x.lightSelection;
      }
    } else if (e.kind == InputEvent::Kind::Key) {
      if (step >= 0 && step < e.holdFrames) {
        in.keysDown.push_back(e.key);
        in.ctrl = in.ctrl || e.ctrl;
      }
    } else if (step >= 0 && step < 4) {
      in.hasMouse = true;
      in.mouse = step < 2 ? e.from : e.to;
      in.mouseDown = step == 1 || step == 2;
      in.shift = e.shift;
    }
  }
  return in;
}

}  // namespace pathlab::ui
