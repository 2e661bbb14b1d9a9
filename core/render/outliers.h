// The outlier finder's tally (issue 34, `pathlab outliers`): the N weighted contributions of
// highest luminance a render made, each a (camera sample, technique) pair, the fireflies. Each
// thread keeps its own N largest (a min-heap: O(log N) a contribution that beats the smallest);
// top() merges them. The course notes' one sentence, "high-contribution paths sampled with low
// probability", needs the first half found; the replay of each (inspectSample) gives the second.
#pragma once

#include "core/counters/counters.h"
#include "core/math/types.h"
#include "core/sampling/technique.h"

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <vector>

namespace pathlab {

struct Outlier {
  float luminance = 0.f;  // of its MIS-weighted contribution, as the image received it
  Spectrum value{0.f};
  SampleId id;            // the camera sample (pixel, pass) that made it
  Technique technique;
  Vec2 pRaster{0.f};      // where it landed: the sample's pixel, or a t = 1 splat's position
};

// Larger first; equal luminances by sample, then technique (the same list at any thread count).
bool brighterOutlier(const Outlier& a, const Outlier& b);

class OutlierTally {
 public:
  explicit OutlierTally(int count) : count_(count < 1 ? 1 : count) {}
  using Heap = std::vector<Outlier>;  // a min-heap under brighterOutlier's order
  // The calling thread's heap (SampleTargets::outliers).
  Heap& local() { return heaps_.local(); }
  // One contribution into `heap`, kept while it is among the count largest.
  void add(Heap& heap, const Outlier& o) const;
  // The count largest of every thread's, brightest first.
  std::vector<Outlier> top() const;
  int count() const { return count_; }

 private:
  int count_;
  tbb::enumerable_thread_specific<Heap> heaps_;
};

}  // namespace pathlab
