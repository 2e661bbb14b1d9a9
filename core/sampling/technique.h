// A path sampling technique, a connection C(s, t) or a merge M(s, t), and the one numbering of all
// of them that every per-technique table indexes by: the technique set, the pyramid's films, the
// counters, the grid, the maps and the check.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>

namespace pathlab {

// The longest technique anything names: a table of every technique up to length n has about n^2
// entries, and the bidirectional tracers connect O(n^2) prefix pairs; beyond this, nothing is gained.
inline constexpr int kMaxTechniqueLength = 4096;

// The families of techniques. A connection joins two subpaths' endpoints by an edge (Veach 1997,
// sec. 10.2); a merge (vertex merging, Georgiev et al. 2012, sec. 4) takes a light subpath vertex
// and a camera subpath vertex closer than a radius as one vertex.
// The equiangular family E(1, t) (core/bpt/equiangular_technique.h) samples the medium vertex that
// C(1, t) connects to the light by a second density.
enum class TechniqueKind : uint8_t { Connection, Merge, Equiangular };

// Which families a table or a loop covers (a bit per TechniqueKind).
enum class TechniqueFamilies : uint8_t { Connections = 1, Merges = 2, Equiangular = 4, All = 7 };
constexpr bool covers(TechniqueFamilies f, TechniqueKind k) {
  return (static_cast<unsigned>(f) >> static_cast<unsigned>(k)) & 1u;
}
constexpr TechniqueFamilies operator|(TechniqueFamilies a, TechniqueFamilies b) {
  return static_cast<TechniqueFamilies>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
constexpr TechniqueFamilies operator&(TechniqueFamilies a, TechniqueFamilies b) {
  return static_cast<TechniqueFamilies>(static_cast<unsigned>(a) & static_cast<unsigned>(b));
}
// The families without `b`.
constexpr TechniqueFamilies without(TechniqueFamilies a, TechniqueFamilies b) {
  return static_cast<TechniqueFamilies>(static_cast<unsigned>(a) & ~static_cast<unsigned>(b));
}

// s light subpath vertices and t camera subpath vertices. Connection C(s, t): joined by an edge into
// a path of s + t - 1 edges (s = 0: the camera subpath hits an emitter; t = 1: light tracing).
// Equiangular E(1, t): the path of C(1, t) with its last camera vertex z(t-1) placed in a medium by
// equiangular sampling toward the light point (Kulla and Fajardo 2012) rather than by the walk's
// distance sampling; t >= 2, so a length k >= 2 has one.
// Merge M(s, t): y_{s-1} and z_{t-1} become one vertex, a path of s + t - 2 edges; neither may be on
// the light or at the camera, so s, t >= 2 and a length k has k - 1 merges.
struct Technique {
  int s = 0, t = 1;
  TechniqueKind kind = TechniqueKind::Connection;

  static constexpr Technique merge(int s, int t) { return Technique{s, t, TechniqueKind::Merge}; }
  static constexpr Technique equiangular(int t) { return Technique{1, t, TechniqueKind::Equiangular}; }

  constexpr bool isMerge() const { return kind == TechniqueKind::Merge; }
  constexpr bool isEquiangular() const { return kind == TechniqueKind::Equiangular; }
  constexpr int length() const { return s + t - (isMerge() ? 2 : 1); }
  constexpr bool valid() const {
    return isMerge() ? s >= 2 && t >= 2 : isEquiangular() ? s == 1 && t >= 2 : s >= 0 && t >= 1 && length() >= 1;
  }

  // One index space, lengths one after another; within length k the k + 1 connections by s
  // (Veach's fig. 10.3 read row by row), then its k - 1 merges by s, then (k >= 2) its equiangular
  // technique. Length 1 holds 2 techniques and a length k >= 2 holds 2k + 1, so length k >= 2
  // starts at k^2 - 2. Valid techniques only.
  constexpr size_t index() const { return firstIndexOfLength(length()) + static_cast<size_t>(slot()); }
  // The position within its length, index() - firstIndexOfLength(length()): s for a connection
  // (so per-length tables and bit masks over s keep their meaning), k - 1 + s for a merge, 2k for
  // the equiangular technique.
  constexpr int slot() const { return isMerge() ? length() - 1 + s : isEquiangular() ? 2 * length() : s; }
  // The number of slots of length k.
  static constexpr int slotsOfLength(int k) { return k <= 1 ? 2 * k : 2 * k + 1; }
  // The technique at slot r of length k (0 <= r < slotsOfLength(k)).
  static constexpr Technique atSlot(int k, int r) {
    return r <= k ? Technique{r, k + 1 - r} : r < 2 * k ? merge(r - k + 1, 2 * k + 1 - r) : equiangular(k);
  }
  // Number of techniques of length 1..maxLength, which is also the index of the first longer one.
  static constexpr size_t countUpTo(int maxLength) { return firstIndexOfLength(maxLength + 1); }
  // Those of some families only: k + 1 connections, k - 1 merges and (k >= 2) one equiangular a length.
  static constexpr size_t countUpTo(int maxLength, TechniqueFamilies f) {
    const size_t n = static_cast<size_t>(maxLength < 0 ? 0 : maxLength);
    return (covers(f, TechniqueKind::Connection) ? n * (n + 3) / 2 : 0) +
           (covers(f, TechniqueKind::Merge) && n > 0 ? n * (n - 1) / 2 : 0) +
           (covers(f, TechniqueKind::Equiangular) && n > 0 ? n - 1 : 0);
  }
  static constexpr size_t firstIndexOfLength(int k) {
    return k <= 1 ? 0 : static_cast<size_t>(k) * static_cast<size_t>(k) - 2;
  }
  // The technique whose index() is i: the largest k with firstIndexOfLength(k) <= i, from the
  // root of k^2 - 2 = i, then corrected for rounding.
  static Technique fromIndex(size_t i) {
    int k = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(i) + 2.0)));
    while (k > 1 && firstIndexOfLength(k) > i) --k;
    while (firstIndexOfLength(k + 1) <= i) ++k;
    return atSlot(k, static_cast<int>(i - firstIndexOfLength(k)));
  }
  // The index among the techniques of its own family only (connections: Veach's row-by-row
  // numbering). Colours are keyed by it, so a connection's colour does not depend on which other
  // families exist.
  constexpr size_t familyIndex() const {
    const size_t k = static_cast<size_t>(length());
    return isMerge()         ? (k - 2) * (k - 1) / 2 + static_cast<size_t>(s - 2)
           : isEquiangular() ? k - 2
                             : (k - 1) * (k + 2) / 2 + static_cast<size_t>(s);
  }

  bool operator==(const Technique&) const = default;
};

