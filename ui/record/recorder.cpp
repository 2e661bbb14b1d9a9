// The recorder's writer thread and the ffmpeg call (posix_spawn, no shell, output captured).
#include "ui/record/recorder.h"

#include "ui/gl/screenshot.h"

#include <fmt/core.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <exception>

extern char** environ;

namespace pathlab::ui {

namespace {

// About a quarter of a second of 720p frames at 30 fps (3.7 MB each): enough to ride out a slow
// PNG, small enough that a disk that cannot keep up shows as drops rather than memory growth.
constexpr size_t kQueueFrames = 8;

struct Spawned {
  int exitCode = -1;
  std::string output;
};

// Runs argv[0] = `program` with stdin from /dev/null and stdout + stderr captured.
Spawned run(const std::string& program, const std::vector<std::string>& args) {
  int pipeFds[2];
  if (pipe2(pipeFds, O_CLOEXEC) != 0) return {-1, std::strerror(errno)};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], 2);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawnError = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipeFds[1]);
  Spawned result;
  if (spawnError != 0) {
    close(pipeFds[0]);
    return {-1, std::strerror(spawnError)};
  }
  char buffer[4096];
  for (ssize_t n; (n = read(pipeFds[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    result.output.append(buffer, static_cast<size_t>(n));
  }
  close(pipeFds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string lastLine(const std::string& text) {
  size_t end = text.find_last_not_of("\r\n ");
  if (end == std::string::npos) return "no output";
  const size_t start = text.find_last_of("\r\n", end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end + 1 - (start == std::string::npos ? 0 : start + 1));
}

}  // namespace

Recorder::Recorder(std::string dir, int fps, bool waitWhenFull)
    : dir_(std::move(dir)), fps_(fps), waitWhenFull_(waitWhenFull), clock_(fps), worker_([this] { work(); }) {}

Recorder::~Recorder() { finish(); }

void Recorder::start() {
  if (recording_) return;
  recording_ = true;
  droppedInTake_ = 0;
  clock_.restart();
}

void Recorder::stop() {
  if (!recording_) return;
  recording_ = false;
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(Job{{}, Vec2i(0), 0, droppedInTake_});  // never dropped: it ends the take
  }
  changed_.notify_all();
}

void Recorder::submit(std::vector<unsigned char> rgba, Vec2i size, int copies) {
  std::unique_lock lock(mutex_);
  if (waitWhenFull_) changed_.wait(lock, [&] { return queue_.size() < kQueueFrames; });
  if (queue_.size() >= kQueueFrames) {
    droppedInTake_ += copies;
    if (!queue_.empty() && queue_.back().copies > 0) queue_.back().copies += copies;
    return;
  }
  queue_.push_back(Job{std::move(rgba), size, copies, 0});
  lock.unlock();
  changed_.notify_all();
}

std::optional<std::string> Recorder::takeReport() {
  std::lock_guard lock(mutex_);
  if (reports_.empty()) return std::nullopt;
  std::string r = std::move(reports_.front());
  reports_.erase(reports_.begin());
  return r;
}

void Recorder::finish() {
  stop();
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void Recorder::work() {
  long long next = 0, takeStart = 0;
  std::string error;  // the first write error of a take (a full disk), reported once
  for (;;) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return quit_ || !queue_.empty(); });
    if (queue_.empty()) return;  // quit_, and everything written
    Job job = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    changed_.notify_all();  // room in the queue
    if (job.copies > 0) {
      for (int c = 0; c < job.copies && error.empty(); ++c) {
        try {
          writePngRgba(recordFrameName(dir_, next), job.size, job.rgba);
          ++next;
        } catch (const std::exception& e) {
          error = e.what();
        }
      }
      continue;
    }
    std::string report = error.empty() ? assemble(next, job.dropped) : "warning: recording stopped writing: " + error;
    report = fmt::format("{} ({} frames this take)", report, next - takeStart);
    takeStart = next;
    error.clear();
    lock.lock();
    reports_.push_back(std::move(report));
  }
}

std::string Recorder::assemble(long long frames, long long dropped) {
  std::string line = fmt::format("recording {}: {} frames at {} fps", dir_, frames, fps_);
  if (dropped > 0) line += fmt::format(", {} dropped (the queue was full; the previous frame repeated)", dropped);
  const std::string ffmpeg = findInPath("ffmpeg");
  if (frames == 0) return line;
  if (ffmpeg.empty()) return line + "; ffmpeg not found, no .mp4 assembled";
  const Spawned r = run(ffmpeg, ffmpegArguments(dir_, fps_));
  if (r.exitCode != 0)
    return fmt::format("warning: {}; ffmpeg failed (exit {}: {}), frames kept", line, r.exitCode, lastLine(r.output));
  return line + "; " + ffmpegArguments(dir_, fps_).back();
}

}  // namespace pathlab::ui
