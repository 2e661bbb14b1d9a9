// PCG32 random streams keyed by (seed, pixel, sample index, stream) so any sample can be replayed.
#pragma once

#include "core/math/types.h"

namespace pathlab {

// O'Neill 2014, PCG: XSH-RR 64/32.
class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t initState, uint64_t sequence) { seed(initState, sequence); }
  // A generator nobody will draw from, without the cost of seeding one (a valid stream all the same).
  static Pcg32 unseeded() { return Pcg32(Unseeded{}); }

  void seed(uint64_t initState, uint64_t sequence) {
    state_ = 0u;
    inc_ = (sequence << 1u) | 1u;
    nextU32();
    state_ += initState;
    nextU32();
  }
  uint32_t nextU32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  // Uniform in [0, 1): 24 random mantissa bits, never exactly 1.
  float next1D() { return static_cast<float>(nextU32() >> 8) * 0x1p-24f; }
  Vec2 next2D() {
    const float a = next1D();
    return {a, next1D()};
  }

 private:
  struct Unseeded {};
  explicit Pcg32(Unseeded) : state_(0), inc_(1) {}
  uint64_t state_ = 0, inc_ = 0;
};

// SplitMix64 finaliser: decorrelates nearby keys.
inline uint64_t mixBits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

// Which independent stream of a sample: the camera subpath and the light subpath draw from
// different streams so that one can be replayed without the other shifting.
enum class RngStream : uint64_t { Camera = 0, Light = 1, Test = 7 };

inline Pcg32 makeSampleRng(uint64_t seed, uint64_t pixelIndex, uint64_t sampleIndex,
                           RngStream stream = RngStream::Camera) {
  const uint64_t key = mixBits(seed ^ mixBits(pixelIndex * 0x9E3779B97F4A7C15ULL + sampleIndex));
  return Pcg32(key, mixBits(sampleIndex ^ (static_cast<uint64_t>(stream) << 56) ^ pixelIndex));
}

}  // namespace pathlab
