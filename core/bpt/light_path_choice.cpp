// LightPathChoice: --light-paths auto's moments, cost model and choice (light_path_choice.h).
#include "core/bpt/light_path_choice.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/bpt/light_paths.h"
#include "core/sampling/technique.h"

namespace pathlab {

namespace {
constexpr size_t kCandidates = kLightPathCandidates.size();
}

LightPathChoice::LightPathChoice(int width, int height, float lightPaths)
    : width_(width),
      height_(height),
      current_(lightPaths),
      second_(static_cast<size_t>(width) * static_cast<size_t>(height) * kCandidates, 0.f),
      first_(second_.size(), 0.f) {}

std::array<double, kCandidates> LightPathChoice::ratios(double lightWalkWeight) const {
  // w_L clamped to [0, 1]: the weights' sums are a partition of unity up to rounding. Every candidate is
  // positive, so the denominator is too.
  const double wL = std::clamp(lightWalkWeight, 0.0, 1.0), wN = 1.0 - wL;
  std::array<double, kCandidates> r{};
  for (size_t c = 0; c < kCandidates; ++c) r[c] = 1.0 / (wN + static_cast<double>(kLightPathCandidates[c] / current_) * wL);
  return r;
}

void LightPathChoice::add(int t, bool lightWalkTechnique, Vec2 pRaster, float x, double lightWalkWeight,
                          SampleSums& sample, std::vector<Splat>& splats) const {
  if (!(x > 0.f) || !std::isfinite(x)) return;
  if (t == 1) {
    const int px = static_cast<int>(std::floor(pRaster.x)), py = static_cast<int>(std::floor(pRaster.y));
    if (px < 0 || py < 0 || px >= width_ || py >= height_) return;
    const size_t pixel = static_cast<size_t>(py) * static_cast<size_t>(width_) + static_cast<size_t>(px);
    splats.push_back(Splat{static_cast<uint32_t>(pixel), x, static_cast<float>(lightWalkWeight)});
    return;
  }
  const std::array<double, kCandidates> r = ratios(lightWalkWeight);
  sample.any = true;
  const double x1 = static_cast<double>(x), x2 = x1 * x1;
  for (size_t c = 0; c < kCandidates; ++c) {
    // A light-walk technique's weight also scales by F_c / F_n; its contribution without the walk's 1 / F_n
    // is X F_n: L_c gathers X F_c r, and its square in Y_c^2 is X^2 r^2 F_c / F_n.
    const double fc = static_cast<double>(kLightPathCandidates[c]);
    if (lightWalkTechnique) {
      sample.lightSide[c] += x1 * fc * r[c];
      sample.diagonal[c] += x2 * r[c] * r[c] * fc / static_cast<double>(current_);
    } else {
      sample.cameraSide[c] += x1 * r[c];
      sample.diagonal[c] += x2 * r[c] * r[c];
    }
    sample.balance[c] += x2 * r[c];
  }
}

void LightPathChoice::addCameraSample(int px, int py, const SampleSums& sample) {
  if (!sample.any || px < 0 || py < 0 || px >= width_ || py >= height_) return;
  const size_t pixel = static_cast<size_t>(py) * static_cast<size_t>(width_) + static_cast<size_t>(px);
  float* second = second_.data() + pixel * kCandidates;
  float* first = first_.data() + pixel * kCandidates;
  const double fn = static_cast<double>(current_);
  for (size_t c = 0; c < kCandidates; ++c) {
    const double a = sample.cameraSide[c], l = sample.walked ? sample.lightSide[c] : 0.0;
    const double fc = static_cast<double>(kLightPathCandidates[c]);
    // Y_c^2 with its diagonal (each contribution's own square at F_c) replaced by the balance form X^2 r:
    // both estimate the sum over the path's techniques of E_c[X_t^2] without bias, but the balance form reads
    // it from whichever technique sampled the path, where the own squares wait for the technique that will
    // carry it at F_c to sample it (rarely, when F_c is small: paths that light tracing samples well and s =
    // 0 poorly).
    second[c] += static_cast<float>(a * a + (2.0 * a * l + l * l / fc) / fn - sample.diagonal[c] + sample.balance[c]);
    first[c] += static_cast<float>(a + l / fn);
  }
}

void LightPathChoice::addSplats(std::vector<Splat>& splats) {
  for (const Splat& s : splats) {
    // A splat's square at F_c in the balance form X^2 r, as the camera samples' diagonal (its own square at
    // F_c would be X^2 (F_c / F_n) r^2: its walk's weight change and probability).
    const std::array<double, kCandidates> r = ratios(s.lightWalkWeight);
    const double x2 = static_cast<double>(s.x) * static_cast<double>(s.x);
    float* second = second_.data() + static_cast<size_t>(s.pixel) * kCandidates;
    for (size_t c = 0; c < kCandidates; ++c) second[c] += static_cast<float>(x2 * r[c]);
  }
  splats.clear();
}

void LightPathChoice::countPass(const Counters& pass) {
  // Walk rays count 1, shadow rays kShadowRayCost; a technique's shadow rays go to the side whose walk it
  // needs (light_paths.h usesLightSubpath). The counters' last slot (lengths beyond kCountedLength) goes to
  // the light side: its techniques are mostly connections from it.
  double camera = static_cast<double>(pass.cameraWalk.rays), light = static_cast<double>(pass.lightWalk.rays);
  for (size_t i = 0; i < pass.techniques.size(); ++i) {
    const double shadow = kShadowRayCost * static_cast<double>(pass.techniques[i].shadowRays);
    if (shadow == 0.0) continue;
    bool lightSide = true;
    if (i < kCountedTechniques) {
      const Technique x = Technique::fromIndex(i);
      lightSide = x.isMerge() || (x.kind == TechniqueKind::Connection && usesLightSubpath(x.s, x.t));
    }
    (lightSide ? light : camera) += shadow;
  }
  cameraCost_ += camera;
  lightCost_ += light;
  samples_ += static_cast<double>(pass.cameraSamples);
  lightWalks_ += static_cast<double>(pass.cameraSamples) * static_cast<double>(current_);
}

double LightPathChoice::cost(float lightPaths) const {
  if (samples_ <= 0.0) return 1.0;
  const double a = kCameraSampleCost + cameraCost_ / samples_, b = lightWalks_ > 0.0 ? lightCost_ / lightWalks_ : 0.0;
  return a + static_cast<double>(lightPaths) * b;
}

double LightPathChoice::moment(size_t pixel, size_t candidate) const {
  return passes_ > 0 ? static_cast<double>(second_[pixel * kCandidates + candidate]) / static_cast<double>(passes_) : 0.0;
}

double LightPathChoice::mean(size_t pixel, size_t candidate) const {
  return passes_ > 0 ? static_cast<double>(first_[pixel * kCandidates + candidate]) / static_cast<double>(passes_) : 0.0;
}

void LightPathChoice::choose(const Image& image) {
  if (passes_ == 0) return;
  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  // 1 / (I_p^2 + eps), I_p the luminance of the image so far in a 3 x 3 box around p.
  std::vector<double> inverseSquare(pixels);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double sum = 0.0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= width_ || qy >= height_) continue;
          sum += static_cast<double>(luminance(image.at(qx, qy)));
          ++n;
        }
      const double mean = std::isfinite(sum) ? sum / n : 0.0;
      inverseSquare[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)] =
          1.0 / (mean * mean + kRelativeErrorEpsilon);
    }
  const size_t outliers = static_cast<size_t>(kOutlierFraction * static_cast<double>(pixels));
  std::vector<double> relative(pixels);
  estimates_.assign(kCandidates, LightPathEstimate{});
  size_t best = 0;
  double bestWork = 0.0;
  for (size_t c = 0; c < kCandidates; ++c) {
    // V_p(c) = E[Y_c^2] - E[Y_c]^2 (the splats' variance in the first).
    for (size_t p = 0; p < pixels; ++p) {
      const double m = mean(p, c), variance = moment(p, c) - m * m;
      relative[p] = std::isfinite(variance) ? variance * inverseSquare[p] : 0.0;
    }
    double sum = 0.0;
    if (outliers > 0) {
      // The brightest `outliers` pixels left out: partition them to the end.
      std::nth_element(relative.begin(), relative.end() - static_cast<std::ptrdiff_t>(outliers), relative.end());
      for (size_t p = 0; p + outliers < pixels; ++p) sum += relative[p];
    } else {
      for (double r : relative) sum += r;
    }
    LightPathEstimate& e = estimates_[c];
    e.lightPaths = kLightPathCandidates[c];
    e.relativeVariance = std::max(sum / static_cast<double>(pixels), 0.0);
    e.cost = cost(e.lightPaths);
    const double work = e.relativeVariance * e.cost;
    // Ties (a black image: every variance zero) keep the larger F: the candidates run from 1 down.
    if (c == 0 || work < bestWork) best = c, bestWork = work;
  }
  const double reference = estimates_[0].relativeVariance * estimates_[0].cost;
  for (LightPathEstimate& e : estimates_) {
    const double work = e.relativeVariance * e.cost;
    e.efficiency = work > 0.0 ? reference / work : 1.0;
  }
  current_ = kLightPathCandidates[best];
  ++choices_;
}

std::string LightPathChoice::summary() const {
  if (estimates_.empty())
    return fmt::format(
        "light paths auto: F = {:g} (no choice yet: the first "
        "after {} passes)\n",
        current_, kLightPathPilotPasses);
  std::string text = fmt::format(
      "light paths auto: F = {:g} light subpaths per camera sample "
      "(chosen {} time{} from {} learning pass{})\n",
      current_, choices_, choices_ == 1 ? "" : "s", passes_, passes_ == 1 ? "" : "es");
  return text + lightPathTable(status(), "  ");
}

std::string lightPathTable(const LightPathStatus& status, const std::string& indent) {
  std::string text = indent + "F        rel. variance     rays/sample   est. efficiency vs F = 1\n";
  for (const LightPathEstimate& e : status.estimates)
    text += fmt::format("{}{:<7.4g}  {:>15.4g}   {:>11.3f}   {:>8.3f}{}\n", indent, e.lightPaths, e.relativeVariance,
                        e.cost, e.efficiency, e.lightPaths == status.lightPaths ? "  <" : "");
  return text;
}

}  // namespace pathlab
