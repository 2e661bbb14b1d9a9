// TechniqueSet: rules and listed techniques kept canonical, the SPEC parser and printer.
#include "core/bpt/technique_set.h"

#include "core/sampling/technique_label.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <stdexcept>

namespace pathlab {

namespace {

using Bits = std::vector<uint64_t>;

void setBit(Bits& bits, size_t i) {
  if (bits.size() <= i / 64) bits.resize(i / 64 + 1, 0);
  bits[i / 64] |= uint64_t{1} << (i % 64);
}

void clearBit(Bits& bits, size_t i) {
  if (i / 64 < bits.size()) bits[i / 64] &= ~(uint64_t{1} << (i % 64));
}

void trim(Bits& bits) {
  while (!bits.empty() && bits.back() == 0) bits.pop_back();
}

// Calls fn(i) for every set bit, ascending.
template <typename Fn>
void forEachBit(const Bits& bits, Fn&& fn) {
  for (size_t w = 0; w < bits.size(); ++w)
    for (uint64_t word = bits[w]; word != 0; word &= word - 1)
      fn(w * 64 + static_cast<size_t>(std::countr_zero(word)));
}

// The highest set bit + 1 (0 when none).
size_t bitEnd(const Bits& bits) {
  return bits.empty() ? 0 : (bits.size() - 1) * 64 + static_cast<size_t>(64 - std::countl_zero(bits.back()));
}

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

int parseInt(const std::string& text, const std::string& item) {
  const std::string t = trimmed(text);
  int v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size())
    throw std::invalid_argument("techniques: '" + item + "': '" + t + "' is not an integer");
  return v;
}

void checkRange(int v, int lo, const char* what, const std::string& item) {
  if (v < lo || v > kMaxTechniqueLength)
    throw std::invalid_argument("techniques: '" + item + "': need " + std::to_string(lo) + " <= " + what +
                                " <= " + std::to_string(kMaxTechniqueLength));
}

}  // namespace

TechniqueSet TechniqueSet::all() {
  TechniqueSet set;
  set.all_ = true;
  return set;
}

TechniqueSet TechniqueSet::withS(int s) {
  checkRange(s, 0, "s", "s=" + std::to_string(s));
  TechniqueSet set;
  setBit(set.sRule_, static_cast<size_t>(s));
  return set;
}

TechniqueSet TechniqueSet::withT(int t) {
  checkRange(t, 1, "t", "t=" + std::to_string(t));
  TechniqueSet set;
  setBit(set.tRule_, static_cast<size_t>(t));
  return set;
}

TechniqueSet TechniqueSet::ofLength(int k) {
  checkRange(k, 1, "k", "k=" + std::to_string(k));
  TechniqueSet set;
  for (Technique x : techniquesOfLength(k, TechniqueFamilies::Connections | TechniqueFamilies::Equiangular)) setBit(set.listed_, x.index());
  return set;
}

TechniqueSet TechniqueSet::mergesOfLength(int k) {
  checkRange(k, 2, "k", "m=" + std::to_string(k));
  TechniqueSet set;
  for (Technique x : techniquesOfLength(k, TechniqueFamilies::Merges)) setBit(set.listed_, x.index());
  return set;
}

TechniqueSet TechniqueSet::allMerges() {
  TechniqueSet set;
  set.allMerges_ = true;
  return set;
}

TechniqueSet TechniqueSet::pathTracing() { return withS(0) | withS(1); }

TechniqueSet TechniqueSet::lightTracing() { return withT(1); }

void TechniqueSet::normalise() {
  if (allMerges_)  // every merge: none remains to list
    forEachBit(listed_, [&](size_t i) {
      if (Technique::fromIndex(i).isMerge()) clearBit(listed_, i);
    });
  if (all_) {  // every connection and equiangular technique: only listed merges remain to say
    sRule_.clear(), tRule_.clear();
    forEachBit(listed_, [&](size_t i) {
      if (!Technique::fromIndex(i).isMerge()) clearBit(listed_, i);
    });
    trim(listed_);
    return;
  }
  trim(sRule_), trim(tRule_);
  if (!sRule_.empty() || !tRule_.empty())
    forEachBit(listed_, [&](size_t i) {
      if (coveredByRule(Technique::fromIndex(i))) clearBit(listed_, i);
    });
  trim(listed_);
}

void TechniqueSet::enable(Technique x) {
  if (!x.valid() || x.length() > kMaxTechniqueLength)
    throw std::invalid_argument("techniques: " + techniqueLabel(x) + " is not a technique of length 1.." +
                                std::to_string(kMaxTechniqueLength));
  if (!coveredByRule(x)) setBit(listed_, x.index());
}

