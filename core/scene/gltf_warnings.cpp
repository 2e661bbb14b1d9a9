// The loader's warnings, folded (see Warnings in gltf_internal.h).
#include "core/scene/gltf_internal.h"

namespace pathlab::gltf {

namespace {
// Subjects named in a folded line; the rest are counted.
constexpr size_t kNamedSubjects = 3;
}  // namespace

void Warnings::add(const std::string& subject, const std::string& problem) {
  std::string who = oneLine(subject), what = oneLine(problem);
  if (!seen_.insert(who + '\0' + what).second) return;
  auto [it, inserted] = index_.emplace(what, problems_.size());
  if (inserted) problems_.push_back(Problem{what, {}});
  problems_[it->second].subjects.push_back(std::move(who));
}

std::vector<std::string> Warnings::take() {
  std::vector<std::string> lines;
  for (Problem& p : problems_) {
    const size_t n = p.subjects.size();
    if (n == 1) {
      lines.push_back(p.subjects[0].empty() ? p.text : p.subjects[0] + ": " + p.text);
      continue;
    }
    std::string line = p.text + " (" + std::to_string(n) + " times: ";
    for (size_t i = 0; i < std::min(n, kNamedSubjects); ++i) {
      line += (i ? ", " : "") + (p.subjects[i].empty() ? std::string("the file") : p.subjects[i]);
    }
    if (n > kNamedSubjects) line += " and " + std::to_string(n - kNamedSubjects) + " more";
    lines.push_back(line + ")");
  }
  problems_.clear();
  index_.clear();
  seen_.clear();
  return lines;
}

}  // namespace pathlab::gltf
