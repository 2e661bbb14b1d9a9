// The viewer's live convergence measurement, without any UI: a reference image with the view it
// was rendered from, and one error series per generation of the progressive renderer, recorded at
// geometric checkpoints on the render thread (ProgressiveRenderer::setPassObserver). Series are
// kept across generations so that runs of several configurations overlay.
#pragma once

#include "core/metrics/error_metrics.h"
#include "core/render/progressive_renderer.h"

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace pathlab {

// Renderers whose errors one tracker can follow at once (the viewer's A/B comparison).
inline constexpr int kErrorLanes = 2;

enum class ErrorMetric { RelMse, Rmse, Mape };
const char* errorMetricName(ErrorMetric metric);
double metricValue(const ErrorMetrics& error, ErrorMetric metric);
// The Monte Carlo rate of the metric against time or samples in log-log: -1 for relMSE (a mean
// squared error falls as the variance, 1/N), -1/2 for RMSE and MAPE (as the standard deviation).
double monteCarloSlope(ErrorMetric metric);

struct ErrorPoint {
  double seconds = 0.0;  // render time of the generation (pauses excluded)
  uint64_t spp = 0;
  ErrorMetrics error;
};

struct ErrorSeries {
  int id = 0;  // 1, 2, ... in order of creation: stable colours and names while older ones go
  uint64_t generation = 0;
  std::string label;
  std::vector<ErrorPoint> points;
};

// A short name of the configuration for a legend: "bpt power(2) [s=0;s=1] L10".
std::string seriesLabel(const RenderSettings& settings);

// Geometric checkpoints: the first full pass, then whenever the render time or the samples per
// pixel have grown by `factor` since the last recorded point, so both log-log plots (against time
// and against samples) get evenly spaced points and a long run costs O(log t) evaluations.
class CheckpointSchedule {
 public:
  explicit CheckpointSchedule(double factor = 1.25) : factor_(factor) {}
  bool due(double seconds, uint64_t spp) const;
  void record(double seconds, uint64_t spp);
  void reset() { recorded_ = false; }

 private:
  double factor_;
  bool recorded_ = false;
  double seconds_ = 0.0;
  uint64_t spp_ = 0;
};

// The view an image is rendered from. The error against a reference means something only while
// the image shows the same view: same scene, camera, lens and resolution (the estimator may differ,
// that is the point).
struct ReferenceView {
  const Scene* scene = nullptr;
  std::optional<CameraDesc> camera;  // none: the scene's own camera
  LensOptions lens;
  int width = 0, height = 0;
  bool operator==(const ReferenceView&) const = default;
};
ReferenceView viewOf(const RenderSettings& settings, const Scene* scene);

enum class ReferenceStatus { None, Valid, SizeMismatch, ViewChanged };

class ErrorTracker {
 public:
  explicit ErrorTracker(size_t maxSeries = 8, double checkpointFactor = 1.25);

  // Throws std::invalid_argument naming `source` when the image is empty, too large or holds NaN,
  // Inf or negative values (they would make every metric meaningless). Points are recorded from
  // the next pass on; generation `own` (the one a "current image" reference was taken from, 0:
  // none) is never compared with itself.
  void setReference(Image reference, const ReferenceView& view, const std::string& source, uint64_t own = 0);
  void dropReference();
  std::shared_ptr<const Image> reference() const;
  uint64_t referenceVersion() const;  // changes whenever the reference does
  std::optional<ReferenceView> referenceView() const;
  std::string referenceSource() const;
  // Whether an image rendered with these settings can be compared with the reference, and if not,
  // a one-line reason for the UI.
  ReferenceStatus statusFor(const RenderSettings& settings, const Scene* scene, std::string* why = nullptr) const;

  // The render thread's side: records a point when a checkpoint is due and the view matches.
  // `lane`: which of the viewer's side-by-side renderers (0: the main one, 1: the comparison's,
  // whose series are labelled "B: ..."); each lane has its own generations and checkpoints, so two
  // renderers running at once each get their series.
  void observe(const PassInfo& info, const Image& mean, int lane = 0);

  // The UI's side. version() changes whenever the series do, so a copy is taken only then.
  uint64_t version() const;
  std::vector<ErrorSeries> series() const;
  void clear();
  void setMaxSeries(size_t n);
  size_t maxSeries() const;
  double lastMetricMilliseconds() const;  // time of the newest evaluation (on the render thread)
  // Every point of every series: series,label,generation,seconds,spp,rmse,relmse,mape.
  std::string csv() const;

 private:
  mutable std::mutex mutex_;
  size_t maxSeries_;
  // One renderer's running series: its generation, the series its points go to (0: none yet, or
  // cleared) and its checkpoints.
  struct Lane {
    CheckpointSchedule schedule;
    uint64_t generation = 0;
    int seriesId = 0;
  };
  std::array<Lane, kErrorLanes> lanes_;
  std::shared_ptr<const Image> reference_;
  ReferenceView view_;
  std::string source_;
  uint64_t ownGeneration_ = 0;
  uint64_t referenceVersion_ = 0;
  std::vector<ErrorSeries> series_;
  int nextId_ = 1;
  uint64_t version_ = 0;
  double metricMs_ = 0.0;
  void trimLocked();
};

}  // namespace pathlab