void TechniqueSet::disable(Technique x, int maxLength) {
  if (!contains(x)) return;
  if (x.isMerge() && allMerges_) {  // "m=all" has no hole either: its merges up to maxLength, listed
    allMerges_ = false;
    for (const Technique m : techniquesUpTo(maxLength, TechniqueFamilies::Merges)) setBit(listed_, m.index());
  }
  if (coveredByRule(x)) *this = upToKeepingMergeRule(maxLength);
  clearBit(listed_, x.index());
  trim(listed_);
}

void TechniqueSet::disable(const TechniqueSet& group, int maxLength) {
  if (group.allMerges_) {
    allMerges_ = false;
    forEachBit(listed_, [&](size_t i) {
      if (Technique::fromIndex(i).isMerge()) clearBit(listed_, i);
    });
    trim(listed_);
  }
  if (group.all_) {  // every connection goes; the merges the group does not list stay
    TechniqueSet r;
    r.allMerges_ = allMerges_;
    forEachBit(listed_, [&](size_t i) {
      if (const Technique x = Technique::fromIndex(i); x.isMerge() && !group.contains(x)) setBit(r.listed_, i);
    });
    *this = r;
    return;
  }
  // A rule cannot have a hole: "all" becomes its connections, listed, when the group takes any
  // connection (merges are never under a rule).
  if (all_ && without(group.families(), TechniqueFamilies::Merges) != TechniqueFamilies{})
    *this = upToKeepingMergeRule(maxLength);
  forEachBit(group.sRule_, [&](size_t s) { clearBit(sRule_, s); });
  forEachBit(group.tRule_, [&](size_t t) { clearBit(tRule_, t); });
  normalise();
  for (const Technique x : techniquesUpTo(maxLength, TechniqueFamilies::All))
    if (group.contains(x)) disable(x, maxLength);
}

TechniqueSet& TechniqueSet::operator|=(const TechniqueSet& o) {
  all_ = all_ || o.all_;
  allMerges_ = allMerges_ || o.allMerges_;
  auto unite = [](Bits& a, const Bits& b) {
    if (a.size() < b.size()) a.resize(b.size(), 0);
    for (size_t i = 0; i < b.size(); ++i) a[i] |= b[i];
  };
  unite(sRule_, o.sRule_);
  unite(tRule_, o.tRule_);
  unite(listed_, o.listed_);
  normalise();
  return *this;
}

TechniqueSet operator&(const TechniqueSet& a, const TechniqueSet& b) {
  // "all" is every connection and its merges: with it, the other set keeps its connections and
  // the merges both have.
  auto withAll = [](const TechniqueSet& allSet, const TechniqueSet& other) {
    TechniqueSet r = other;
    r.allMerges_ = other.allMerges_ && allSet.allMerges_;
    if (other.allMerges_ && !allSet.allMerges_)
      forEachBit(allSet.listed_, [&](size_t i) {
        if (Technique::fromIndex(i).isMerge()) setBit(r.listed_, i);
      });
    forEachBit(other.listed_, [&](size_t i) {
      if (const Technique x = Technique::fromIndex(i); x.isMerge() && !allSet.contains(x)) clearBit(r.listed_, i);
    });
    r.normalise();
    return r;
  };
  if (a.all_) return withAll(a, b);
  if (b.all_) return withAll(b, a);
  TechniqueSet r;
  r.allMerges_ = a.allMerges_ && b.allMerges_;
  auto intersect = [](const TechniqueSet::Bits& x, const TechniqueSet::Bits& y) {
    TechniqueSet::Bits out(std::min(x.size(), y.size()));
    for (size_t i = 0; i < out.size(); ++i) out[i] = x[i] & y[i];
    return out;
  };
  r.sRule_ = intersect(a.sRule_, b.sRule_);
  r.tRule_ = intersect(a.tRule_, b.tRule_);
  // An s = S line and a t = T line meet in the one technique (S, T).
  auto cross = [&](const TechniqueSet& p, const TechniqueSet& q) {
    forEachBit(p.sRule_, [&](size_t s) {
      forEachBit(q.tRule_, [&](size_t t) {
        const Technique x{static_cast<int>(s), static_cast<int>(t)};
        if (x.valid() && x.length() <= kMaxTechniqueLength) setBit(r.listed_, x.index());
        // ... and, for s = 1, in E(1, T) too.
        if (const Technique e = Technique::equiangular(static_cast<int>(t));
            s == 1 && e.valid() && e.length() <= kMaxTechniqueLength)
          setBit(r.listed_, e.index());
      });
    });
    forEachBit(p.listed_, [&](size_t i) {
      if (q.contains(Technique::fromIndex(i))) setBit(r.listed_, i);
    });
  };
  cross(a, b);
  cross(b, a);
  r.normalise();
  return r;
}

