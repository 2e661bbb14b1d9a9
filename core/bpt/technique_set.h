// The set of enabled path sampling techniques, connections C(s, t) and merges M(s, t)
// (core/sampling/technique.h), as a value: compared with ==, parsed from a SPEC only at the edges (CLI, the viewer's text field,
// presets, converge configurations) and printed back in one canonical form.
#pragma once

#include "core/sampling/technique.h"

#include <cstdint>
#include <string>
#include <vector>

namespace pathlab {

// A set of techniques of every length, independent of the maximum path length. It is the union of
// rules that hold at every length ("all", "s=S": every technique with S light vertices, "t=T")
// and of listed techniques (what "S,T" and "k=K" name, and what the viewer's grid switches one by
// one). So when the maximum length changes the set does not: "all", "s=0;s=1" and "t=1" take in
// the new lengths by themselves, listed techniques stay what they were, and a tracer simply never
// asks about lengths beyond its maximum. (Front ends that shorten the maximum drop the listed
// techniques that no longer fit, ui/estimator/technique_grid.h, since a listed technique longer than the
// maximum is refused by validateSettings.)
//
// The rules "all", "s=S", "t=T" and "k=K" name connections and the equiangular techniques E(1, t),
// which have one light vertex and stand beside C(1, t) ("all" is every one of them, what bpt
// samples; E(1, t) is sampled only where --medium-sampling and the scene's media allow, see
// sampledFamilies in core/render/render_settings.h), and "E1,T" lists one;
// "m=all" is every merge at every length (with "all": vertex connection and merging), and merges
// are otherwise listed ("MS,T", or "m=K" for every merge of length K).
//
// The representation is canonical (rules as bitsets over s and over t, listed techniques that no
// rule already covers as a bitset over Technique::index(), no trailing zero words), so two sets
// are == exactly when they contain the same techniques: "k=1" equals "0,2;1,1", and
// "s=0;k=2" equals "s=0;1,2;2,1". contains() is a few word tests: it is called per connection.
class TechniqueSet {
 public:
  TechniqueSet() = default;  // empty

  static TechniqueSet all();
  static TechniqueSet withS(int s);       // s = S at every length (S >= 0)
  static TechniqueSet withT(int t);       // t = T at every length (T >= 1)
  static TechniqueSet ofLength(int k);    // the k + 1 connections of length k and E(1, k) (k >= 1)
  static TechniqueSet mergesOfLength(int k);  // the k - 1 merges of length k (k >= 2)
  static TechniqueSet allMerges();            // every merge of every length ("m=all")
  // The path tracer's two techniques, s <= 1: the camera subpath hits an emitter (s = 0) or
  // connects to a light sample (s = 1, next-event estimation).
  static TechniqueSet pathTracing();
  // Light tracing, t = 1: light subpaths connected to the camera and splatted on the film.
  static TechniqueSet lightTracing();

  // SPEC: ';'-separated items "S,T", "s=S", "t=T", "k=K" (every connection of length K and E(1,K)),
  // "all" (every connection and equiangular technique), "E1,T" (an equiangular technique), "MS,T" (a merge), "m=K" (every merge of length K), "m=all"; their union. Throws std::invalid_argument naming the item on bad input or an empty SPEC.
  // Lengths are checked against a maximum only by checkFits.
  static TechniqueSet parse(const std::string& spec);

  bool contains(int s, int t) const {
    if (s < 0 || t < 1 || s + t < 2) return false;
    if (all_) return true;
    return test(listed_, Technique{s, t}.index()) || test(sRule_, static_cast<size_t>(s)) ||
           test(tRule_, static_cast<size_t>(t));
  }
  bool contains(Technique x) const {
    if (x.isMerge()) return x.valid() && (allMerges_ || test(listed_, x.index()));
    if (x.isEquiangular()) return x.valid() && (coveredByRule(x) || test(listed_, x.index()));
    return contains(x.s, x.t);
  }

  // Adds one technique; throws std::invalid_argument when it is not valid or longer than
  // kMaxTechniqueLength.
  void enable(Technique x);
  // Removes one technique. A rule cannot have a hole: when one covers x, the set first becomes its
  // techniques of length 1..maxLength, listed (as a click in the viewer's grid does).
  void disable(Technique x, int maxLength);
  // Removes every technique of `group`: its rules that the set holds as rules go as a whole ("s=1"
  // from "s=0;s=1" leaves "s=0"), the rest of it up to maxLength one by one as above.
  void disable(const TechniqueSet& group, int maxLength);

  TechniqueSet& operator|=(const TechniqueSet& o);
  friend TechniqueSet operator|(TechniqueSet a, const TechniqueSet& b) { return a |= b; }
  friend TechniqueSet operator&(const TechniqueSet& a, const TechniqueSet& b);

  // The techniques of length 1..maxLength, listed (no rules).
  TechniqueSet upTo(int maxLength) const;
  // The same rules, without the listed techniques longer than maxLength.
  TechniqueSet fittedTo(int maxLength) const;
  // Throws std::invalid_argument naming the problem when a listed technique is longer than
  // maxLength ("techniques: (s,t) has length k, more than the maximum length M") or when the set
  // has no technique of length 1..maxLength: what a renderer with that maximum length refuses.
  void checkFits(int maxLength) const;

  bool empty() const { return *this == TechniqueSet(); }
  int count(int maxLength) const;  // techniques of length 1..maxLength in the set, of every family
  bool anyUpTo(int maxLength) const;
  // Every technique of length 1..maxLength of those families.
  bool containsAllUpTo(int maxLength, TechniqueFamilies families = TechniqueFamilies::Connections) const;
  // The families the set has a technique of (at any length): what the tables must be made for.
  TechniqueFamilies families() const;
  // Lengths 1..maxLength that no technique of the set can sample (their light is missing).
  std::vector<int> uncoveredLengths(int maxLength) const;

  // The canonical SPEC: "" for the empty set, "all", else the rules ("s=0;s=1;t=1", ascending),
  // then the listed techniques by length, a length whose every technique is in the set as "k=K",
  // the others as "S,T" by s. parse(x.toString()) == x for every non-empty x.
  std::string toString() const;

  bool operator==(const TechniqueSet&) const = default;

 private:
  using Bits = std::vector<uint64_t>;
  static bool test(const Bits& bits, size_t i) { return i / 64 < bits.size() && (bits[i / 64] >> (i % 64)) & 1u; }
  bool coveredByRule(Technique x) const {
    if (x.isMerge()) return false;
    return all_ || test(sRule_, static_cast<size_t>(x.s)) || test(tRule_, static_cast<size_t>(x.t));
  }
  void normalise();
  // upTo, with "m=all" kept as the rule: a hole among the connections lists only them.
  TechniqueSet upToKeepingMergeRule(int maxLength) const;

  bool all_ = false;
  bool allMerges_ = false;  // "m=all"
  Bits sRule_;   // bit S: s = S at every length
  Bits tRule_;   // bit T: t = T at every length
  Bits listed_;  // bit Technique::index(): listed, and covered by no rule
};

}  // namespace pathlab
