// The viewer's keyboard shortcuts, one table: the viewer dispatches from it, the help panel and
// docs/viewer.md list it. Keys are GLFW key codes (ImGui 1.86 indexes io.KeysDown by them).
#pragma once

#include <span>

namespace pathlab::ui {

// The last one is ExportView3D (the tests check every action has a key).
enum class Action {
  TogglePause, ToggleUi, ToggleHelp, TogglePyramid,
  TechniquesAll, TechniquesPathTracing, TechniquesLightTracing, TechniquesOneLength, TechniquesClear,
  CycleMode, CycleHeuristic, CycleIntegrator, LongerPaths, ShorterPaths,
  IsolateMoreLight, IsolateMoreCamera, IsolateLonger, IsolateShorter,
  NextPreset, PreviousPreset,
  IsolateS0, IsolateS1, IsolateS2, IsolateS3, IsolateS4, IsolateS5, IsolateS6, IsolateS7, IsolateS8, IsolateS9,
  ExposureUp, ExposureDown, ToggleToneMap, ToggleFalseColour,
  ToggleConvergence, ToggleErrorView, UseImageAsReference,
  ResetCamera, ReloadScene, SaveImage, Screenshot, ToggleRecording, Quit,
  ToggleCompare, SwapCompareSides,
  ToggleInspector, NextSample, PreviousSample, BrightestSample,
  ToggleView3D, ToggleParticles, ExportInspection, ExportView3D,
};

struct Shortcut {
  int key;           // GLFW_KEY_*
  bool ctrl;
  const char* keyName;
  Action action;
  const char* description;
};

std::span<const Shortcut> shortcuts();
// Held keys of the fly camera (not actions: they act every frame while down).
inline constexpr const char* kFlyKeysHelp = "W A S D: fly forward, left, back, right; Q E: down, up";
inline constexpr const char* kMouseHelp =
    "Left or right drag: orbit; middle drag or Shift+drag: pan; wheel: zoom (dolly)";

}  // namespace pathlab::ui
