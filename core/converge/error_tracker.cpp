// Live error series against a reference (see the header).
#include "core/converge/error_tracker.h"

#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

constexpr int kMaxReferenceSide = 16384;

}  // namespace

const char* errorMetricName(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::RelMse: return "relMSE";
    case ErrorMetric::Rmse: return "RMSE";
    case ErrorMetric::Mape: return "MAPE";
  }
  return "?";
}

double metricValue(const ErrorMetrics& error, ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::RelMse: return error.relMse;
    case ErrorMetric::Rmse: return error.rmse;
    case ErrorMetric::Mape: return error.mape;
  }
  return 0.0;
}

double monteCarloSlope(ErrorMetric metric) { return metric == ErrorMetric::RelMse ? -1.0 : -0.5; }

std::string seriesLabel(const RenderSettings& s) {
  std::string out = integratorName(s.integrator);
  if (s.integrator != IntegratorKind::Pt) {
    // Light tracing has one technique a length: its weights are 1 whatever the heuristic.
    if (s.integrator == IntegratorKind::Bpt)
      out += s.mis.heuristic == MisHeuristic::Power ? fmt::format(" power({:g})", s.mis.beta)
                                                     : std::string(" ") + misHeuristicName(s.mis.heuristic);
    if (s.connect != ConnectStrategy::All) out += std::string(" connect=") + connectStrategyName(s.connect);
    if (s.techniques != TechniqueSet::all()) out += " [" + s.techniques.toString() + "]";
    if (s.isolate)
      out += fmt::format(" only {}{}", techniqueLabel(s.isolate->technique()), s.isolate->unweighted ? " unweighted" : "");
  }
  out += fmt::format(" L{}", s.maxLength);
  if (!s.russianRoulette) out += " no-RR";
  // Set explicitly only: the A | B lanes of the fog presets differ in it (issue 35).
  if (s.mediumSampling) out += std::string(" media=") + mediumSamplingName(*s.mediumSampling);
  return out;
}

bool CheckpointSchedule::due(double seconds, uint64_t spp) const {
  if (!recorded_) return true;
  return seconds >= seconds_ * factor_ || static_cast<double>(spp) >= static_cast<double>(spp_) * factor_;
}

void CheckpointSchedule::record(double seconds, uint64_t spp) {
  recorded_ = true;
  seconds_ = seconds;
  spp_ = spp;
}

ReferenceView viewOf(const RenderSettings& settings, const Scene* scene) {
  return ReferenceView{scene, settings.camera, settings.lens, settings.width, settings.height};
}

ErrorTracker::ErrorTracker(size_t maxSeries, double checkpointFactor)
    : maxSeries_(std::max<size_t>(maxSeries, 1)) {
  for (Lane& lane : lanes_) lane.schedule = CheckpointSchedule(checkpointFactor);
}

void ErrorTracker::setReference(Image reference, const ReferenceView& view, const std::string& source, uint64_t own) {
  if (reference.width <= 0 || reference.height <= 0 || reference.rgb.empty())
    throw std::invalid_argument(source + ": the reference image is empty");
  if (reference.width > kMaxReferenceSide || reference.height > kMaxReferenceSide)
    throw std::invalid_argument(fmt::format("{}: a {} x {} reference is larger than {} pixels a side", source,
                                            reference.width, reference.height, kMaxReferenceSide));
  size_t bad = 0;
  for (float v : reference.rgb) bad += !(std::isfinite(v) && v >= 0.f);
  if (bad > 0)
    throw std::invalid_argument(fmt::format("{}: {} values of the reference are NaN, Inf or negative", source, bad));
  auto shared = std::make_shared<const Image>(std::move(reference));
  std::lock_guard lock(mutex_);
  reference_ = std::move(shared);
  view_ = view;
  view_.width = reference_->width;
  view_.height = reference_->height;
  source_ = source;
  ownGeneration_ = own;
  ++referenceVersion_;
  // Points against another reference are not comparable with the new ones.
  series_.clear();
  for (Lane& lane : lanes_) {
    lane.seriesId = 0;
    lane.schedule.reset();
  }
  ++version_;
}

void ErrorTracker::dropReference() {
  std::lock_guard lock(mutex_);
  if (!reference_) return;
  reference_.reset();
  source_.clear();
  ++referenceVersion_;
  ++version_;
}

std::shared_ptr<const Image> ErrorTracker::reference() const {
  std::lock_guard lock(mutex_);
  return reference_;
}

uint64_t ErrorTracker::referenceVersion() const {
  std::lock_guard lock(mutex_);
  return referenceVersion_;
}

std::optional<ReferenceView> ErrorTracker::referenceView() const {
  std::lock_guard lock(mutex_);
  if (!reference_) return std::nullopt;
  return view_;
}

std::string ErrorTracker::referenceSource() const {
  std::lock_guard lock(mutex_);
  return source_;
}