TechniqueSet TechniqueSet::upTo(int maxLength) const {
  TechniqueSet r;
  if (maxLength < 1) return r;
  const size_t end = Technique::countUpTo(maxLength);
  if (all_)  // every connection and equiangular technique, then the listed merges below
    for (const Technique x : techniquesUpTo(maxLength, TechniqueFamilies::Connections | TechniqueFamilies::Equiangular)) setBit(r.listed_, x.index());
  if (allMerges_)
    for (const Technique x : techniquesUpTo(maxLength, TechniqueFamilies::Merges)) setBit(r.listed_, x.index());
  forEachBit(listed_, [&](size_t i) {
    if (i < end) setBit(r.listed_, i);
  });
  // The s = S line starts at length max(S, 1), the t = T line at max(T - 1, 1).
  forEachBit(sRule_, [&](size_t s) {
    for (int k = std::max(static_cast<int>(s), 1); k <= maxLength; ++k)
      setBit(r.listed_, Technique{static_cast<int>(s), k + 1 - static_cast<int>(s)}.index());
    if (s == 1)  // E(1, k) beside C(1, k)
      for (int k = 2; k <= maxLength; ++k) setBit(r.listed_, Technique::equiangular(k).index());
  });
  forEachBit(tRule_, [&](size_t t) {
    for (int k = std::max(static_cast<int>(t) - 1, 1); k <= maxLength; ++k)
      setBit(r.listed_, Technique{k + 1 - static_cast<int>(t), static_cast<int>(t)}.index());
    if (t >= 2 && static_cast<int>(t) <= maxLength) setBit(r.listed_, Technique::equiangular(static_cast<int>(t)).index());
  });
  trim(r.listed_);
  return r;
}

TechniqueSet TechniqueSet::upToKeepingMergeRule(int maxLength) const {
  TechniqueSet r = upTo(maxLength);
  r.allMerges_ = allMerges_;
  r.normalise();
  return r;
}

TechniqueSet TechniqueSet::fittedTo(int maxLength) const {
  TechniqueSet r = *this;
  const size_t end = Technique::countUpTo(std::max(maxLength, 0));
  for (size_t i = end; i < bitEnd(r.listed_); ++i) clearBit(r.listed_, i);
  trim(r.listed_);
  return r;
}

void TechniqueSet::checkFits(int maxLength) const {
  if (const size_t end = bitEnd(listed_); end > Technique::countUpTo(maxLength)) {
    const Technique x = Technique::fromIndex(end - 1);
    throw std::invalid_argument("techniques: " + techniqueLabel(x) + " has length " + std::to_string(x.length()) +
                                ", more than the maximum length " + std::to_string(maxLength));
  }
  if (!anyUpTo(maxLength))
    throw std::invalid_argument("techniques: no technique of length 1.." + std::to_string(maxLength) + " is enabled");
}

int TechniqueSet::count(int maxLength) const {
  int n = 0;
  for (uint64_t word : upTo(maxLength).listed_) n += std::popcount(word);
  return n;
}

bool TechniqueSet::anyUpTo(int maxLength) const {
  if (maxLength < 1) return false;
  if (all_ || (allMerges_ && maxLength >= 2)) return true;
  bool any = false;
  forEachBit(listed_, [&](size_t i) { any = any || i < Technique::countUpTo(maxLength); });
  forEachBit(sRule_, [&](size_t s) { any = any || std::max(static_cast<int>(s), 1) <= maxLength; });
  forEachBit(tRule_, [&](size_t t) { any = any || std::max(static_cast<int>(t) - 1, 1) <= maxLength; });
  return any;
}

bool TechniqueSet::containsAllUpTo(int maxLength, TechniqueFamilies families) const {
  const TechniqueRange range = techniquesUpTo(maxLength, families);
  if (all_ && !covers(families, TechniqueKind::Merge)) return true;
  return std::all_of(range.begin(), range.end(), [&](Technique x) { return contains(x); });
}

TechniqueFamilies TechniqueSet::families() const {
  // A rule covers connections and (through s = 1 or t >= 2) equiangular techniques.
  unsigned f = (all_ || !sRule_.empty() || !tRule_.empty() ? 1u : 0u) | (allMerges_ ? 2u : 0u);
  if (all_ || test(sRule_, 1)) f |= 4u;
  forEachBit(tRule_, [&](size_t t) { f |= t >= 2 ? 4u : 0u; });
  forEachBit(listed_, [&](size_t i) { f |= 1u << static_cast<unsigned>(Technique::fromIndex(i).kind); });
  return static_cast<TechniqueFamilies>(f);
}

std::vector<int> TechniqueSet::uncoveredLengths(int maxLength) const {
  std::vector<int> out;
  if (all_) return out;
  for (int k = 1; k <= maxLength; ++k) {
    const TechniqueRange row = techniquesOfLength(k, TechniqueFamilies::All);
    if (std::none_of(row.begin(), row.end(), [&](Technique x) { return contains(x); })) out.push_back(k);
  }
  return out;
}

