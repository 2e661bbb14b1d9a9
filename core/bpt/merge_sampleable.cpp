// sampleableWithMerges: the connections' bits from sampleableTechniques, then the merges'.
#include "core/bpt/merge_sampleable.h"

namespace pathlab {

uint64_t sampleableWithMerges(const MisPath& path, TechniqueKind formedBy, MergeSite site) {
  const int s = path.s, n = path.s + path.t, k = n - 1;
  uint64_t bits = sampleableTechniques(path);
  if (n > kSampleableBits) return bits;
  auto vertex = [&](int i) -> const PathVertex& {
    return i < s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i);
  };
  const bool merged = formedBy == TechniqueKind::Merge;
  // sampleableTechniques took x(s) as a connection's end: in a merge's path it is z(t-2), which the
  // connections C(s) (x(s-1) -- x(s)) and C(s + 1) (x(s) -- x(s+1)) cannot join if it is delta.
  if (merged && s < n && vertex(s).isDelta) {
    bits &= ~(uint64_t{1} << s);
    if (s + 1 <= k) bits &= ~(uint64_t{1} << (s + 1));
  }
  // A connection's joined ends scattered through the connection, not by a delta lobe.
  auto delta = [&](int i) { return vertex(i).isDelta && (merged || (i != s - 1 && i != s)); };
  // Progressive photon mapping merges only at the camera subpath's first vertex that is not a
  // delta scatter: x(firstSite - 1), every vertex after it (x(firstSite) .. x(n-2)) delta.
  int firstSite = n - 1;
  if (site == MergeSite::FirstNonSpecular)
    while (firstSite >= 2 && delta(firstSite - 1)) --firstSite;
  for (int sp = 2; sp <= k && k - 1 + sp < 64; ++sp) {
    const int i = sp - 1;  // the merged vertex
    if (site == MergeSite::FirstNonSpecular && sp != firstSite) continue;
    if (vertex(i).type == VertexType::Surface && !delta(i)) bits |= uint64_t{1} << (k - 1 + sp);
  }
  return bits;
}

}  // namespace pathlab
