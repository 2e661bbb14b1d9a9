// An isolated technique written as the command line (--isolate) and the presets take it:
// "S,T" for the connection (s,t), "MS,T" for the merge M(s,t).
#include "core/bpt/bidir_options.h"

#include <charconv>
#include <stdexcept>
#include <string_view>

namespace pathlab {

namespace {

int parsePart(std::string_view part, const std::string& text) {
  int v = 0;
  const char* end = part.data() + part.size();
  const auto [ptr, ec] = std::from_chars(part.data(), end, v);
  if (part.empty() || ec != std::errc() || ptr != end)
    throw std::invalid_argument("'" + text + "' is not S,T or MS,T ('" + std::string(part) + "' is not an integer)");
  return v;
}

}  // namespace

Isolation parseIsolation(const std::string& text) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos) throw std::invalid_argument("'" + text + "' is not S,T, MS,T or E1,T");
  const bool merge = !text.empty() && (text[0] == 'M' || text[0] == 'm');
  const bool equiangular = !text.empty() && (text[0] == 'E' || text[0] == 'e');
  const std::string_view all(text);
  const size_t from = merge || equiangular ? 1 : 0;
  const Isolation x{parsePart(all.substr(from, comma - from), text), parsePart(all.substr(comma + 1), text), false,
                    merge ? TechniqueKind::Merge : equiangular ? TechniqueKind::Equiangular : TechniqueKind::Connection};
  if (equiangular && (x.s != 1 || x.t < 2))
    throw std::invalid_argument("'" + text + "': an equiangular technique is E1,T with T >= 2");
  return x;
}

}  // namespace pathlab
