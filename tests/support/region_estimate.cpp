// Region means from independent passes, their z-tests and the Bonferroni threshold.
#include "tests/support/region_estimate.h"

#include "core/bsdf/bsdf.h"
#include "core/camera/camera.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pathlab::test {

PixelLabels gridLabels(int width, int height, int cellsX, int cellsY) {
  PixelLabels labels{width, height, cellsX * cellsY, std::vector<int>(static_cast<size_t>(width * height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      labels.label[static_cast<size_t>(y * width + x)] = (y * cellsY / height) * cellsX + x * cellsX / width;
  return labels;
}

bool hasDeltaLobe(const Material& m) {
  const float alpha = m.roughnessFactor * m.roughnessFactor;
  return alpha < kDeltaAlpha && (m.metallicFactor > 0.f || m.specularFactor > 0.f || m.transmissionFactor > 0.f);
}

namespace {

// Per pixel: how many of n x n sub-pixel camera rays (lens centre) hit a surface `which` selects.
std::vector<int> surfaceHits(const Scene& scene, const RenderSettings& s, const MaterialPredicate& which, int n) {
  const Camera camera(s.camera.value_or(scene.cameraDesc()), s.width, s.height, s.lens);
  std::vector<int> hits(static_cast<size_t>(s.width * s.height), 0);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec2 p(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(n),
                       static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(n));
          // Through index-matched boundaries (media, issue 16): the surface the camera sees.
          Ray ray = camera.generateRay(p, Vec2(0.5f));
          auto hit = scene.intersect(ray);
          for (int crossing = 0; hit && hit->indexMatched && crossing < 16; ++crossing) {
            ray.o = offsetRayOrigin(hit->p, hit->pError, hit->ng, ray.d);
            hit = scene.intersect(ray);
          }
          if (hit && which(scene.material(hit->material))) ++hits[static_cast<size_t>(y * s.width + x)];
        }
  return hits;
}

// Keeps the pixels whose 3 x 3 neighbourhood satisfies `keep` for every member.
PixelLabels keepNeighbourhoods(const RenderSettings& s, PixelLabels labels, const std::vector<int>& hits,
                               bool (*keep)(int hits, int n2), int n) {
  PixelLabels out = labels;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= s.width || yy >= s.height) continue;
          if (!keep(hits[static_cast<size_t>(yy * s.width + xx)], n * n))
            out.label[static_cast<size_t>(y * s.width + x)] = -1;
        }
  return out;
}

}  // namespace

PixelLabels withoutSeenDirectly(const Scene& scene, const RenderSettings& s, PixelLabels labels,
                                const MaterialPredicate& which, int n) {
  return keepNeighbourhoods(
      s, std::move(labels), surfaceHits(scene, s, which, n), [](int h, int) { return h == 0; }, n);
}

PixelLabels onlySeenDirectly(const Scene& scene, const RenderSettings& s, PixelLabels labels,
                             const MaterialPredicate& which, int n) {
  return keepNeighbourhoods(
      s, std::move(labels), surfaceHits(scene, s, which, n), [](int h, int n2) { return h == n2; }, n);
}

int labelledPixels(const PixelLabels& labels) {
  int count = 0;
  for (int l : labels.label) count += l >= 0;
  return count;
}

