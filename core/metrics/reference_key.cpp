// FNV-1a hashing of the reference's inputs.
#include "core/metrics/reference_key.h"

#include <fmt/core.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace pathlab {

namespace {

// FNV-1a, 64-bit (Fowler, Noll, Vo): enough to tell inputs apart, not a security hash.
struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const std::string& bytes) {
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 0x100000001b3ull;
    }
  }
};

std::string describe(const RenderSettings& s) {
  std::string text = fmt::format(
      "pathlab-reference-1 size={}x{} maxLength={} rr={} seed={} integrator={} techniques={} mis={} beta={} "
      "aperture={} focus={} pyramid={}",
      s.width, s.height, s.maxLength, s.russianRoulette, s.seed, integratorName(s.integrator), s.techniques,
      misHeuristicName(s.mis.heuristic), s.mis.beta, s.lens.apertureRadius, s.lens.focusDistance, s.pyramidLength);
  if (s.isolate) text += fmt::format(" isolate={},{},{}", s.isolate->s, s.isolate->t, s.isolate->unweighted);
  if (s.camera) {
    text += fmt::format(" yfov={} aspect={} camera=", s.camera->yfov, s.camera->aspectRatio.value_or(0.f));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) text += fmt::format("{},", s.camera->cameraToWorld[c][r]);
  }
  return text;
}

}  // namespace

std::string referenceKey(const std::string& scenePath, const RenderSettings& settings, const std::string& budget) {
  std::ifstream in(scenePath, std::ios::binary);
  if (!in) throw std::runtime_error(scenePath + ": cannot read the scene file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Fnv1a hash;
  hash.add(bytes);
  hash.add("\n" + describe(settings) + "\n" + budget);
  return fmt::format("{:016x}", hash.h);
}

}  // namespace pathlab
