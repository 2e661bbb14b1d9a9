// Fewer light subpaths than camera samples: the first knob of efficiency-aware bidirectional
// sampling (Grittmann, Yazici, Georgiev and Slusallek 2022, "Efficiency-aware multiple importance
// sampling for bidirectional rendering algorithms"). A pass of BPT walks one light subpath per
// camera sample; with F = --light-paths < 1 each camera sample walks one with probability F, so
// a pass holds F x pixels of them on average. The techniques that need a light walk (light
// tracing, t = 1, and every s >= 2; not s = 0, nor next-event estimation s = 1, which samples its
// light point afresh) then draw F samples per camera sample instead of one:
//   - their contributions are divided by F (E[1{walked} X / F] = E[X]: each stays unbiased);
//   - every MIS weight counts F samples for them (Veach's n_i, eq. 9.5: w_i = n_i p_i / sum n_j p_j),
//     through the same per-technique counts the variance-aware factors use (PathDensities::factors).
// What is saved is the light walk and its connections on 1 - F of the camera samples; what is
// lost is those techniques' share where they are the better ones. Where light tracing and the
// connections beyond next-event estimation do little (open scenes, environment light) a small F
// is nearly free variance and a large saving; where they carry caustics it is not.
#pragma once

#include "core/math/rng.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// Whether technique (s, t) walks the light subpath (BidirTracer::lightWalkNeeded).
constexpr bool usesLightSubpath(int s, int t) { return s >= 1 && !(s == 1 && t >= 2); }

// Whether the camera sample whose connections are keyed by `connectionKey` walks a light subpath,
// with probability `lightPaths`: a number of its own, salted apart from the connections' streams
// (the camera and light walks' numbers are untouched, so F = 1 renders the same bits as before).
inline bool walksLightSubpath(uint64_t connectionKey, float lightPaths) {
  if (lightPaths >= 1.f) return true;
  constexpr uint64_t kSalt = 0xA0761D6478BD642Full;
  const float u = static_cast<float>(mixBits(connectionKey ^ kSalt) >> 40) * 0x1p-24f;
  return u < lightPaths;
}

// Each technique's sample count per camera sample, by Technique::index up to maxLength (merges: 1):
// the row of length k starts at Technique::firstIndexOfLength(k), as the weights read it.
inline std::vector<float> lightPathCounts(int maxLength, float lightPaths) {
  std::vector<float> counts(Technique::countUpTo(maxLength), 1.f);
  for (size_t i = 0; i < counts.size(); ++i) {
    const Technique x = Technique::fromIndex(i);
    if (!x.isMerge() && usesLightSubpath(x.s, x.t)) counts[i] = lightPaths;
  }
  return counts;
}

}  // namespace pathlab
