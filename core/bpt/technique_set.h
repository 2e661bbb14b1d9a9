// The set of enabled bidirectional sampling techniques (s, t): s light vertices, t camera
// vertices, path length s + t - 1 edges (Veach 1997, sec. 10.2). s >= 0, t >= 1.
#pragma once

#include <string>
#include <vector>

namespace pathlab {

class TechniqueSet {
 public:
  TechniqueSet() = default;
  explicit TechniqueSet(int maxLength);  // empty

  static TechniqueSet all(int maxLength);
  // SPEC: ';'-separated items "S,T", "s=S", "t=T", "k=K" (every technique of length K), "all".
  // Throws std::invalid_argument naming the item on bad input or a technique longer than maxLength.
  static TechniqueSet parse(const std::string& spec, int maxLength);

  int maxLength() const { return maxLength_; }
  // True when (s, t) is a technique of length <= maxLength (s >= 0, t >= 1).
  bool valid(int s, int t) const { return s >= 0 && t >= 1 && s + t - 1 >= 1 && s + t - 1 <= maxLength_; }
  bool contains(int s, int t) const { return valid(s, t) && bits_[index(s, t)]; }
  void enable(int s, int t);
  void disable(int s, int t);
  int size() const;  // number of enabled techniques
  // Lengths 1..maxLength that no enabled technique can sample (their light is missing).
  std::vector<int> uncoveredLengths() const;
  std::string toString() const;

  bool operator==(const TechniqueSet&) const = default;

 private:
  // Techniques of length k (edges) are s = 0..k; they start at (k - 1)(k + 2) / 2.
  static size_t index(int s, int t) {
    const int k = s + t - 1;
    return static_cast<size_t>((k - 1) * (k + 2) / 2 + s);
  }
  int maxLength_ = 0;
  std::vector<bool> bits_;
};

}  // namespace pathlab
