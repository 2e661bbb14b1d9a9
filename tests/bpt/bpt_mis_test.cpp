// misWeight: partition of unity over the techniques able to produce a path, for every heuristic
// and random enabled subsets, against a brute-force oracle built from explicit full-path
// densities (each technique's path pdf as a product of area densities). weightWithMerges
// (core/bpt/merge_mis.h): the same over connections and merges.
#include "core/bpt/bidir_tracer.h"
#include "core/bpt/connect.h"
#include "core/bsdf/bsdf.h"
#include "core/bpt/merge_mis.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

namespace pathlab {
namespace {

using test::lambertian;
using test::quad;

// Area density at x_to of sampling it at x_at, having come from x_from (nullptr at a light
// origin or the camera): the oracle's own evaluation, written from the definitions.
// An environment vertex (at infinity, ng the direction its light travels) is a direction: from it
// the next vertex's density is the emission disk's, per unit area normal to the light, times the
// receiver's cosine; toward it a solid-angle density stays one (pbrt-v4 ConvertDensity).
double oracleDensity(const Scene& scene, const Camera& camera, const PathVertex& at, const PathVertex* from,
                     const PathVertex& to, TransportMode mode) {
  const Vec3 d = to.p - at.p;
  const double dist2 = glm::dot(d, d);
  const Vec3 w = at.isInfinite ? at.ng : to.isInfinite ? -to.ng : glm::normalize(d);
  const double cosTo = to.type == VertexType::Camera || to.ng == Vec3(0.f) || to.isInfinite ? 1.0 : absDot(to.ng, w);
  if (at.type == VertexType::Camera && camera.isOrthographic()) {
    // Parallel rays along the view axis, uniform over the film rectangle: a planar density, times
    // the receiver's cosine to the axis (no distance: the rays do not spread).
    const Vec3 axis = camera.forward();
    const double cosAxis = to.type == VertexType::Surface ? absDot(to.ng, axis) : 1.0;
    return camera.pdfWe(Ray{at.p, axis}).pdfPosA * cosAxis;
  }
  if (at.isInfinite) {
    const Light& light = scene.lights()[static_cast<size_t>(at.light)];
    return light.pdfLe(at.p, at.ng, w).pdfPosA * cosTo;
  }
  double pdfW = 0.0;
  if (at.type == VertexType::Camera) {
    pdfW = camera.pdfWe(Ray{at.p, w}).pdfDirW;
  } else if (!from) {  // light origin
    const Light& light = scene.lights()[static_cast<size_t>(at.light)];
    pdfW = light.pdfLe(at.p, at.ng, w).pdfDirW;
  } else if (at.type == VertexType::Medium) {
    // Henyey-Greenstein from its definition, the scattering angle's cosine between the direction
    // light travelled into `at` and the one it leaves in.
    const Vec3 in = glm::normalize(at.p - from->p);
    const double g = scene.medium(at.media.inside).g;
    pdfW = (1.0 - g * g) / (4.0 * 3.14159265358979 * std::pow(1.0 + g * g - 2.0 * g * glm::dot(in, w), 1.5));
  } else {
    const Bsdf bsdf(at.ns, at.ng, evalMaterial(scene.material(at.material), at.uv, scene.textures()));
    pdfW = bsdf.pdf(from->isInfinite ? -from->ng : glm::normalize(from->p - at.p), w, mode);
  }
  return to.isInfinite ? pdfW : pdfW * cosTo / dist2;
}

struct FullPath {
  std::vector<PathVertex> x;  // x0 on the light ... x(n-1) the camera
  std::vector<double> pL, pE;
  // x0's density under technique s' = 1 (n >= 3): next-event estimation chose its light for x1
  // (LightSet::pmfNee: a light BVH's choice in scenes of several emitters), not by power.
  double pLNee = 0.0;
  bool orthographic = false;  // the camera's importance is a delta in direction: t' = 1 cannot connect
};

FullPath densities(const Scene& scene, const Camera& camera, std::vector<PathVertex> x) {
  FullPath f;
  const int n = static_cast<int>(x.size());
  f.pL.assign(static_cast<size_t>(n), 0.0);
  f.pE.assign(static_cast<size_t>(n), 0.0);
  // The origin's density: a point on the light, or the environment's direction (toward -ng).
  const Light& light = scene.lights()[static_cast<size_t>(x[0].light)];
  const double originDensity = light.type() == LightType::Environment
                                   ? light.environmentLight()->pdfDirection(-x[0].ng)
                                   : light.pdfLe(x[0].p, x[0].ng, Vec3(0, 0, 1)).pdfPosA;
  f.pL[0] = scene.lights().pmf(x[0].light) * originDensity;
  f.pLNee = f.pL[0];
  if (n >= 3) {
    const PathVertex& x1 = x[1];
    const LightSampleContext receiver{x1.p, x1.type == VertexType::Medium ? Vec3(0.f) : x1.ng};
    f.pLNee = scene.lights().pmfNee(receiver, x[0].light) * originDensity;
  }
  for (int i = 1; i < n; ++i)
    f.pL[static_cast<size_t>(i)] = oracleDensity(scene, camera, x[static_cast<size_t>(i - 1)],
                                                 i >= 2 ? &x[static_cast<size_t>(i - 2)] : nullptr,
                                                 x[static_cast<size_t>(i)], TransportMode::Importance);
  f.pE[static_cast<size_t>(n - 1)] = 1.0;
  for (int i = n - 2; i >= 0; --i)
    f.pE[static_cast<size_t>(i)] = oracleDensity(scene, camera, x[static_cast<size_t>(i + 1)],
                                                 i + 2 < n ? &x[static_cast<size_t>(i + 2)] : nullptr,
                                                 x[static_cast<size_t>(i)], TransportMode::Radiance);
  f.x = std::move(x);
  f.orthographic = camera.isOrthographic();
  return f;
}

// The equiangular technique E(1, n-1) (issue 35) from its definition: x0's density with its light
// chosen from x2, then x1 placed on the ray from x2 by Kulla and Fajardo's density on the unbounded
// ray toward x0, D / ((pi/2 - theta_a) (D^2 + (t - delta)^2)), in place of distance sampling's
// mean over the channels of sigma_t exp(-sigma_t t); everything else as C(1, n-1). 0 where E
// cannot sample the path: x1 not in a homogeneous scattering medium, the ray from x2 not starting
// in it, x0 at infinity.
double oracleEquiangularDensity(const Scene& scene, const FullPath& f) {
  const int n = static_cast<int>(f.x.size());
  if (n < 3) return 0.0;
  const PathVertex &x0 = f.x[0], &x1 = f.x[1], &x2 = f.x[2];
  if (x1.type != VertexType::Medium || x0.isInfinite) return 0.0;
  const int m = x1.media.inside;
  if (m < 0 || scene.mediumGrid(m) || !scene.medium(m).scatters()) return 0.0;
  const glm::dvec3 o(x2.p), c(x0.p), e = glm::dvec3(x1.p) - o;
  const double t = glm::length(e);
  const glm::dvec3 d = e / t;
  // The medium the ray from x2 starts in; the camera's from where it is.
  const int start = x2.type == VertexType::Camera ? scene.mediumAt(x2.p) : x2.media.toward(x2.ng, Vec3(d));
  if (start != m) return 0.0;
  const double delta = glm::dot(c - o, d), D = glm::length(o + delta * d - c);
  const double pe = D / ((3.14159265358979 / 2 - std::atan(-delta / D)) * (D * D + (t - delta) * (t - delta)));
  const Spectrum sigmaT = scene.medium(m).sigmaT;
  double pd = 0.0;
  for (int k = 0; k < 3; ++k) pd += sigmaT[k] * std::exp(-sigmaT[k] * t) / 3.0;
  const Light& light = scene.lights()[static_cast<size_t>(x0.light)];
  const double x0Density = scene.lights().pmfNee(LightSampleContext{x2.p, Vec3(0.f)}, x0.light) *
                           light.pdfLe(x0.p, x0.ng, Vec3(0, 0, 1)).pdfPosA;
  double p = x0Density * f.pE[1] * pe / pd;
  for (int i = 2; i < n - 1; ++i) p *= f.pE[static_cast<size_t>(i)];
  return p;
}

// Brute force: p_s' = prod_{i < s'} pL_i * prod_{i >= s'} pE_i, then the heuristic directly, over
// the enabled techniques able to produce the path, less those whose connection edge
// x(s'-1) -- x(s') is shorter than minDistance while a technique without a short one remains.
// With o.mediumSampling not Distance, weight n (the last) is E(1, n-1)'s (pEquiangular, 0 where it
// cannot sample the path), which joins x0 and x1 as C(1, n-1) does and under Equiangular replaces it.
// factors: variance-aware MIS's per slot of the length (connections at s', E(1, n-1) at 2(n-1)),
// multiplying each technique's density (o.heuristic VarianceAware: the balance heuristic).
std::vector<double> oracleWeights(const FullPath& f, const TechniqueSet& enabled, const MisOptions& o,
                                  double minDistance, double pEquiangular = 0.0, const float* factors = nullptr) {
  const int n = static_cast<int>(f.x.size());
  std::vector<double> p(static_cast<size_t>(n + 1), 0.0), w(static_cast<size_t>(n + 1), 0.0);
  // E(1, n-1) has its own switch.
  const bool equiangular = o.mediumSampling != MediumSampling::Distance && pEquiangular > 0.0 &&
                           enabled.contains(Technique::equiangular(n - 1));
  const bool x0Hittable = !f.x[0].isDeltaPosition && !f.x[0].isDeltaDirection;
  // No lens point connects to the environment: (1, 1) cannot form the path environment -> camera.
  const bool lensToInfinity = n == 2 && f.x[0].isInfinite;
  auto candidate = [&](int sp) {
    if (sp == n) return equiangular;
    if (sp == 1 && equiangular && o.mediumSampling == MediumSampling::Equiangular) return false;
    return enabled.contains(sp, n - sp) && (sp != 0 || x0Hittable) && !(sp == 1 && lensToInfinity) &&
           !(sp == n - 1 && f.orthographic);
  };
  auto shortEdge = [&](int sp) {
    const int e = sp == n ? 1 : sp;  // E's connection edge is C(1, n-1)'s
    return e >= 1 && glm::distance(f.x[static_cast<size_t>(e - 1)].p, f.x[static_cast<size_t>(e)].p) < minDistance;
  };
  bool longRemains = false;
  for (int sp = 0; sp <= n; ++sp) longRemains |= candidate(sp) && !shortEdge(sp);
  double sum = 0.0;
  int count = 0;
  for (int sp = 0; sp <= n; ++sp) {
    if (!candidate(sp) || (longRemains && shortEdge(sp))) continue;
    double prod = 1.0;
    if (sp == n)
      prod = pEquiangular;
    else
      for (int i = 0; i < n - 1; ++i)
        prod *= i == 0 && sp == 1 ? f.pLNee : i < sp ? f.pL[static_cast<size_t>(i)] : f.pE[static_cast<size_t>(i)];
    if (factors) prod *= static_cast<double>(factors[sp == n ? 2 * (n - 1) : sp]);
    const double b = o.heuristic == MisHeuristic::Power ? o.beta : 1.0;
    p[static_cast<size_t>(sp)] = std::pow(prod, b);
    sum += p[static_cast<size_t>(sp)];
    ++count;
  }
  for (int sp = 0; sp <= n; ++sp)
    if (p[static_cast<size_t>(sp)] > 0.0)
      w[static_cast<size_t>(sp)] = o.heuristic == MisHeuristic::Uniform ? 1.0 / count : p[static_cast<size_t>(sp)] / sum;
  return w;
}

// Technique s' of the full path, in the form the walks would have stored it; `equiangular`: also
// E(1, n-1)'s weight as that view sees it.
double equiangularWeightSeenBy(const Scene& scene, const Camera& camera, const MisPath& view, const TechniqueSet& enabled,
                               const MisOptions& o, const float* factors = nullptr);
float fastWeight(const Scene& scene, const Camera& camera, const FullPath& f, int sp, const TechniqueSet& enabled,
                 const MisOptions& o, double* equiangular = nullptr, const float* factors = nullptr) {
  const int n = static_cast<int>(f.x.size());
  std::vector<PathVertex> light, cam;
  for (int i = 0; i < sp; ++i) {
    PathVertex v = f.x[static_cast<size_t>(i)];
    v.pdfFwdA = static_cast<float>(f.pL[static_cast<size_t>(i)]);
    v.pdfRevA = static_cast<float>(f.pE[static_cast<size_t>(i)]);
    v.pdfNeeA = static_cast<float>(i == 0 ? f.pLNee : f.pL[static_cast<size_t>(i)]);
    light.push_back(v);
  }
  for (int i = n - 1; i >= sp; --i) {
    PathVertex v = f.x[static_cast<size_t>(i)];
    v.pdfFwdA = static_cast<float>(f.pE[static_cast<size_t>(i)]);
    v.pdfRevA = static_cast<float>(f.pL[static_cast<size_t>(i)]);
    cam.push_back(v);
  }
  const MisPath view{light.data(), sp, cam.data(), n - sp, nullptr};
  if (equiangular) *equiangular = equiangularWeightSeenBy(scene, camera, view, enabled, o, factors);
  return misWeight(scene, camera, view, enabled, o, lightTracingRatio(), factors);
}

// E(1, n-1)'s weight as the view of technique s' of the same path sees it (its densities), which
// must not depend on s'.
double equiangularWeightSeenBy(const Scene& scene, const Camera& camera, const MisPath& view, const TechniqueSet& enabled,
                               const MisOptions& o, const float* factors) {
  PathDensities d = pathDensities(scene, camera, view);
  d.factors = factors;
  return weightFromDensities(d, 1, enabled, o, lightTracingRatio(), minConnectionDistance(scene, o), true);
}

SceneDesc furnace() {
  SceneDesc desc;
  desc.path = "furnace";
  desc.materials = {lambertian(0.6f, Spectrum(0.7f))};
  desc.meshes = test::inwardBox(1.f, 0);
  desc.camera = test::lookAt(Vec3(0.1f, 0.2f, 0.3f), Vec3(1.f, -0.3f, -0.5f), Vec3(0, 1, 0), 1.2f);
  return desc;
}

SceneDesc squareEmitter() {
  SceneDesc desc;
  desc.path = "square";
  desc.materials = {lambertian(0.5f), lambertian(0.f, Spectrum(1.f))};
  desc.meshes = {quad(Vec3(-5, 0, 5), Vec3(5, 0, 5), Vec3(5, 0, -5), Vec3(-5, 0, -5), 0),
                 quad(Vec3(-.5f, 1, -.5f), Vec3(.5f, 1, -.5f), Vec3(.5f, 1, .5f), Vec3(-.5f, 1, .5f), 1)};
  desc.camera = test::lookAt(Vec3(0.3f, 1.5f, 2.6f), Vec3(0.f), Vec3(0, 1, 0), 0.9f);
  return desc;
}

SceneDesc pointLight() {
  SceneDesc desc;
  desc.path = "point";
  desc.materials = {lambertian(0.6f)};
  desc.meshes = test::inwardBox(1.f, 0);
  PunctualLightDesc l;
  l.position = Vec3(0.2f, 0.5f, -0.1f);
  desc.punctualLights = {l};
  desc.camera = test::lookAt(Vec3(0.1f, 0.2f, 0.3f), Vec3(1.f, -0.3f, -0.5f), Vec3(0, 1, 0), 1.2f);
  return desc;
}

// The square emitter's floor with a floating sphere, lit also by an environment map (a sky gradient
// over a black lower half and a bright patch): light selection between the two, camera paths
// that escape to it (s = 0), next-event estimation toward it (s = 1) and light subpaths from it.
SceneDesc environmentAndSquare() {
  SceneDesc desc = squareEmitter();
  desc.path = "environment";
  desc.materials.push_back(lambertian(0.7f));
  desc.meshes.push_back(test::uvSphere(Vec3(-1.f, 0.6f, 0.f), 0.3f, 2, 16, 8));
  auto env = std::make_shared<EnvironmentDesc>();
  env->width = 16;
  env->height = 8;
  env->rotationDegrees = 25.f;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      env->texels.push_back(y >= 4 ? Spectrum(0.f) : (x == 5 && y == 1) ? Spectrum(40.f) : Spectrum(0.3f + 0.1f * y));
  desc.environment = env;
  return desc;
}

// Every path the walks of `samples` camera samples through an 8 x 8 film give, under every
// technique whose connection contributes: fn(s, t, c, x, lp, cp) with x the path's vertices x0 on
// the light .. x(n-1) at the camera. Stops after a sample that failed a test.
template <class Fn>
void forEachConnectedPath(const Scene& scene, const Camera& camera, int maxLength, int samples, Pcg32& rng, Fn&& fn) {
  const int size = 8;
  CameraSubpath cp;
  LightSubpath lp;
  Counters counters;
  for (int sample = 0; sample < samples; ++sample) {
    const int nt = generateCameraSubpath(scene, camera, Vec2(rng.next1D() * size, rng.next1D() * size), rng.next2D(),
                                         rng, WalkOptions{maxLength + 1, false, scene.mediumAt(camera.position())}, cp,
                                         counters);
    const int ns = generateLightSubpath(scene, rng, WalkOptions{maxLength, false}, lp, counters);
    for (int t = 1; t <= nt; ++t)
      for (int s = 0; s <= ns && s + t - 1 <= maxLength; ++s) {
        if (s + t < 2) continue;
        const Connection c = connect(scene, camera, lp, s, cp, t, rng, counters);
        if (isBlack(c.L)) continue;
        std::vector<PathVertex> x;
        for (int i = 0; i < s; ++i) x.push_back(i == 0 && s == 1 && t >= 2 ? c.sampled : lp[i]);
        for (int j = t - 1; j >= 0; --j) x.push_back(j == 0 && t == 1 ? c.sampled : cp[j]);
        x[0].type = VertexType::Light;  // an emitter found by the camera walk is the light origin
        fn(s, t, c, x, lp, cp);
      }
    if (::testing::Test::HasFailure()) return;
  }
}

// minConnection: MisOptions::minConnection. The default leaves out a connection only at a corner;
// a large value makes short connections common, the fallback (no long one left) included.
// cameraDesc: the camera seeing the scene (none: the scene's own).
// mediumSampling: with the equiangular family (not Distance), its technique E(1, n-1) is weighed
// too, from the real view and from every technique's (its weight and the sum).
void checkPartition(const Scene& scene, int maxLength, const char* name, float minConnection = kDefaultMinConnection,
                    const std::optional<CameraDesc>& cameraDesc = std::nullopt,
                    MediumSampling mediumSampling = MediumSampling::Distance) {
  const Camera camera(cameraDesc.value_or(scene.cameraDesc()), 8, 8);
  Pcg32 rng(1234, 5);
  int checked = 0, shortExcluded = 0, equiangularPaths = 0;
  forEachConnectedPath(scene, camera, maxLength, 400, rng, [&](int s, int t, const Connection& c,
                                                          const std::vector<PathVertex>& x, const LightSubpath& lp,
                                                          const CameraSubpath& cp) {
    const int n = s + t;
    const FullPath f = densities(scene, camera, x);
    // Variance-aware: a factor per slot of the length (E(1, n-1)'s at 2(n-1)), log-uniform over 1e-2..1e2.
    std::vector<float> slotFactors(static_cast<size_t>(2 * (n - 1) + 1), 1.f);
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform, MisHeuristic::VarianceAware}) {
      const MisOptions o{h, h == MisHeuristic::Power ? 1.f + 2.f * rng.next1D() : 2.f, minConnection, mediumSampling};
      for (float& c : slotFactors) c = std::pow(10.f, -2.f + 4.f * rng.next1D());
      const float* factors = h == MisHeuristic::VarianceAware ? slotFactors.data() : nullptr;
      const double pEquiangular = mediumSampling != MediumSampling::Distance ? oracleEquiangularDensity(scene, f) : 0.0;
      equiangularPaths += pEquiangular > 0.0;
      TechniqueSet enabled = TechniqueSet::all();
      if (rng.next1D() < 0.7f)
        for (int sp = 0; sp < n; ++sp)
          if (sp != s && rng.next1D() < 0.4f) enabled.disable({sp, n - sp}, maxLength);
      const std::vector<double> oracle =
          oracleWeights(f, enabled, o, minConnection * scene.bounds().radius, pEquiangular, factors);
      shortExcluded += [&] {
        int excluded = 0;
        for (int sp = 0; sp < n; ++sp)
          excluded += enabled.contains(sp, n - sp) && oracle[static_cast<size_t>(sp)] == 0.0 && sp >= 1 &&
                      glm::distance(f.x[static_cast<size_t>(sp - 1)].p, f.x[static_cast<size_t>(sp)].p) <
                          minConnection * scene.bounds().radius;
        return excluded;
      }();
      // The weight the tracer computes from the walks' own densities and the connection's.
      const MisPath real{lp.data(), s, cp.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
      const float wReal = misWeight(scene, camera, real, enabled, o, lightTracingRatio(), factors);
      EXPECT_NEAR(wReal, oracle[static_cast<size_t>(s)], 1e-4)
          << name << " (" << s << "," << t << ") " << misHeuristicName(h) << [&] {
               const PathDensities d = pathDensities(scene, camera, real);
               std::string out;
               for (int i = 0; i < n; ++i)
                 out += "\n x" + std::to_string(i) + " L " + std::to_string(d.pFromLight[size_t(i)]) + " / " +
                        std::to_string(f.pL[size_t(i)]) + "  E " + std::to_string(d.pFromCamera[size_t(i)]) + " / " +
                        std::to_string(f.pE[size_t(i)]);
               return out;
             }();
      // E's weight, from the real view and below from every technique's.
      EXPECT_NEAR(equiangularWeightSeenBy(scene, camera, real, enabled, o, factors), oracle[static_cast<size_t>(n)], 1e-4)
          << name << " E(1," << n - 1 << ") seen by (" << s << "," << t << ") " << misHeuristicName(h);
      double sum = oracle[static_cast<size_t>(n)];
      for (int sp = 0; sp < n; ++sp) {
        double wE = 0.0;
        const float w = fastWeight(scene, camera, f, sp, enabled, o, &wE, factors);
        EXPECT_NEAR(wE, oracle[static_cast<size_t>(n)], 1e-4) << name << " E(1," << n - 1 << ") seen by s'=" << sp;
        EXPECT_NEAR(w, oracle[static_cast<size_t>(sp)], 1e-4) << name << " s'=" << sp << " of (" << s << "," << t << ")"
            << " light " << static_cast<int>(scene.lights()[static_cast<size_t>(f.x[0].light)].type()) << " pL0 " << f.pL[0]
            << " pLNee " << f.pLNee << " real x0Nee " << pathDensities(scene, camera, real).x0Nee << " real pL0 "
            << pathDensities(scene, camera, real).pFromLight[0];
        sum += w;
      }
      EXPECT_NEAR(sum, 1.0, 1e-5) << name << " (" << s << "," << t << ") " << misHeuristicName(h);
      ++checked;
    }
  });
  EXPECT_GT(checked, 100) << name;
  if (mediumSampling != MediumSampling::Distance) {
    EXPECT_GT(equiangularPaths, 100) << name;
  }
  // A large minConnection must actually have left techniques out, or the case is untested.
  if (minConnection >= 0.1f) {
    EXPECT_GT(shortExcluded, 20) << name;
  }
}

TEST(BptMis, PartitionOfUnityFurnace) { checkPartition(Scene(furnace()), 5, "furnace"); }
// Next-event estimation that cannot choose x0's light for x1 (a light BVH's bounds, or rounding,
// refuse it): technique (1, t) has density zero, not a delta, and the others share the path.
TEST(BptMis, ZeroNextEventDensityLeavesOutTechniqueOne) {
  PathDensities d;
  d.n = 4;
  d.pFromLight = {0.3, 0.7, 1.9, 0.0};
  d.pFromCamera = {0.5, 1.1, 0.4, 1.0};
  d.delta = {0, 0, 0, 0};
  d.edgeLength2 = {1.f, 1.f, 1.f};
  d.x0CanBeHit = true;
  d.x0Nee = 0.0;
  d.neeRefused = true;
  for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
    const MisOptions o{h, 2.f, 0.f};
    double sum = 0.0;
    for (int sp = 0; sp < d.n; ++sp) sum += weightFromDensities(d, sp, TechniqueSet::all(), o, 1.f, 0.f);
    EXPECT_NEAR(sum, 1.0, 1e-9) << misHeuristicName(h);
    EXPECT_EQ(weightFromDensities(d, 1, TechniqueSet::all(), o, 1.f, 0.f), 0.0) << misHeuristicName(h);
    if (h == MisHeuristic::Balance) {
      // The others in proportion to their own densities: p0 = C0 C1 C2, p2 = L0 L1 C2, p3 = L0 L1 L2.
      const double p0 = 0.5 * 1.1 * 0.4, p2 = 0.3 * 0.7 * 0.4, p3 = 0.3 * 0.7 * 1.9;
      EXPECT_NEAR(weightFromDensities(d, 2, TechniqueSet::all(), o, 1.f, 0.f), p2 / (p0 + p2 + p3), 1e-9);
    }
  }
}
// The furnace's six emitting faces are six emitters, so next-event estimation chooses among them
// by a light BVH (LightSelection::Auto); chosen by power, x0's density is the same for every
// technique.
TEST(BptMis, PartitionOfUnityFurnaceByPower) {
  SceneDesc desc = furnace();
  desc.lightSelection = LightSelection::Power;
  checkPartition(Scene(std::move(desc)), 5, "furnace by power");
}
// Every kind of light at once, next-event estimation choosing by a light BVH: x0's density under
// technique (1, t) depends on x1 (the receiver), unlike its density as a light subpath's origin.
TEST(BptMis, PartitionOfUnityManyLightsByBvh) {
  SceneDesc desc = environmentAndSquare();
  desc.path = "many lights";
  PunctualLightDesc point, spot, sun;
  point.position = Vec3(0.6f, 0.4f, 0.3f);
  point.intensity = 0.5f;
  spot.type = PunctualLightType::Spot;
  spot.position = Vec3(-0.8f, 1.6f, 0.2f);
  spot.direction = glm::normalize(Vec3(0.2f, -1.f, 0.f));
  spot.intensity = 3.f;
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.6f;
  sun.type = PunctualLightType::Directional;
  sun.direction = glm::normalize(Vec3(0.3f, -1.f, 0.4f));
  sun.intensity = 0.7f;
  desc.punctualLights = {point, spot, sun};
  desc.lightSelection = LightSelection::Bvh;
  const Scene scene(std::move(desc));
  ASSERT_TRUE(scene.lights().neeByContext());
  checkPartition(scene, 4, "many lights");
}
// Medium vertices (issue 16) anywhere on the path: densities in the volume measure, no cosine.
TEST(BptMis, PartitionOfUnityFoggyFurnace) {
  checkPartition(Scene(test::foggyFurnace(0.5f, 1.f, 1.5f, 0.4f)), 5, "foggy furnace");
}
// The equiangular technique E(1, k) (issue 35) beside the connections and in place of C(1, k), in
// the fog-lamp scene (a point light and two area lights in fog) and the foggy furnace; and with
// next-event estimation by a light BVH, where E chooses x0's light from x2 and C(1, k) from x1.
TEST(BptMis, PartitionOfUnityWithTheEquiangularTechnique) {
  SceneDesc lamp = loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/fog-lamp.gltf");
  for (const MediumSampling m : {MediumSampling::Mis, MediumSampling::Equiangular}) {
    checkPartition(Scene(SceneDesc(lamp)), 4, "fog lamp", kDefaultMinConnection, std::nullopt, m);
    checkPartition(Scene(test::foggyFurnace(0.5f, 1.f, 1.5f, 0.4f)), 4, "foggy furnace", kDefaultMinConnection,
                   std::nullopt, m);
  }
  lamp.lightSelection = LightSelection::Bvh;
  const Scene byBvh(std::move(lamp));
  ASSERT_TRUE(byBvh.lights().neeByContext());
  checkPartition(byBvh, 4, "fog lamp by BVH", kDefaultMinConnection, std::nullopt, MediumSampling::Mis);
  checkPartition(byBvh, 4, "fog lamp by BVH, short", 0.3f, std::nullopt, MediumSampling::Mis);
}
TEST(BptMis, PartitionOfUnitySquareEmitter) { checkPartition(Scene(squareEmitter()), 4, "square"); }
TEST(BptMis, PartitionOfUnityPointLight) { checkPartition(Scene(pointLight()), 4, "point"); }
TEST(BptMis, PartitionOfUnityEnvironment) { checkPartition(Scene(environmentAndSquare()), 4, "environment"); }
// An orthographic camera (issue 15): its importance is a delta in direction, so no t = 1
// technique is counted, and the camera subpath's first vertex is sampled by its film position.
TEST(BptMis, PartitionOfUnityOrthographicCamera) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  CameraDesc ortho = scene.cameraDesc();
  ortho.orthographic = Vec2(0.3f, 0.3f);
  checkPartition(scene, 5, "cornell orthographic", kDefaultMinConnection, ortho);
  checkPartition(Scene(pointLight()), 4, "point orthographic", kDefaultMinConnection, [] {
    CameraDesc c = pointLight().camera.value();
    c.orthographic = Vec2(0.4f, 0.4f);
    return c;
  }());
}
TEST(BptMis, PartitionOfUnityCornellBox) {
  checkPartition(Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf")), 5, "cornell");
}

// Short connections left out (MisOptions::minConnection at 30 % of the bounding radius): the
// weights over the remaining techniques still sum to one, also where every enabled technique's
// connection is short and none is left out.
TEST(BptMis, PartitionOfUnityShortConnectionsFurnace) { checkPartition(Scene(furnace()), 5, "furnace", 0.3f); }
TEST(BptMis, PartitionOfUnityShortConnectionsPointLight) { checkPartition(Scene(pointLight()), 4, "point", 0.3f); }
TEST(BptMis, PartitionOfUnityShortConnectionsCornellBox) {
  checkPartition(Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf")), 5, "cornell", 0.3f);
}


// Connections and merges of every path the walks give (checkPartition's paths, glass included),
// under random eta = pi r^2 N over seven decades and random subsets of both families: each weight
// against the brute-force oracle, where a merge at x(s'-1) has n p = eta pE(x(s'-1)) p_C(s'), and
// the weights over C and M summing to one; with no merge enabled, misWeight's weights.
void checkMergePartition(const Scene& scene, int maxLength, const char* name) {
  const Camera camera(scene.cameraDesc(), 8, 8);
  Pcg32 rng(77, 3);
  int checked = 0, withMerges = 0;
  forEachConnectedPath(scene, camera, maxLength, 300, rng, [&](int s, int t, const Connection& c,
                                                          const std::vector<PathVertex>& x, const LightSubpath& lp,
                                                          const CameraSubpath& cp) {
    const int n = s + t;
    const FullPath f = densities(scene, camera, x);
    std::vector<uint8_t> surface(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) surface[static_cast<size_t>(i)] = x[static_cast<size_t>(i)].type == VertexType::Surface;
    const MisPath real{lp.data(), s, cp.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
    PathDensities d = pathDensities(scene, camera, real);
    const float minDistance = kDefaultMinConnection * scene.bounds().radius;
    // Variance-aware: the balance heuristic with a factor per technique of the length (by slot:
    // connections at s', merges at k - 1 + s'), here log-uniform over 1e-2..1e2.
    std::vector<float> factors(static_cast<size_t>(2 * (n - 1)), 1.f);
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform, MisHeuristic::VarianceAware}) {
      const MisOptions o{h, h == MisHeuristic::Power ? 1.f + 2.f * rng.next1D() : 2.f, kDefaultMinConnection};
      for (float& c : factors) c = std::pow(10.f, -2.f + 4.f * rng.next1D());
      d.factors = h == MisHeuristic::VarianceAware ? factors.data() : nullptr;
      auto factor = [&](int slot) { return d.factors ? static_cast<double>(factors[static_cast<size_t>(slot)]) : 1.0; };
      const MergeMis merge{std::pow(10.0, -4.0 + 7.0 * rng.next1D())};
      TechniqueSet enabled = TechniqueSet::all();
      if (rng.next1D() < 0.5f)
        for (int sp = 0; sp < n; ++sp)
          if (sp != s && rng.next1D() < 0.4f) enabled.disable({sp, n - sp}, maxLength);
      for (int sp = 0; sp < n; ++sp)
        EXPECT_NEAR(weightWithMerges(d, surface, Technique{sp, n - sp}, enabled, o, lightTracingRatio(), minDistance, merge),
                    weightFromDensities(d, sp, enabled, o, lightTracingRatio(), minDistance), 1e-6)
            << name << " no merge enabled, s'=" << sp;
      bool anyMerge = false;
      for (int sp = 2; sp < n; ++sp)
        if (rng.next1D() < 0.6f) enabled.enable(Technique::merge(sp, n + 1 - sp)), anyMerge = true;
      // The oracle: n p of every usable technique of both families as explicit products of the
      // vertices' densities, a delta's zero counting one (it cancels between the techniques
      // that share it). Connections: enabled, their edge free of delta vertices, as misWeight
      // (x0 hittable for s' = 0, no lens point toward infinity); merges: enabled, at an
      // interior surface vertex without a delta lobe.
      const double b = h == MisHeuristic::Power ? o.beta : 1.0;
      auto one = [](double v) { return v != 0.0 ? v : 1.0; };
      auto pC = [&](int sp) {
        double prod = 1.0;
        for (int i = 0; i < n; ++i)
          prod *= one(i == 0 && sp == 1 ? f.pLNee : i < sp ? f.pL[static_cast<size_t>(i)] : f.pE[static_cast<size_t>(i)]);
        return prod;
      };
      auto delta = [&](int i) { return x[static_cast<size_t>(i)].isDelta; };
      auto connectionPossible = [&](int sp) {
        if (!enabled.contains(sp, n - sp)) return false;
        if (sp == 0) return !x[0].isDeltaPosition && !x[0].isDeltaDirection && !delta(0);
        if (sp == 1 && n == 2 && x[0].isInfinite) return false;
        if (sp == 1 && f.pLNee == 0.0) return false;
        return !delta(sp - 1) && !delta(sp);
      };
      // --min-connection: a short connection edge is left out while a connection without one remains.
      auto shortEdge = [&](int sp) {
        return sp >= 1 && glm::distance(x[static_cast<size_t>(sp - 1)].p, x[static_cast<size_t>(sp)].p) < minDistance;
      };
      bool longRemains = false;
      for (int sp = 0; sp < n; ++sp) longRemains |= connectionPossible(sp) && !shortEdge(sp);
      auto connectionUsable = [&](int sp) { return connectionPossible(sp) && !(longRemains && shortEdge(sp)); };
      std::vector<double> pc(static_cast<size_t>(n), 0.0), pm(static_cast<size_t>(n), 0.0);
      double sumP = 0.0;
      int count = 0;
      for (int sp = 0; sp < n; ++sp) {
        if (connectionUsable(sp)) {
          pc[static_cast<size_t>(sp)] = std::pow(pC(sp) * (n - sp == 1 ? lightTracingRatio() : 1.0) * factor(sp), b);
          sumP += pc[static_cast<size_t>(sp)], ++count;
        }
        const size_t m = static_cast<size_t>(sp - 1);
        if (sp >= 2 && sp <= n - 1 && enabled.contains(Technique::merge(sp, n + 1 - sp)) && surface[m] && !delta(sp - 1)) {
          pm[static_cast<size_t>(sp)] = std::pow(merge.eta * one(f.pE[m]) * pC(sp) * factor(n - 2 + sp), b);
          sumP += pm[static_cast<size_t>(sp)], ++count;
        }
      }
      double sum = 0.0;
      for (int sp = 0; sp < n; ++sp)
        for (const bool isMerge : {false, true}) {
          if (isMerge && sp < 2) continue;
          const Technique y = isMerge ? Technique::merge(sp, n + 1 - sp) : Technique{sp, n - sp};
          const double p = (isMerge ? pm : pc)[static_cast<size_t>(sp)];
          const double expected = p > 0.0 ? (h == MisHeuristic::Uniform ? 1.0 / count : p / sumP) : 0.0;
          const double w = weightWithMerges(d, surface, y, enabled, o, lightTracingRatio(), minDistance, merge);
          EXPECT_NEAR(w, expected, 1e-4) << name << " " << (isMerge ? "M" : "C") << "(" << y.s << "," << y.t << ") of ("
                                         << s << "," << t << ") " << misHeuristicName(h) << " eta " << merge.eta;
          sum += w;
        }
      EXPECT_NEAR(sum, 1.0, 1e-5) << name << " (" << s << "," << t << ") " << misHeuristicName(h);
      ++checked;
      withMerges += anyMerge && std::any_of(pm.begin(), pm.end(), [](double p) { return p > 0.0; }) ? 1 : 0;
    }
  });
  EXPECT_GT(checked, 100) << name;
  EXPECT_GT(withMerges, 50) << name;  // merges did take part
}

TEST(MergeMis, PartitionOfUnityFurnace) { checkMergePartition(Scene(furnace()), 5, "furnace"); }
TEST(MergeMis, PartitionOfUnityPointLight) { checkMergePartition(Scene(pointLight()), 4, "point"); }
TEST(MergeMis, PartitionOfUnityEnvironment) { checkMergePartition(Scene(environmentAndSquare()), 4, "environment"); }
TEST(MergeMis, PartitionOfUnityCausticScene) {
  checkMergePartition(Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/caustic.gltf")), 5, "caustic");
}
// Medium vertices are never merged: their paths keep only the connections and the surface merges.
TEST(MergeMis, PartitionOfUnityFoggyFurnace) {
  checkMergePartition(Scene(test::foggyFurnace(0.5f, 1.f, 1.5f, 0.4f)), 5, "foggy furnace");
}
}  // namespace
}  // namespace pathlab
