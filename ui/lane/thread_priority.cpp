// Per-thread nice through /proc/self/task (see thread_priority.h for why).
#include "ui/lane/thread_priority.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#endif

namespace pathlab::ui {

int lowerRenderThreadPriority(int niceness) {
#if defined(__linux__)
  const pid_t self = static_cast<pid_t>(syscall(SYS_gettid));
  auto nameOf = [](const std::filesystem::path& task) {
    std::ifstream in(task / "comm");
    std::string name;
    std::getline(in, name);
    return name;
  };
  std::error_code ec;
  const std::string processName = nameOf(std::filesystem::path("/proc/self/task") / std::to_string(getpid()));
  int changed = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    const pid_t tid = static_cast<pid_t>(std::stol(task.path().filename().string()));
    if (tid == self || nameOf(task.path()) != processName) continue;
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, static_cast<id_t>(tid));
    if (errno == 0 && current < niceness && setpriority(PRIO_PROCESS, static_cast<id_t>(tid), niceness) == 0) ++changed;
  }
  return changed;
#else
  (void)niceness;
  return 0;
#endif
}

}  // namespace pathlab::ui
