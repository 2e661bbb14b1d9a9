// Recording the viewer: numbered PNG frames written by a background thread from a bounded queue,
// and on stop, when ffmpeg is installed, DIR/recording.mp4 assembled from them. The UI thread only
// reads back pixels and queues them (ui/record/recording.h has the frame clock and the names).
#pragma once

#include "core/math/types.h"
#include "ui/record/recording.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace pathlab::ui {

class Recorder {
 public:
  // `dir` must exist and be prepared (prepareRecordDirectory). `waitWhenFull`: a full queue makes
  // submit wait instead of dropping (headless, where a deterministic clip matters more than pace).
  Recorder(std::string dir, int fps, bool waitWhenFull);
  ~Recorder();  // finish()
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  const std::string& dir() const { return dir_; }
  bool recording() const { return recording_; }
  // A take: the clip clock restarts at zero; frames are numbered on from the last take.
  void start();
  // Ends the take; after its frames are written the clip is assembled and a report made.
  void stop();
  // Clip frames the drawn frame at `seconds` since the take started stands for (0 while stopped).
  int framesDue(double seconds) { return recording_ ? clock_.framesDue(seconds) : 0; }
  // Queues one read-back frame (RGBA8, top row first) written `copies` times. With a full queue
  // the frame is dropped and counted, and the last queued frame is repeated in its place, so the
  // clip keeps real time and its numbering has no gap (ffmpeg stops at the first gap).
  void submit(std::vector<unsigned char> rgba, Vec2i size, int copies);
  // One line per finished take (frames, drops, the .mp4 or why there is none), once.
  std::optional<std::string> takeReport();
  // Stops a running take and waits until everything is written and assembled.
  void finish();

 private:
  struct Job {
    std::vector<unsigned char> rgba;
    Vec2i size{0};
    int copies = 0;  // 0: assemble the clip (the end of a take)
    long long dropped = 0;
  };
  void work();
  std::string assemble(long long frames, long long dropped);

  std::string dir_;
  int fps_;
  bool waitWhenFull_;
  bool recording_ = false;
  CaptureClock clock_;
  long long droppedInTake_ = 0;  // UI thread

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  bool quit_ = false;
  std::vector<std::string> reports_;
  std::thread worker_;
};

}  // namespace pathlab::ui
