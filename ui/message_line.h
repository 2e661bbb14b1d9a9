// The side panel's message line: the last notice or error, which the viewer and its controllers
// write and the panel draws (a notice fades, an error stays until dismissed).
#pragma once

#include <chrono>
#include <string>

namespace pathlab::ui {

struct MessageLine {
  std::string text;
  bool isError = false;
  std::chrono::steady_clock::time_point time{};

  void show(const std::string& message, bool error = false) {
    text = message;
    isError = error;
    time = std::chrono::steady_clock::now();
  }
  // An error not dismissed yet ("" when there is none).
  std::string error() const { return isError ? text : std::string(); }
};

}  // namespace pathlab::ui