ReferenceStatus ErrorTracker::statusFor(const RenderSettings& settings, const Scene* scene, std::string* why) const {
  std::lock_guard lock(mutex_);
  auto say = [&](ReferenceStatus status, std::string text) {
    if (why) *why = std::move(text);
    return status;
  };
  if (!reference_) return say(ReferenceStatus::None, "no reference");
  if (settings.width != view_.width || settings.height != view_.height)
    return say(ReferenceStatus::SizeMismatch,
               fmt::format("the reference is {} x {} but the image is {} x {}: no error can be computed",
                           view_.width, view_.height, settings.width, settings.height));
  if (scene != view_.scene) return say(ReferenceStatus::ViewChanged, "the scene changed since the reference was taken");
  if (settings.camera != view_.camera)
    return say(ReferenceStatus::ViewChanged, "the camera moved since the reference was taken: the error is meaningless");
  if (!(settings.lens == view_.lens))
    return say(ReferenceStatus::ViewChanged, "the lens changed since the reference was taken");
  return say(ReferenceStatus::Valid, "");
}

void ErrorTracker::observe(const PassInfo& info, const Image& mean, int laneIndex) {
  if (laneIndex < 0 || laneIndex >= kErrorLanes) return;
  Lane& lane = lanes_[static_cast<size_t>(laneIndex)];
  std::shared_ptr<const Image> reference;
  {
    std::lock_guard lock(mutex_);
    // A "current image" reference was taken from the main renderer's generation `ownGeneration_`.
    if (!reference_ || (laneIndex == 0 && info.generation == ownGeneration_)) return;
    if (!(viewOf(info.settings, info.scene) == view_)) return;
    if (info.generation != lane.generation) {
      lane.generation = info.generation;
      lane.seriesId = 0;
      lane.schedule.reset();
    }
    if (!lane.schedule.due(info.renderSeconds, info.samplesPerPixel)) return;
    lane.schedule.record(info.renderSeconds, info.samplesPerPixel);
    reference = reference_;
  }
  // The metric outside the lock: the UI thread never waits for it.
  const auto start = std::chrono::steady_clock::now();
  const ErrorMetrics error = errorMetrics(mean, *reference);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::lock_guard lock(mutex_);
  if (reference != reference_ || info.generation != lane.generation) return;  // changed meanwhile
  metricMs_ = ms;
  auto it = std::find_if(series_.begin(), series_.end(), [&](const ErrorSeries& s) { return s.id == lane.seriesId; });
  if (it == series_.end()) {
    const std::string label = laneIndex == 0 ? seriesLabel(info.settings) : "B: " + seriesLabel(info.settings);
    series_.push_back(ErrorSeries{nextId_++, info.generation, label, {}});
    lane.seriesId = series_.back().id;
    trimLocked();
    it = std::find_if(series_.begin(), series_.end(), [&](const ErrorSeries& s) { return s.id == lane.seriesId; });
  }
  it->points.push_back(ErrorPoint{info.renderSeconds, info.samplesPerPixel, error});
  ++version_;
}

uint64_t ErrorTracker::version() const {
  std::lock_guard lock(mutex_);
  return version_;
}

std::vector<ErrorSeries> ErrorTracker::series() const {
  std::lock_guard lock(mutex_);
  return series_;
}

void ErrorTracker::clear() {
  std::lock_guard lock(mutex_);
  series_.clear();
  for (Lane& lane : lanes_) lane.seriesId = 0;  // the running generations continue in new series
  ++version_;
}

void ErrorTracker::setMaxSeries(size_t n) {
  std::lock_guard lock(mutex_);
  maxSeries_ = std::max<size_t>(n, 1);
  trimLocked();
  ++version_;
}

size_t ErrorTracker::maxSeries() const {
  std::lock_guard lock(mutex_);
  return maxSeries_;
}

double ErrorTracker::lastMetricMilliseconds() const {
  std::lock_guard lock(mutex_);
  return metricMs_;
}

void ErrorTracker::trimLocked() {
  // The oldest go first; the running ones (one per lane) always stay.
  auto running = [&](const ErrorSeries& s) {
    return std::any_of(lanes_.begin(), lanes_.end(), [&](const Lane& lane) { return lane.seriesId == s.id; });
  };
  for (auto it = series_.begin(); series_.size() > maxSeries_ && it != series_.end();)
    it = running(*it) ? it + 1 : series_.erase(it);
}

std::string ErrorTracker::csv() const {
  std::lock_guard lock(mutex_);
  std::string out = "series,label,generation,seconds,spp,rmse,relmse,mape\n";
  for (const ErrorSeries& s : series_) {
    std::string label = s.label;
    std::replace(label.begin(), label.end(), '"', '\'');
    for (const ErrorPoint& p : s.points)
      out += fmt::format("{},\"{}\",{},{:.6g},{},{:.8g},{:.8g},{:.8g}\n", s.id, label, s.generation, p.seconds, p.spp,
                         p.error.rmse, p.error.relMse, p.error.mape);
  }
  return out;
}

}  // namespace pathlab
