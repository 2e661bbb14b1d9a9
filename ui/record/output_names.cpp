// Fresh output names for saved images and screenshots.
#include "ui/record/output_names.h"

#include <ctime>
#include <filesystem>

namespace pathlab::ui {

std::string freshStem(const std::string& dir, const std::string& prefix, const std::vector<std::string>& extensions) {
  std::filesystem::create_directories(dir);
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  const std::string base = (std::filesystem::path(dir) / (prefix + "-" + stamp)).string();
  for (int n = 1;; ++n) {
    const std::string stem = n == 1 ? base : base + "-" + std::to_string(n);
    bool taken = false;
    for (const std::string& ext : extensions) taken = taken || std::filesystem::exists(stem + ext);
    if (!taken) return stem;
  }
}

}  // namespace pathlab::ui
