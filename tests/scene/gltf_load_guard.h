// Test support: loadGltf in a child process with a deadline, so a loader that hangs (a FIFO, a
// device, an unbounded expansion) fails the test instead of hanging the suite.
#pragma once

#include "core/scene/gltf_loader.h"

#include <csignal>
#include <optional>
#include <poll.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

namespace pathlab::gltf_test {

struct GuardedLoad {
  bool finished = false;  // false: killed at the deadline
  bool loaded = false;    // finished without an exception
  std::string message;    // the SceneError's what() (or "other exception: ...")
};

// A fork, not a thread: a thread blocked in open() on a FIFO could not be stopped.
inline GuardedLoad loadWithDeadline(const std::string& path, const LoadOptions& options = {},
                                    int seconds = 20) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    close(fds[0]);
    std::string out;
    try {
      loadGltf(path, options);
      out = "L";
    } catch (const SceneError& e) {
      out = std::string("E") + e.what();
    } catch (const std::exception& e) {
      out = std::string("Eother exception: ") + e.what();
    }
    for (size_t done = 0; done < out.size();) {
      const ssize_t n = write(fds[1], out.data() + done, out.size() - done);
      if (n <= 0) break;
      done += size_t(n);
    }
    _exit(0);
  }
  close(fds[1]);
  GuardedLoad result;
  std::string received;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, int(left.count())) <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) {
      result.finished = !received.empty();
      break;
    }
    received.append(buffer, size_t(n));
  }
  close(fds[0]);
  if (!result.finished) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  if (result.finished) {
    result.loaded = received[0] == 'L';
    result.message = received.substr(1);
  }
  return result;
}

}  // namespace pathlab::gltf_test
