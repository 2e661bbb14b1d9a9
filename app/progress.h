// A progress bar on stderr, redrawn from a background thread while the main thread renders.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <thread>

namespace pathlab::app {

// A count for a progress or summary line: 1.23G, 4.56M, 7.8k or 12.
std::string humanCount(double v);

class ProgressBar {
 public:
  // `status` returns the fraction done in [0, 1] and a short text; it is called every ~200 ms.
  using Status = std::function<std::pair<double, std::string>()>;
  explicit ProgressBar(Status status);
  ~ProgressBar();  // stops the thread and ends the line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

 private:
  void draw(bool final);
  Status status_;
  std::atomic<bool> stop_{false};
  bool interactive_;
  int lastPercentPrinted_ = -1;
  std::thread thread_;
};

}  // namespace pathlab::app
