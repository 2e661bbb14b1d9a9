// Delta and ratio tracking through the bundled smoke's density grid (issue 35), without rays or
// surfaces: what a unit of optical depth costs. Chords of the grid's unit cube (origin uniform in
// the cube, direction uniform on the sphere, to the cube's face), sigma_t 30 per unit density as
// in assets/smoke.gltf (which scales the cube to 1.2 x 1.8 x 1.2 m; here it stays a unit cube,
// so optical depths are those of a cube of side 1 m).
//   Tracking/smoke/ratio: ratio tracking over whole chords (Russian roulette below T = 0.1);
//   Tracking/smoke/delta: delta tracking to the first real collision or the face;
//   Tracking/constant/*: the same in a density-1 grid, whose majorant is tight.
// Reported per chord: time, tentative collisions, and the chord's true optical depth (the field
// integrated by quadrature, outside the timed loop); their ratios give ns per tentative collision,
// collisions per unit optical depth (1 with a tight majorant) and ns per unit optical depth.
#include "core/math/rng.h"
#include "core/media/procedural_volumes.h"
#include "core/media/volume_grid.h"
#include "core/sampling/warp.h"

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <string>
#include <vector>

namespace pathlab::bench {

namespace {

constexpr int kResolution = 64;
constexpr float kSigmaT = 30.f;
constexpr size_t kChords = 4096;

// Pcg32 that counts its draws (tracking draws one per tentative collision plus one per choice).
struct CountingRng {
  Pcg32 rng;
  uint64_t draws = 0;
  float next1D() {
    ++draws;
    return rng.next1D();
  }
};

struct Chord {
  Vec3 o, d;
  float length;
  double depth;  // integral of sigma_t along it
};

struct Setup {
  VolumeGrid grid;
  HomogeneousMedium medium;
  std::vector<Chord> chords;
  double meanDepth = 0.0;
};

const Setup& setup(ProceduralVolume kind) {
  static Setup setups[3];
  static bool made[3] = {false, false, false};
  Setup& s = setups[int(kind)];
  if (made[int(kind)]) return s;
  made[int(kind)] = true;
  const Mat4 indexToWorld = glm::translate(Mat4(1.f), proceduralOrigin(kResolution)) *
                            glm::scale(Mat4(1.f), Vec3(proceduralVoxelSize(kResolution)));
  s.grid = VolumeGrid(makeProceduralVolume(kind, kResolution), indexToWorld);
  s.medium.sigmaT = Spectrum(kSigmaT);
  s.medium.sigmaS = Spectrum(0.95f * kSigmaT);
  Pcg32 rng(2026, 35);
  for (size_t i = 0; i < kChords; ++i) {
    const Vec3 o = Vec3(rng.next1D(), rng.next1D(), rng.next1D()) - 0.5f;
    const Vec3 d = sampleUniformSphere(rng.next2D());
    float t = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a)
      if (d[a] != 0.f) t = std::min(t, ((d[a] > 0.f ? 0.5f : -0.5f) - o[a]) / d[a]);
    double depth = 0.0;
    const int steps = 512;
    for (int k = 0; k < steps; ++k) depth += double(s.grid.densityAt(o + (float(k) + 0.5f) / steps * t * d));
    depth *= double(kSigmaT) * double(t) / steps;
    s.chords.push_back({o, d, t, depth});
    s.meanDepth += depth / kChords;
  }
  return s;
}

template <bool Delta>
void tracking(benchmark::State& state, ProceduralVolume kind) {
  const Setup& s = setup(kind);
  CountingRng rng{Pcg32(7, 11)};
  size_t chords = 0;
  double sink = 0.0, depth = 0.0;
  for (auto _ : state) {
    for (const Chord& c : s.chords) {
      if constexpr (Delta) {
        const DistanceSample d = deltaTrack(s.medium, s.grid, c.o, c.d, c.length, rng);
        sink += d.t;
        // The optical depth delta tracking walked: to its collision, else the whole chord.
        depth += d.scattered ? c.depth * double(d.t / c.length) : c.depth;
      } else {
        sink += ratioTrack(s.medium, s.grid, c.o, c.d, c.length, rng).r;
        depth += c.depth;
      }
    }
    chords += s.chords.size();
  }
  benchmark::DoNotOptimize(sink);
  const double n = double(chords);
  state.counters["chords_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["collisions_per_chord"] = double(rng.draws) / (Delta ? 2.0 : 1.0) / n;
  state.counters["depth_per_chord"] = depth / n;
  state.counters["collisions_per_depth"] = double(rng.draws) / (Delta ? 2.0 : 1.0) / depth;
  // Seconds per unit optical depth (printed with an SI prefix, e.g. 20n): the time over the
  // depth walked.
  state.counters["time_per_depth"] =
      benchmark::Counter(depth, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
  for (const ProceduralVolume kind : {ProceduralVolume::Smoke, ProceduralVolume::Constant}) {
    const std::string name = std::string("Tracking/") + proceduralVolumeName(kind);
    benchmark::RegisterBenchmark((name + "/ratio").c_str(), [=](benchmark::State& s) { tracking<false>(s, kind); })
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((name + "/delta").c_str(), [=](benchmark::State& s) { tracking<true>(s, kind); })
        ->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace

}  // namespace pathlab::bench
