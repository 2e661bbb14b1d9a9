// The single-process job: nothing to agree on, nothing to combine.
#include "app/job.h"

#include <iostream>

namespace pathlab::app {

namespace {

// An ostream whose buffer accepts and drops every character.
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

}  // namespace

std::ostream& Job::log() const {
  static NullBuffer buffer;
  static std::ostream discard(&buffer);
  return leader() ? std::cerr : discard;
}

void Job::agree(const std::string& error, uint64_t) {
  if (!error.empty()) throw std::runtime_error(error);
}

JobTotals Job::combine(RenderSession& session, double seconds) { return JobTotals{session.passes(), seconds}; }

uint64_t shapeOf(RenderSession& session) {
  // FNV-1a over the number of sums and each one's size.
  uint64_t h = 14695981039346656037ull;
  auto mix = [&](uint64_t v) {
    for (int i = 0; i < 8; ++i) h = (h ^ ((v >> (8 * i)) & 0xff)) * 1099511628211ull;
  };
  const std::vector<std::span<double>> sums = session.sums();
  mix(sums.size());
  for (const std::span<double>& s : sums) mix(s.size());
  return h;
}

}  // namespace pathlab::app
