// The shortcut table. Letters W A S D Q E are the fly keys and R resets the camera, so the
// technique presets sit on the digits (1..4 and 0, like the grid's preset buttons).
#include "ui/input/shortcuts.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace pathlab::ui {

namespace {

constexpr Shortcut kShortcuts[] = {
    {GLFW_KEY_SPACE, false, "Space", Action::TogglePause, "pause / resume rendering"},
    {GLFW_KEY_TAB, false, "Tab", Action::ToggleUi, "hide / show the panels"},
    {GLFW_KEY_F1, false, "F1", Action::ToggleHelp, "help (this list)"},
    {GLFW_KEY_G, false, "G", Action::TogglePyramid, "technique pyramid on / off"},
    {GLFW_KEY_1, false, "1", Action::TechniquesAll, "techniques: all"},
    {GLFW_KEY_2, false, "2", Action::TechniquesPathTracing, "techniques: path tracing (s <= 1)"},
    {GLFW_KEY_3, false, "3", Action::TechniquesLightTracing, "techniques: light tracing (t = 1)"},
    {GLFW_KEY_4, false, "4", Action::TechniquesOneLength, "techniques: only the selected length"},
    {GLFW_KEY_0, false, "0", Action::TechniquesClear, "techniques: clear"},
    {GLFW_KEY_M, false, "M", Action::CycleMode, "mode: combine with MIS / isolate weighted / isolate unweighted"},
    {GLFW_KEY_U, false, "U", Action::CycleHeuristic, "MIS heuristic: balance / power / uniform / off / variance-aware / optimal"},
    {GLFW_KEY_I, false, "I", Action::CycleIntegrator, "integrator: bpt / pt / lt"},
    {GLFW_KEY_RIGHT_BRACKET, false, "]", Action::LongerPaths, "maximum path length + 1"},
    {GLFW_KEY_LEFT_BRACKET, false, "[", Action::ShorterPaths, "maximum path length - 1"},
    {GLFW_KEY_RIGHT, false, "Right", Action::IsolateMoreLight, "isolated technique: s + 1, t - 1 (same length)"},
    {GLFW_KEY_LEFT, false, "Left", Action::IsolateMoreCamera, "isolated technique: s - 1, t + 1 (same length)"},
    {GLFW_KEY_UP, false, "Up", Action::IsolateLonger, "isolated technique: t + 1 (one edge longer)"},
    {GLFW_KEY_DOWN, false, "Down", Action::IsolateShorter, "isolated technique: t - 1 (one edge shorter)"},
    {GLFW_KEY_0, true, "Ctrl+0", Action::IsolateS0, "isolate (0, k+1) of the selected length k (the grid's k)"},
    {GLFW_KEY_1, true, "Ctrl+1", Action::IsolateS1, "isolate (1, k) of the selected length k"},
    {GLFW_KEY_2, true, "Ctrl+2", Action::IsolateS2, "isolate (2, k-1) of the selected length k"},
    {GLFW_KEY_3, true, "Ctrl+3", Action::IsolateS3, "isolate (3, k-2) of the selected length k"},
    {GLFW_KEY_4, true, "Ctrl+4", Action::IsolateS4, "isolate (4, k-3) of the selected length k"},
    {GLFW_KEY_5, true, "Ctrl+5", Action::IsolateS5, "isolate (5, k-4) of the selected length k"},
    {GLFW_KEY_6, true, "Ctrl+6", Action::IsolateS6, "isolate (6, k-5) of the selected length k"},
    {GLFW_KEY_7, true, "Ctrl+7", Action::IsolateS7, "isolate (7, k-6) of the selected length k"},
    {GLFW_KEY_8, true, "Ctrl+8", Action::IsolateS8, "isolate (8, k-7) of the selected length k"},
    {GLFW_KEY_9, true, "Ctrl+9", Action::IsolateS9, "isolate (9, k-8) of the selected length k"},
    {GLFW_KEY_PAGE_DOWN, false, "PageDown", Action::NextPreset, "next named preset"},
    {GLFW_KEY_PAGE_UP, false, "PageUp", Action::PreviousPreset, "previous named preset"},
    {GLFW_KEY_EQUAL, false, "=", Action::ExposureUp, "exposure + 1/2 stop"},
    {GLFW_KEY_MINUS, false, "-", Action::ExposureDown, "exposure - 1/2 stop"},
    {GLFW_KEY_T, false, "T", Action::ToggleToneMap, "tone map: clamp / filmic"},
    {GLFW_KEY_F, false, "F", Action::ToggleFalseColour, "false colour (log luminance) on / off"},
    {GLFW_KEY_C, false, "C", Action::ToggleCompare, "compare A | B side by side on / off (B: the other integrator, or --compare)"},
    {GLFW_KEY_V, false, "V", Action::SwapCompareSides, "swap the sides A and B (the panels edit A)"},
    {GLFW_KEY_K, false, "K", Action::ToggleInspector, "path inspector on / off (then click a pixel: its sample's paths)"},
    {GLFW_KEY_N, false, "N", Action::NextSample, "path inspector: the pixel's next sample"},
    {GLFW_KEY_B, false, "B", Action::PreviousSample, "path inspector: the pixel's previous sample"},
    {GLFW_KEY_H, false, "H", Action::BrightestSample, "path inspector: the brightest of the pixel's first 256 samples (16 with merges)"},
    {GLFW_KEY_O, false, "O", Action::ToggleView3D, "3D view beside the image on / off (its own orbit camera: drag, Shift+drag, wheel)"},
    {GLFW_KEY_L, false, "L", Action::ToggleParticles, "light particles in the 3D view: the last pass's light subpaths"},
    {GLFW_KEY_J, true, "Ctrl+J", Action::ExportInspection, "path inspector: write the sample as JSON in out/"},
    {GLFW_KEY_E, true, "Ctrl+E", Action::ExportView3D, "write the 3D view as PNG in out/"},
    {GLFW_KEY_P, false, "P", Action::ToggleConvergence, "convergence panel: error plot and technique rays / time"},
    {GLFW_KEY_X, false, "X", Action::ToggleErrorView, "false-colour error against the reference on / off"},
    {GLFW_KEY_R, true, "Ctrl+R", Action::UseImageAsReference, "use the current image as the reference"},
    {GLFW_KEY_R, false, "R", Action::ResetCamera, "reset the camera to the scene's"},
    {GLFW_KEY_F5, false, "F5", Action::ReloadScene, "reload the scene file"},
    {GLFW_KEY_S, true, "Ctrl+S", Action::SaveImage, "save the image as EXR and PNG in out/"},
    {GLFW_KEY_F12, false, "F12", Action::Screenshot, "screenshot of the window in out/"},
    {GLFW_KEY_F9, false, "F9", Action::ToggleRecording, "start / stop recording PNG frames (--record DIR, else out/)"},
    {GLFW_KEY_Q, true, "Ctrl+Q", Action::Quit, "quit"},
};

}  // namespace

std::span<const Shortcut> shortcuts() { return kShortcuts; }

}  // namespace pathlab::ui
