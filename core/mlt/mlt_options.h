// Metropolis light transport's settings (issue 33): which chain, how many, how it mutates.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace pathlab {

// Multiplexed: MMLT (Hachisuka, Kaplanyan and Dachsbacher 2014), the chain's state also picks one
// enabled technique (s, t) of its path length, one set of chains per length (pbrt-v4's MLT).
// PrimarySpace: PSSMLT (Kelemen et al. 2002), the chain's state is a whole bidirectional sample,
// every enabled technique of every length combined by MIS as in `bpt`.
enum class MltVariant : uint8_t { Multiplexed, PrimarySpace };

struct MltOptions {
  MltVariant variant = MltVariant::Multiplexed;
  int chains = 1000;             // Markov chains, spread over the threads
  uint64_t bootstrap = 100000;   // independent samples per path length (PSSMLT: in all) that estimate b
  float largeStep = 0.3f;        // the probability of a large step (an independent sample)
  float sigma = 0.01f;           // the small step's standard deviation in primary sample space
  // Paths of up to this many edges are rendered by BPT beside the chains, one sample a pixel a
  // pass, and the chains explore only the longer ones (Mitsuba's MLT "separateDirect"): light seen
  // directly and direct lighting are what independent samples do best, and a chain spent on
  // them is one not spent where they fail. 0: the chains render every length.
  int directLength = 0;
  bool operator==(const MltOptions&) const = default;
};

inline constexpr int kMaxMltChains = 1 << 20;
// Per length: the bootstrap keeps a double per sample of every length (at most 2^24 x 100 lengths
// of the viewer's and the CLI's range would be 13 GiB: validateSettings bounds the product too).
inline constexpr uint64_t kMaxMltBootstrap = uint64_t{1} << 24;
inline constexpr uint64_t kMaxMltBootstrapSamples = uint64_t{1} << 27;  // over all lengths: 1 GiB of weights
inline constexpr float kMinMltSigma = 1e-5f, kMaxMltSigma = 1.f;

const char* mltVariantName(MltVariant v);  // "mmlt", "pss"
std::optional<MltVariant> parseMltVariant(std::string_view name);

}  // namespace pathlab
