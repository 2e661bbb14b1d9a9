// mergeableTechniques and sampleableByMerge: structural masks over a path's vertices.
#include "core/bpt/sampleable_merges.h"

namespace pathlab {

namespace {

const PathVertex& pathVertex(const MisPath& path, int i) {
  const int n = path.s + path.t;
  return i < path.s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i);
}

constexpr int kMaxMergeMaskVertices = 33;  // slot 2n - 3 of the last merge must fit in 63 bits

}  // namespace

uint64_t mergeableTechniques(const MisPath& path) {
  const int n = path.s + path.t;
  if (n > kMaxMergeMaskVertices) return 0;
  uint64_t bits = 0;
  for (int i = 1; i <= n - 2; ++i) {
    const PathVertex& v = pathVertex(path, i);
    // Merged at x_i: M(i + 1, n - i), slot n - 1 + i.
    if (v.type == VertexType::Surface && !v.isDelta) bits |= uint64_t{1} << (n - 1 + i);
  }
  return bits;
}

uint64_t sampleableByMerge(const MisPath& path) {
  const int n = path.s + path.t;
  if (n > kMaxMergeMaskVertices) return 0;
  // As sampleableTechniques, with no exception for the "connection's" ends (see the header).
  auto delta = [&](int i) { return pathVertex(path, i).isDelta; };
  uint64_t bits = 0;
  bool previousDelta = delta(0);
  if (canBeHitAsOrigin(pathVertex(path, 0)) && !previousDelta) bits |= 1;
  for (int sp = 1; sp < n; ++sp) {
    const bool d = delta(sp);
    const bool lensToInfinity = sp == 1 && n == 2 && pathVertex(path, 0).isInfinite;
    if (!previousDelta && !d && !lensToInfinity) bits |= uint64_t{1} << sp;
    previousDelta = d;
  }
  return bits | mergeableTechniques(path);
}

}  // namespace pathlab
