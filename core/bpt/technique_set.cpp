// TechniqueSet: enable mask over (s, t) and its SPEC parser.
#include "core/bpt/technique_set.h"

#include <charconv>
#include <stdexcept>

namespace pathlab {

namespace {

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

int parseInt(const std::string& text, const std::string& item) {
  const std::string t = trim(text);
  int v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size())
    throw std::invalid_argument("techniques: '" + item + "': '" + t + "' is not an integer");
  return v;
}

}  // namespace

TechniqueSet::TechniqueSet(int maxLength) : maxLength_(maxLength) {
  if (maxLength < 1) throw std::invalid_argument("techniques: maximum length must be >= 1");
  bits_.assign(static_cast<size_t>(maxLength) * static_cast<size_t>(maxLength + 3) / 2, false);
}

TechniqueSet TechniqueSet::all(int maxLength) {
  TechniqueSet set(maxLength);
  set.bits_.assign(set.bits_.size(), true);
  return set;
}

void TechniqueSet::enable(int s, int t) {
  if (!valid(s, t))
    throw std::invalid_argument("techniques: (" + std::to_string(s) + "," + std::to_string(t) +
                                ") is not a technique of length 1.." + std::to_string(maxLength_));
  bits_[index(s, t)] = true;
}

void TechniqueSet::disable(int s, int t) {
  if (valid(s, t)) bits_[index(s, t)] = false;
}

int TechniqueSet::size() const {
  int n = 0;
  for (bool b : bits_) n += b ? 1 : 0;
  return n;
}

std::vector<int> TechniqueSet::uncoveredLengths() const {
  std::vector<int> out;
  for (int k = 1; k <= maxLength_; ++k) {
    bool any = false;
    for (int s = 0; s <= k && !any; ++s) any = contains(s, k + 1 - s);
    if (!any) out.push_back(k);
  }
  return out;
}

std::string TechniqueSet::toString() const {
  std::string out;
  for (int k = 1; k <= maxLength_; ++k)
    for (int s = 0; s <= k; ++s)
      if (contains(s, k + 1 - s)) out += (out.empty() ? "" : ";") + std::to_string(s) + "," + std::to_string(k + 1 - s);
  return out;
}

TechniqueSet TechniqueSet::parse(const std::string& spec, int maxLength) {
  TechniqueSet set(maxLength);
  if (trim(spec).empty()) throw std::invalid_argument("techniques: empty specification");
  size_t start = 0;
  while (start <= spec.size()) {
    const size_t end = std::min(spec.find(';', start), spec.size());
    const std::string item = trim(spec.substr(start, end - start));
    start = end + 1;
    if (item.empty()) throw std::invalid_argument("techniques: empty item in '" + spec + "'");
    if (item == "all") {
      set.bits_.assign(set.bits_.size(), true);
    } else if (item.size() > 2 && item[1] == '=' && (item[0] == 's' || item[0] == 't' || item[0] == 'k')) {
      const int v = parseInt(item.substr(2), item);
      int added = 0;
      for (int k = 1; k <= maxLength; ++k)
        for (int s = 0; s <= k; ++s) {
          const int t = k + 1 - s;
          if ((item[0] == 's' && s == v) || (item[0] == 't' && t == v) || (item[0] == 'k' && k == v)) {
            set.enable(s, t);
            ++added;
          }
        }
      if (added == 0)
        throw std::invalid_argument("techniques: '" + item + "' names no technique of length 1.." +
                                    std::to_string(maxLength));
    } else if (const size_t comma = item.find(','); comma != std::string::npos) {
      const int s = parseInt(item.substr(0, comma), item), t = parseInt(item.substr(comma + 1), item);
      if (s < 0 || t < 1) throw std::invalid_argument("techniques: '" + item + "': need s >= 0 and t >= 1");
      set.enable(s, t);
    } else {
      throw std::invalid_argument("techniques: '" + item + "' is not S,T, s=S, t=T, k=K or all");
    }
    if (end == spec.size()) break;
  }
  return set;
}

}  // namespace pathlab
