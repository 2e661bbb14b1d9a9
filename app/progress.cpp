// Progress bar drawing: in place on a terminal, a line every 10% otherwise (CI logs).
#include "app/progress.h"

#include <fmt/format.h>

#include <cstdio>
#include <unistd.h>

namespace pathlab::app {

ProgressBar::ProgressBar(Status status) : status_(std::move(status)), interactive_(isatty(STDERR_FILENO)) {
  thread_ = std::thread([this] {
    while (!stop_.load()) {
      draw(false);
      for (int i = 0; i < 4 && !stop_.load(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
}

ProgressBar::~ProgressBar() {
  stop_.store(true);
  thread_.join();
  draw(true);
}

void ProgressBar::draw(bool final) {
  auto [fraction, text] = status_();
  fraction = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
  const int percent = static_cast<int>(fraction * 100.0);
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.append(static_cast<size_t>(kWidth - filled), '.');
  if (interactive_) {
    std::fprintf(stderr, "\r[%s] %3d%% %s\033[K%s", bar.c_str(), percent, text.c_str(), final ? "\n" : "");
  } else if (final || percent / 10 > lastPercentPrinted_ / 10) {
    std::fprintf(stderr, "[%s] %3d%% %s\n", bar.c_str(), percent, text.c_str());
    lastPercentPrinted_ = percent;
  }
  std::fflush(stderr);
}

std::string humanCount(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f}M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

}  // namespace pathlab::app
