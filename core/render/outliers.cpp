// The outlier finder's bounded heaps.
#include "core/render/outliers.h"

#include <algorithm>
#include <tuple>

namespace pathlab {

bool brighterOutlier(const Outlier& a, const Outlier& b) {
  if (a.luminance != b.luminance) return a.luminance > b.luminance;
  return std::tuple(a.id.sample, a.id.y, a.id.x, a.technique.index()) <
         std::tuple(b.id.sample, b.id.y, b.id.x, b.technique.index());
}

void OutlierTally::add(Heap& heap, const Outlier& o) const {
  // std::push_heap with brighterOutlier keeps the least bright on top (a min-heap of brightness).
  if (heap.size() < static_cast<size_t>(count_)) {
    heap.push_back(o);
    std::push_heap(heap.begin(), heap.end(), brighterOutlier);
    return;
  }
  if (!brighterOutlier(o, heap.front())) return;
  std::pop_heap(heap.begin(), heap.end(), brighterOutlier);
  heap.back() = o;
  std::push_heap(heap.begin(), heap.end(), brighterOutlier);
}

std::vector<Outlier> OutlierTally::top() const {
  std::vector<Outlier> all;
  for (const Heap& h : heaps_) all.insert(all.end(), h.begin(), h.end());
  std::sort(all.begin(), all.end(), brighterOutlier);
  if (all.size() > static_cast<size_t>(count_)) all.resize(static_cast<size_t>(count_));
  return all;
}

}  // namespace pathlab