std::string TechniqueSet::toString() const {
  std::string out = all_ ? "all" : "";
  auto item = [&](const std::string& text) { out += (out.empty() ? "" : ";") + text; };
  forEachBit(sRule_, [&](size_t s) { item("s=" + std::to_string(s)); });
  forEachBit(tRule_, [&](size_t t) { item("t=" + std::to_string(t)); });
  const size_t end = bitEnd(listed_);
  for (int k = 1; end > 0 && k <= Technique::fromIndex(end - 1).length(); ++k) {
    const TechniqueRange row = techniquesOfLength(k, TechniqueFamilies::Connections | TechniqueFamilies::Equiangular);
    if (std::none_of(row.begin(), row.end(), [&](Technique x) { return test(listed_, x.index()); })) continue;
    if (std::all_of(row.begin(), row.end(), [&](Technique x) { return contains(x); })) {
      item("k=" + std::to_string(k));
      continue;
    }
    for (Technique x : row)
      if (test(listed_, x.index())) item((x.isEquiangular() ? "E" : "") + std::to_string(x.s) + "," + std::to_string(x.t));
  }
  // Then the merges: "m=all", or by length "m=K" for all of a length's, else "MS,T" one by one.
  if (allMerges_) item("m=all");
  for (int k = 2; end > 0 && k <= Technique::fromIndex(end - 1).length(); ++k) {
    const TechniqueRange row = techniquesOfLength(k, TechniqueFamilies::Merges);
    if (std::none_of(row.begin(), row.end(), [&](Technique x) { return test(listed_, x.index()); })) continue;
    if (std::all_of(row.begin(), row.end(), [&](Technique x) { return test(listed_, x.index()); })) {
      item("m=" + std::to_string(k));
      continue;
    }
    for (Technique x : row)
      if (test(listed_, x.index())) item("M" + std::to_string(x.s) + "," + std::to_string(x.t));
  }
  return out;
}

TechniqueSet TechniqueSet::parse(const std::string& spec) {
  if (trimmed(spec).empty()) throw std::invalid_argument("techniques: empty specification");
  TechniqueSet set;
  size_t start = 0;
  while (start <= spec.size()) {
    const size_t end = std::min(spec.find(';', start), spec.size());
    const std::string item = trimmed(spec.substr(start, end - start));
    start = end + 1;
    if (item.empty()) throw std::invalid_argument("techniques: empty item in '" + spec + "'");
    if (item == "all") {
      set.all_ = true;
    } else if (item.size() > 2 && item[1] == '=' && (item[0] == 's' || item[0] == 't' || item[0] == 'k')) {
      const int v = parseInt(item.substr(2), item);
      checkRange(v, item[0] == 's' ? 0 : 1, item.substr(0, 1).c_str(), item);
      set |= item[0] == 's' ? withS(v) : item[0] == 't' ? withT(v) : ofLength(v);
    } else if (item == "m=all") {
      set.allMerges_ = true;
    } else if (item.size() > 2 && item[0] == 'm' && item[1] == '=') {
      const int v = parseInt(item.substr(2), item);
      checkRange(v, 2, "k", item);
      set |= mergesOfLength(v);
    } else if (const size_t comma = item.find(','); comma != std::string::npos) {
      const bool merge = item[0] == 'M', equiangular = item[0] == 'E';
      const size_t from = merge || equiangular ? 1 : 0;
      const Technique x{parseInt(item.substr(from, comma - from), item), parseInt(item.substr(comma + 1), item),
                        merge ? TechniqueKind::Merge : equiangular ? TechniqueKind::Equiangular : TechniqueKind::Connection};
      if (merge && (x.s < 2 || x.t < 2))
        throw std::invalid_argument("techniques: '" + item + "': a merge needs s >= 2 and t >= 2");
      if (equiangular && (x.s != 1 || x.t < 2))
        throw std::invalid_argument("techniques: '" + item + "': an equiangular technique needs s = 1 and t >= 2");
      if (x.s < 0 || x.t < 1) throw std::invalid_argument("techniques: '" + item + "': need s >= 0 and t >= 1");
      if (!x.valid() || x.length() > kMaxTechniqueLength)
        throw std::invalid_argument("techniques: '" + item + "' is not a technique of length 1.." +
                                    std::to_string(kMaxTechniqueLength));
      set.enable(x);
    } else {
      throw std::invalid_argument("techniques: '" + item + "' is not S,T, MS,T, E1,T, s=S, t=T, k=K, m=K, m=all or all");
    }
    if (end == spec.size()) break;
  }
  set.normalise();
  return set;
}

}  // namespace pathlab