// The techniques of a range of lengths and families, in index order; see techniquesOfLength and
// techniquesUpTo.
class TechniqueRange {
 public:
  class Iterator {
   public:
    using value_type = Technique;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    // Slot r of length k (index() - firstIndexOfLength(k)), moved on to the first covered slot.
    constexpr Iterator(int k, int r, int last, TechniqueFamilies families)
        : k_(k), r_(r), last_(last), families_(families) {
      settle();
    }
    constexpr Technique operator*() const { return Technique::atSlot(k_, r_); }
    constexpr Iterator& operator++() {
      ++r_;
      settle();
      return *this;
    }
    constexpr Iterator operator++(int) {
      Iterator old = *this;
      ++*this;
      return old;
    }
    constexpr bool operator==(const Iterator& o) const { return k_ == o.k_ && r_ == o.r_; }

   private:
    // Skips the slots of a family not covered, and past the last length stops at (last + 1, 0),
    // which is end().
    constexpr void settle() {
      for (;;) {
        if (k_ > last_) {
          r_ = 0;
          return;
        }
        if (r_ <= k_) {
          if (covers(families_, TechniqueKind::Connection)) return;
          r_ = k_ + 1;
        }
        if (r_ < 2 * k_) {
          if (covers(families_, TechniqueKind::Merge)) return;
          r_ = 2 * k_;
        }
        if (r_ == 2 * k_ && k_ >= 2 && covers(families_, TechniqueKind::Equiangular)) return;
        ++k_, r_ = 0;
      }
    }

    int k_ = 1, r_ = 0, last_ = 0;
    TechniqueFamilies families_ = TechniqueFamilies::Connections;
  };

  // Lengths first..last (none when last < first).
  constexpr TechniqueRange(int first, int last, TechniqueFamilies families = TechniqueFamilies::Connections)
      : first_(first), last_(last < first ? first - 1 : last), families_(families) {}
  constexpr Iterator begin() const { return Iterator(first_, 0, last_, families_); }
  constexpr Iterator end() const { return Iterator(last_ + 1, 0, last_, families_); }

 private:
  int first_, last_;
  TechniqueFamilies families_;
};

// C(0, k + 1), C(1, k), ..., C(k, 1), then M(2, k), ..., M(k, 2) when merges are asked for, then
// E(1, k) when the equiangular family is: every
// technique of length k of those families, in index order. Replaces the hand-written
// `for (s = 0; s <= k; ++s) { t = k + 1 - s; ... }`.
constexpr TechniqueRange techniquesOfLength(int k, TechniqueFamilies f = TechniqueFamilies::Connections) {
  return TechniqueRange(k, k, f);
}
// Every technique of length 1..maxLength of those families, in index order.
constexpr TechniqueRange techniquesUpTo(int maxLength, TechniqueFamilies f = TechniqueFamilies::Connections) {
  return TechniqueRange(1, maxLength, f);
}

}  // namespace pathlab
