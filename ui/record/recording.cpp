// Recording's frame clock, names, directory policy and ffmpeg command line.
#include "ui/record/recording.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <stdexcept>
#include <unistd.h>

namespace pathlab::ui {

int CaptureClock::framesDue(double seconds) {
  // A microsecond of slack: headless clock times are sums of 1/60 and must not miss k / fps by
  // a rounding error (which would make the frame count depend on floating point).
  const long long due = static_cast<long long>(std::floor((seconds + 1e-6) * fps_)) + 1;
  if (due <= taken_) return 0;
  const long long n = due - taken_;
  taken_ = due;
  return static_cast<int>(n);
}

std::string recordFrameName(const std::string& dir, long long index) {
  return (std::filesystem::path(dir) / fmt::format("frame-{:05d}.png", index)).string();
}

void prepareRecordDirectory(const std::string& dir, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    if (!fs::create_directory(dir, ec)) throw std::runtime_error(fmt::format("{}: cannot create the directory ({})", dir, ec.message()));
    return;
  }
  if (!fs::is_directory(dir)) throw std::runtime_error(fmt::format("{}: exists and is not a directory", dir));
  if (fs::is_empty(dir)) return;
  if (!force) throw std::runtime_error(fmt::format("{}: the directory is not empty (pass --force to record into it)", dir));
  static const std::regex ours(R"(frame-\d{5}\.png|recording\.mp4)");
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && std::regex_match(e.path().filename().string(), ours)) fs::remove(e.path());
}

std::vector<std::string> ffmpegArguments(const std::string& dir, int fps) {
  const std::filesystem::path d(dir);
  return {"ffmpeg", "-y", "-framerate", std::to_string(fps), "-i", (d / "frame-%05d.png").string(),
          "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", (d / "recording.mp4").string()};
}

std::string findInPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string all(path);
  size_t start = 0;
  while (start <= all.size()) {
    const size_t end = std::min(all.find(':', start), all.size());
    const std::string dir = all.substr(start, end - start);
    const std::string candidate = (std::filesystem::path(dir.empty() ? "." : dir) / name).string();
    if (access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
    start = end + 1;
  }
  return {};
}

}  // namespace pathlab::ui
