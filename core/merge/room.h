// Buffers that a progressive render refills every pass with about as many elements: grown with a
// quarter of headroom, so that a pass a little larger than the last does not reallocate (and have
// the kernel fault in a fresh copy of a store of hundreds of megabytes: the merge pass's vertices
// at 512² are 150 MB, and a reallocation cost a third of a second; docs/benchmarks.md, session 17).
#pragma once

#include <cstddef>
#include <vector>

namespace pathlab {

template <class T>
void resizeWithRoom(std::vector<T>& v, size_t n) {
  if (n > v.capacity()) v.reserve(n + n / 4);
  v.resize(n);
}

template <class T>
void assignWithRoom(std::vector<T>& v, size_t n, const T& value) {
  if (n > v.capacity()) v.reserve(n + n / 4);
  v.assign(n, value);
}

}  // namespace pathlab
