// A bidirectional sampling technique (s, t) and the one numbering of all of them that every
// per-technique table indexes by: the technique set, the pyramid's films, the counters, the grid.
#pragma once

#include <cmath>
#include <cstddef>
#include <iterator>

namespace pathlab {

// The longest technique anything names: a table of every technique up to length n has about n^2 / 2
// entries, and the bidirectional tracers connect O(n^2) prefix pairs; beyond this, nothing is gained.
inline constexpr int kMaxTechniqueLength = 4096;

// s light subpath vertices and t camera subpath vertices, joined into a path of s + t - 1 edges
// (Veach 1997, sec. 10.2). s = 0: the camera subpath hits an emitter; t = 1: light tracing.
struct Technique {
  int s = 0, t = 1;

  constexpr int length() const { return s + t - 1; }
  // s >= 0, t >= 1 and at least one edge.
  constexpr bool valid() const { return s >= 0 && t >= 1 && length() >= 1; }
  // Lengths one after another, s = 0..k within length k (Veach's fig. 10.3 read row by row):
  // the techniques of length k start at (k - 1)(k + 2) / 2. Valid techniques only.
  constexpr size_t index() const { return firstIndexOfLength(length()) + static_cast<size_t>(s); }
  // Number of techniques of length 1..maxLength, which is also the index of the first longer one.
  static constexpr size_t countUpTo(int maxLength) { return firstIndexOfLength(maxLength + 1); }
  static constexpr size_t firstIndexOfLength(int k) {
    return static_cast<size_t>(k - 1) * static_cast<size_t>(k + 2) / 2;
  }
  // The technique whose index() is i: the largest k with (k - 1)(k + 2) / 2 <= i, from the root
  // of k^2 + k - 2 = 2i, then corrected for rounding.
  static Technique fromIndex(size_t i) {
    int k = static_cast<int>((std::sqrt(8.0 * static_cast<double>(i) + 9.0) - 1.0) / 2.0);
    while (k > 1 && firstIndexOfLength(k) > i) --k;
    while (firstIndexOfLength(k + 1) <= i) ++k;
    const int s = static_cast<int>(i - firstIndexOfLength(k));
    return Technique{s, k + 1 - s};
  }

  bool operator==(const Technique&) const = default;
};

// The techniques of a range of lengths in index order; see techniquesOfLength and techniquesUpTo.
class TechniqueRange {
 public:
  class Iterator {
   public:
    using value_type = Technique;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    constexpr Iterator(int s, int k) : s_(s), k_(k) {}
    constexpr Technique operator*() const { return Technique{s_, k_ + 1 - s_}; }
    constexpr Iterator& operator++() {
      if (++s_ > k_) s_ = 0, ++k_;
      return *this;
    }
    constexpr Iterator operator++(int) {
      Iterator old = *this;
      ++*this;
      return old;
    }
    bool operator==(const Iterator&) const = default;

   private:
    int s_ = 0, k_ = 1;
  };

  // Lengths first..last (none when last < first).
  constexpr TechniqueRange(int first, int last) : first_(first), last_(last < first ? first - 1 : last) {}
  constexpr Iterator begin() const { return Iterator(0, first_); }
  constexpr Iterator end() const { return Iterator(0, last_ + 1); }

 private:
  int first_, last_;
};

// (0, k + 1), (1, k), ..., (k, 1): every technique of length k, by s. Replaces the hand-written
// `for (s = 0; s <= k; ++s) { t = k + 1 - s; ... }`.
constexpr TechniqueRange techniquesOfLength(int k) { return TechniqueRange(k, k); }
// Every technique of length 1..maxLength, in index order.
constexpr TechniqueRange techniquesUpTo(int maxLength) { return TechniqueRange(1, maxLength); }

}  // namespace pathlab