std::vector<std::vector<RegionMeans>> renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes,
                                                        const std::vector<PixelLabels>& labelSets,
                                                        const std::vector<ImageOf>& images) {
  const auto start = std::chrono::steady_clock::now();
  RenderSession session(scene, s);
  const size_t pixels = static_cast<size_t>(s.width) * static_cast<size_t>(s.height);
  struct Accumulator {
    std::vector<size_t> regionSize;
    size_t labelled = 0;
    std::vector<std::array<RunningStats, 3>> regionStats;
    std::array<RunningStats, 3> wholeStats;
  };
  // [image][label set]
  std::vector<std::vector<Accumulator>> acc(images.size(), std::vector<Accumulator>(labelSets.size()));
  for (auto& perImage : acc)
    for (size_t k = 0; k < labelSets.size(); ++k) {
      const PixelLabels& labels = labelSets[k];
      if (labels.label.size() != pixels) throw std::invalid_argument("labels do not match the image size");
      perImage[k].regionSize.assign(static_cast<size_t>(labels.count), 0);
      for (int l : labels.label)
        if (l >= 0) ++perImage[k].regionSize[static_cast<size_t>(l)], ++perImage[k].labelled;
      perImage[k].regionStats.resize(static_cast<size_t>(labels.count));
    }
  std::vector<std::vector<double>> previous(images.size(), std::vector<double>(3 * pixels, 0.0));
  std::vector<double> thisPass(3 * pixels, 0.0);
  std::vector<std::array<double, 3>> sums;
  for (int pass = 1; pass <= passes; ++pass) {
    session.renderPass();
    for (size_t im = 0; im < images.size(); ++im) {
      const Image img = images[im](session);
      for (size_t i = 0; i < 3 * pixels; ++i) {
        const double total = static_cast<double>(img.rgb[i]) * pass;
        thisPass[i] = total - previous[im][i];
        previous[im][i] = total;
      }
      for (size_t k = 0; k < labelSets.size(); ++k) {
        Accumulator& a = acc[im][k];
        sums.assign(static_cast<size_t>(labelSets[k].count), {0.0, 0.0, 0.0});
        std::array<double, 3> whole{0.0, 0.0, 0.0};
        for (size_t i = 0; i < pixels; ++i) {
          const int l = labelSets[k].label[i];
          if (l < 0) continue;
          for (size_t c = 0; c < 3; ++c) {
            sums[static_cast<size_t>(l)][c] += thisPass[3 * i + c];
            whole[c] += thisPass[3 * i + c];
          }
        }
        for (size_t r = 0; r < sums.size(); ++r)
          for (size_t c = 0; c < 3; ++c)
            if (a.regionSize[r] > 0) a.regionStats[r][c].add(sums[r][c] / static_cast<double>(a.regionSize[r]));
        for (size_t c = 0; c < 3; ++c)
          if (a.labelled > 0) a.wholeStats[c].add(whole[c] / static_cast<double>(a.labelled));
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::vector<RegionMeans>> out(images.size(), std::vector<RegionMeans>(labelSets.size()));
  for (size_t im = 0; im < images.size(); ++im)
    for (size_t k = 0; k < labelSets.size(); ++k) {
      const Accumulator& a = acc[im][k];
      RegionMeans& m = out[im][k];
      m.region.resize(a.regionStats.size());
      for (size_t r = 0; r < a.regionStats.size(); ++r)
        for (size_t c = 0; c < 3; ++c) m.region[r][c] = a.regionStats[r][c].estimate();
      for (size_t c = 0; c < 3; ++c) m.whole[c] = a.wholeStats[c].estimate();
      m.discarded = session.counters().discarded();
      m.seconds = seconds;
    }
  return out;
}

std::vector<RegionMeans> renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes,
                                           const std::vector<PixelLabels>& labelSets) {
  return renderRegionMeans(scene, s, passes, labelSets, {[](const RenderSession& r) { return r.image(); }}).front();
}

RegionMeans renderRegionMeans(const Scene& scene, const RenderSettings& s, int passes, const PixelLabels& labels) {
  return renderRegionMeans(scene, s, passes, std::vector<PixelLabels>{labels}).front();
}

RegionMeans renderPairedDifference(const Scene& scene, const RenderSettings& a, const RenderSettings& b, int passes,
                                   const PixelLabels& labels) {
  // The second session is driven from inside the first one's image callback, one pass behind
  // never: both have rendered the same number of passes whenever the difference is read.
  RenderSession other(scene, b);
  return renderRegionMeans(scene, a, passes, {labels}, {[&](const RenderSession& first) {
                             while (other.passes() < first.passes()) other.renderPass();
                             return imageDifference(first.image(), other.image());
                           }})
      .front()
      .front();
}

Agreement testZero(const RegionMeans& d) {
  RegionMeans zero = d;
  for (auto& r : zero.region)
    for (auto& c : r) c = MeanEstimate{0.0, 0.0, c.count};
  for (auto& c : zero.whole) c = MeanEstimate{0.0, 0.0, c.count};
  return compareRegions(d, zero);
}

RegionMeans difference(const RegionMeans& a, const RegionMeans& b) {
  RegionMeans d = a;
  auto sub = [](const MeanEstimate& x, const MeanEstimate& y) {
    return MeanEstimate{x.mean - y.mean, std::hypot(x.standardError, y.standardError), std::min(x.count, y.count)};
  };
  for (size_t r = 0; r < d.region.size(); ++r)
    for (size_t c = 0; c < 3; ++c) d.region[r][c] = sub(a.region[r][c], b.region[r][c]);
  for (size_t c = 0; c < 3; ++c) d.whole[c] = sub(a.whole[c], b.whole[c]);
  d.discarded = a.discarded + b.discarded;
  return d;
}

Image imageDifference(const Image& a, const Image& b) {
  Image d = a;
  for (size_t i = 0; i < d.rgb.size(); ++i) d.rgb[i] -= b.rgb[i];
  return d;
}

double bonferroniZ(double familyAlpha, int comparisons) {
  const double target = familyAlpha / static_cast<double>(std::max(comparisons, 1));
  double lo = 0.0, hi = 40.0;  // erfc(z / sqrt 2) = P(|Z| > z) is decreasing in z
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Agreement compareRegions(const RegionMeans& a, const RegionMeans& b) {
  Agreement out;
  auto test = [&](const MeanEstimate& x, const MeanEstimate& y, const std::string& where, int c) {
    if (x.count == 0 || y.count == 0) return;  // an empty region
    ++out.comparisons;
    const double z = zDifference(x, y);
    if (std::abs(z) >= out.maxAbsZ) {
      out.maxAbsZ = std::abs(z);
      out.worst = fmt::format("{} channel {}: {:.6g} +- {:.3g} vs {:.6g} +- {:.3g} (z = {:.2f})", where, c, x.mean,
                              x.standardError, y.mean, y.standardError, z);
    }
  };
  for (size_t r = 0; r < a.region.size() && r < b.region.size(); ++r)
    for (int c = 0; c < 3; ++c)
      test(a.region[r][static_cast<size_t>(c)], b.region[r][static_cast<size_t>(c)], fmt::format("region {}", r), c);
  for (int c = 0; c < 3; ++c) test(a.whole[static_cast<size_t>(c)], b.whole[static_cast<size_t>(c)], "whole image", c);
  return out;
}

}  // namespace pathlab::test
