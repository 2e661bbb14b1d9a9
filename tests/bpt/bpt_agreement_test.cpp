// Agreement of every estimator on the bundled scenes: the path tracer, light tracing and the
// bidirectional path tracer under each MIS heuristic estimate the same image (Veach 1997, ch. 10:
// every combination of unbiased techniques with weights that sum to one over the techniques able
// to produce a path is unbiased, eq. 9.2 and sec. 10.3). Region means per channel are compared by
// z-tests whose standard errors are measured from independent passes; one Bonferroni threshold
// covers all comparisons of a test (tests/support/agreement.h). Fixed seeds; set
// PATHLAB_TEST_SEED to rerun with other seeds (the threshold must not depend on one lucky seed).
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"

#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using test::EstimatorSpec;
using test::PairSpec;
using test::PixelLabels;

// Probability that a test fails although every estimator is unbiased (Bonferroni over all of the
// test's comparisons). With ~100-250 comparisons a test this gives |z| thresholds of 4.4-4.7.
using test::kFamilyAlpha;

std::string assetPath(const std::string& name) { return std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name; }

struct Passes {
  int pt = 0, balance = 0, power = 0, lt = 0;  // 0: estimator not run
};

// Renders PT, BPT (balance, power) and LT with the same maximum length and compares
// them region by region. Label set 0 is the grid without the pixels that see a surface `leaveOut`
// selects; label set 1 also leaves out what `leaveOutOfLt` selects: at least the surfaces with a
// delta lobe, which no t = 1 technique can connect to through a pinhole (Veach 1997, sec. 10.3.5).
// Light tracing is compared on set 1 only.
test::AgreementRun runEstimators(const Scene& scene, const RenderSettings& base, const Passes& passes, int cells,
                                 const std::vector<PairSpec>& pairs, const test::MaterialPredicate& leaveOut = {},
                                 const test::MaterialPredicate& leaveOutOfLt = test::hasDeltaLobe) {
  PixelLabels grid = test::gridLabels(base.width, base.height, cells, cells);
  // 16 x 16 rays a pixel: the smallest light of veach-mis covers a few percent of a pixel.
  if (leaveOut) grid = test::withoutSeenDirectly(scene, base, grid, leaveOut, 16);
  const PixelLabels clear = test::withoutSeenDirectly(
      scene, base, grid, [&](const Material& m) { return test::hasDeltaLobe(m) || leaveOutOfLt(m); }, 8);
  std::vector<EstimatorSpec> estimators;
  uint64_t seed = 1000 * test::testSeedBase() + 1;
  auto add = [&](const std::string& name, IntegratorKind kind, MisHeuristic h, int n) {
    if (n == 0) return;
    RenderSettings s = base;
    s.integrator = kind;
    s.mis.heuristic = h;
    s.seed = seed++;
    estimators.push_back({name, s, n});
  };
  add("pt", IntegratorKind::Pt, MisHeuristic::Balance, passes.pt);
  add("balance", IntegratorKind::Bpt, MisHeuristic::Balance, passes.balance);
  add("power", IntegratorKind::Bpt, MisHeuristic::Power, passes.power);
  add("lt", IntegratorKind::Lt, MisHeuristic::Balance, passes.lt);
  return test::runAgreement(scene, estimators, {grid, clear}, pairs, kFamilyAlpha);
}

RenderSettings sceneSettings(int width, int height, int maxLength) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.maxLength = maxLength;
  return s;
}

// Pixels that see a small, very bright emitter directly or through a delta surface have the
// variance of a coin flip worth its radiance (a partly covered pixel: PT and s = 0 hits, the only
// technique that can see it through the delta surface), the same for every estimator; they would
// hide everything else in the image.
using test::emitterOrDelta;

using test::report;

// PT, BPT (balance, power) and LT on a bundled scene, each pair compared (LT on label set 1).
void expectEveryPairAgrees(const std::string& file, const RenderSettings& settings, const Passes& passes, int cells,
                           const test::MaterialPredicate& leaveOut = {}) {
  Scene scene(loadGltf(assetPath(file)));
  const auto run = runEstimators(scene, settings, passes, cells,
                                 {{"balance", "pt"},
                                  {"power", "pt"},
                                  {"lt", "pt", 1},
                                  {"power", "balance"},
                                  {"lt", "balance", 1}},
                                 leaveOut);
  report(run, file);
  test::expectAgreement(run, file);
}

// All Lambertian, one area light: every technique can produce every path, so every pair must
// agree on every region, LT included (no delta surface in view). Not the uniform heuristic, here
// or in any scene with walls: it weights every connection (s, t >= 2) by 1/k whatever its
// density, and next to a concave edge a connection's geometry term grows as 1 / d^2, so the
// uniform estimate has infinite variance there (Veach 1997, sec. 10.3: the reason the weights
// use the densities). Its mean is right, but a short render's measured standard error is not
// (seed 7 gave z = -7.7 on the Cornell box's floor along the front edge, 33 % low, while 16384
// passes of the caustic scene agree with the balance heuristic to z = 1.6). The uniform
// heuristic is tested where every geometry term is bounded: the integrating sphere
// (bpt_technique_agreement_test.cpp), the delta scenes (bpt_delta_test.cpp), and this room with
// every connection shorter than 0.3 of its radius left out (bpt_short_connection_test.cpp).
TEST(BundledAgreement, CornellBox) {
  expectEveryPairAgrees("cornell-box.gltf", sceneSettings(16, 16, 8), {768, 128, 128, 128}, 4);
}

// The mirror-and-glass box (issue 31): delta chains under Russian roulette, which spares delta
// bounces and reweights what it ends (russian_roulette.h). Every estimator agrees with the path
// tracer away from the pixels that see the light or a sphere directly (emitterOrDelta); LT is
// compared away from the spheres (label set 1).
TEST(BundledAgreement, CornellSpheres) {
  expectEveryPairAgrees("cornell-spheres.gltf", sceneSettings(16, 16, 8), {3072, 512, 512, 512}, 4, emitterOrDelta);
}

// The Cornell box through an orthographic camera (issue 15): parallel rays from a film rectangle.
// No t = 1 technique can connect to it, so light tracing is refused and BPT's weights share each
// path among the t >= 2 techniques; PT and BPT under both heuristics agree.
TEST(BundledAgreement, CornellBoxOrthographic) {
  Scene scene(loadGltf(assetPath("cornell-box.gltf")));
  RenderSettings base = sceneSettings(16, 16, 8);
  CameraDesc ortho = scene.cameraDesc();
  ortho.orthographic = Vec2(0.3f, 0.3f);
  base.camera = ortho;
  const auto run = runEstimators(scene, base, {768, 128, 128, 0}, 4,
                                 {{"balance", "pt"}, {"power", "pt"}, {"power", "balance"}});
  report(run, "cornell-box orthographic");
  test::expectAgreement(run, "cornell-box orthographic");
  RenderSettings lt = base;
  lt.integrator = IntegratorKind::Lt;
  EXPECT_THROW({ const RenderSession session(scene, lt); }, std::invalid_argument);
}

// Many lights (issue 15): a sun, a point lamp and eight lantern cubes, next-event estimation
// choosing by a light BVH, so the technique (1, t)'s density of x0 depends on x1. PT (its light
// sample weighted against BSDF sampling with the BVH's probability) and BPT under both heuristics
// agree.
TEST(BundledAgreement, ManyLights) {
  Scene scene(loadGltf(assetPath("many-lights.gltf")));
  ASSERT_TRUE(scene.lights().neeByContext());
  // The point lamp is in view: BPT's (1, 1) sees it as the point it is, which the path tracer
  // cannot (s = 0 never hits a point). Without (1, 1), both estimate the same image.
  RenderSettings base = sceneSettings(15, 10, 6);
  base.techniques.disable({1, 1}, base.maxLength);
  const auto run = runEstimators(scene, base, {6144, 1024, 1024, 0}, 3,
                                 {{"balance", "pt"}, {"power", "pt"}, {"power", "balance"}});
  report(run, "many-lights");
  test::expectAgreement(run, "many-lights");
}

// Veach's MIS scene (1997, fig. 9.2): glossy plates (the top one, roughness 0.03, has GGX alpha
// 9e-4 < kDeltaAlpha: an exact mirror) and four spherical lights of equal power, the smallest
// with radiance 900. Pixels that see a light or the mirror plate are left out (emitterOrDelta):
// every estimator samples them with the same technique (s = 0 hits, a coin flip worth 900 in a
// partly covered pixel). LT is compared away from all plates: through the sharp plates its
// (s, 1) connections are the high-variance technique, whose rare large samples make a short
// render's measured standard error unreliable. No uniform heuristic (see CornellBox); here it
// would moreover weight the s = 1 connections through the sharpest plates and the s = 0 hits
// of the smallest light by 1/k, exactly the variance fig. 9.2 is about.
//
// Up to 2 edges: direct lighting, i.e. fig. 9.2 itself, where PT (next-event estimation and BSDF
// sampling under the power heuristic) is a good estimator and must agree with BPT and LT.
TEST(BundledAgreement, VeachMisDirect) {
  Scene scene(loadGltf(assetPath("veach-mis.gltf")));
  const auto run =
      runEstimators(scene, sceneSettings(24, 16, 2), {1024, 320, 320, 384}, 4,
                    {{"balance", "pt"}, {"power", "pt"}, {"lt", "pt", 1}, {"power", "balance"}, {"lt", "balance", 1}},
                    emitterOrDelta, [](const Material& m) { return m.metallicFactor > 0.f; });
  report(run, "veach-mis, 2 edges");
  test::expectAgreement(run, "veach-mis, 2 edges");
}

// Full length: the plates also throw the lights' glossy reflections onto the floor and the back
// wall (L G D E), which the path tracer finds only by hitting a small light after a glossy
// bounce (the caustic problem, see CausticFullLength), so BPT's heuristics and LT are compared
// with each other here.
TEST(BundledAgreement, VeachMisFullLength) {
  Scene scene(loadGltf(assetPath("veach-mis.gltf")));
  const auto run = runEstimators(scene, sceneSettings(24, 16, 8), {0, 256, 256, 384}, 4,
                                 {{"power", "balance"}, {"lt", "balance", 1}}, emitterOrDelta,
                                 [](const Material& m) { return m.metallicFactor > 0.f; });
  report(run, "veach-mis");
  test::expectAgreement(run, "veach-mis");
}

// Indirect light from a spot light aimed at the ceiling, a glass sphere and glossy surfaces. The
// spot reaches only the Lambertian ceiling (make_scenes.py: the shade's rim is outside the cone),
// so every path's x1 is non-delta and the path tracer's s = 1 connection can sample all of them:
// PT agrees with BPT everywhere; LT everywhere but on the glass sphere (label set 1). No uniform
// heuristic in a room (see CornellBox).
TEST(BundledAgreement, BidirLamp) {
  expectEveryPairAgrees("bidir-lamp.gltf", sceneSettings(15, 15, 8), {768, 96, 96, 128}, 3);
}

// The caustic scene up to 3 edges: direct light, one diffuse bounce, and the light seen through
// the sphere (L S S E, only s = 0 can sample it). No caustic yet (L S S D E has 4 edges), so the
// path tracer's variance is moderate and it must agree with every other estimator. No uniform
// heuristic (see CornellBox); here it would moreover weight the s = 0 hits of the 0.1 m light
// (Le = 1000, hit with a probability of ~1e-4 per bounce) by 1/k, like a path tracer without
// next-event estimation (16384 passes agree with the balance heuristic, 128 do not).
TEST(BundledAgreement, CausticUpToThreeEdges) {
  Scene scene(loadGltf(assetPath("caustic.gltf")));
  const auto run =
      runEstimators(scene, sceneSettings(16, 16, 3), {1024, 128, 128, 384}, 4,
                    {{"balance", "pt"}, {"power", "pt"}, {"lt", "pt", 1}, {"power", "balance"}, {"lt", "balance", 1}},
                    emitterOrDelta);
  report(run, "caustic, 3 edges");
  test::expectAgreement(run, "caustic, 3 edges");
}

// The caustic scene at full length. The caustic (L S S D E) is sampled only by t = 1 (s = 4) and,
// with a tiny probability, by s = 0 (the camera path must hit the 0.1 m light through the glass);
// s = 1..3 cannot connect to a glass vertex. The path tracer finds it with a per-sample
// probability of ~1e-4 (and the light reflected by the caustic onto the walls ~1e-5): its
// estimate is unbiased but the error of a short render is dominated by hits it has not made yet,
// and the measured standard error misses them. So the path tracer is checked up to 3 edges
// above; here the balance and power heuristics and LT (away from the sphere) are compared with
// each other.
TEST(BundledAgreement, CausticFullLength) {
  Scene scene(loadGltf(assetPath("caustic.gltf")));
  const auto run = runEstimators(scene, sceneSettings(16, 16, 8), {0, 128, 128, 384}, 4,
                                 {{"power", "balance"}, {"lt", "balance", 1}}, emitterOrDelta);
  report(run, "caustic");
  test::expectAgreement(run, "caustic");
}

// Fog (issue 16), medium vertices in every technique. In the bundled fog scene the spot light's
// light reaches the room almost only through the glass sphere: reflected off it into the fog
// (spot -> glass -> fog -> camera, 3 edges) or focused into the volumetric caustic under it (spot
// -> glass -> glass -> fog -> camera), paths that only light tracing (t = 1) can sample (no
// camera path hits a point light; no connection reaches a glass vertex). So there the heuristics
// and LT are compared with each other; the path tracer is compared on the scene below.
// A milky glass cube (ior 1.5, a scattering medium inside) on a floor, under an area light, all in
// thin fog: a medium inside glass, nested in another, and every path sampleable by the path
// tracer (its s = 0 hits reach the area light through any chain). The camera sees the cube: LT
// is compared away from it (label set 1).
SceneDesc milkyGlassInFog() {
  SceneDesc desc;
  desc.path = "milky glass in fog";
  Material glass = test::mediumBoundary(Spectrum(3.f, 2.5f, 2.1f), true, 0.2f);
  glass.name = "milky glass";
  glass.ior = 1.5f;  // refracting: a glass surface with a medium inside
  glass.volume->multiscatterColor = Spectrum(0.95f, 0.9f, 0.8f);  // some absorption
  desc.materials = {test::lambertian(0.6f), test::lambertian(0.f, Spectrum(2.f)), glass,
                    test::mediumBoundary(Spectrum(0.25f), true, 0.3f)};
  const float F = 2.f;
  desc.meshes = {test::quad(Vec3(-F, 0, F), Vec3(F, 0, F), Vec3(F, 0, -F), Vec3(-F, 0, -F), 0),
                 test::quad(Vec3(-0.6f, 1.5f, -0.6f), Vec3(0.6f, 1.5f, -0.6f), Vec3(0.6f, 1.5f, 0.6f),
                            Vec3(-0.6f, 1.5f, 0.6f), 1)};  // faces down
  for (TriangleMesh& m : test::outwardBox(Vec3(-0.3f, 0.01f, -0.3f), Vec3(0.3f, 0.61f, 0.3f), 2))
    desc.meshes.push_back(std::move(m));
  for (TriangleMesh& m : test::outwardBox(Vec3(-2.5f, -0.5f, -2.5f), Vec3(2.5f, 2.f, 2.5f), 3))
    desc.meshes.push_back(std::move(m));
  desc.camera = test::lookAt(Vec3(0.4f, 0.9f, 1.8f), Vec3(0.f, 0.3f, 0.f), Vec3(0, 1, 0), 0.9f);
  return desc;
}

TEST(BundledAgreement, MilkyGlassInFog) {
  Scene scene(milkyGlassInFog());
  ASSERT_EQ(scene.media().media().size(), 2u);
  const auto run = runEstimators(scene, sceneSettings(16, 16, 6), {1024, 192, 192, 2048}, 4,
                                 {{"balance", "pt"}, {"power", "pt"}, {"lt", "pt", 1}, {"power", "balance"}, {"lt", "balance", 1}},
                                 test::isEmissive);
  report(run, "milky glass in fog");
  test::expectAgreement(run, "milky glass in fog");
}

// Subsets of techniques and single unweighted techniques through media: subsets holding s = 0
// (which samples every path of this scene: the camera walk reaches the area light through any
// chain) give the full image under each heuristic, and the three unweighted techniques of length 2
// give the same image of the paths of two edges, medium vertices at either end of the connection
// and on the walks. Away from the pixels that see the glass (no connection reaches a delta vertex
// next to the camera) and the light.
TEST(BundledAgreement, MilkyGlassInFogSubsetsAndUnweightedTechniques) {
  Scene scene(milkyGlassInFog());
  RenderSettings base = sceneSettings(16, 16, 4);
  PixelLabels grid = test::gridLabels(base.width, base.height, 2, 2);
  grid = test::withoutSeenDirectly(scene, base, grid, [](const Material& m) { return test::hasDeltaLobe(m) || m.isEmissive(); }, 8);
  uint64_t seed = 1000 * test::testSeedBase() + 501;
  auto spec = [&](const std::string& name, const char* techniques, MisHeuristic h, int passes, int maxLength,
                  std::optional<Isolation> isolate = std::nullopt) {
    RenderSettings s = base;
    s.integrator = IntegratorKind::Bpt;
    s.maxLength = maxLength;
    s.mis.heuristic = h;
    if (techniques) s.techniques = TechniqueSet::parse(techniques);
    s.isolate = isolate;
    s.seed = seed++;
    return test::EstimatorSpec{name, s, passes};
  };
  const std::vector<test::EstimatorSpec> estimators = {
      spec("all", nullptr, MisHeuristic::Balance, 192, 4),
      spec("s=0", "s=0", MisHeuristic::Balance, 384, 4),
      spec("s=0;t=1", "s=0;t=1", MisHeuristic::Uniform, 384, 4),
      spec("s=0;2,2;3,2", "s=0;2,2;3,2", MisHeuristic::Power, 384, 4),
      spec("(0,3)", nullptr, MisHeuristic::Balance, 1024, 2, Isolation{0, 3, true}),
      spec("(1,2)", nullptr, MisHeuristic::Balance, 1024, 2, Isolation{1, 2, true}),
      spec("(2,1)", nullptr, MisHeuristic::Balance, 2048, 2, Isolation{2, 1, true})};
  const auto run = test::runAgreement(scene, estimators, {grid},
                                      {{"s=0", "all"}, {"s=0;t=1", "all"}, {"s=0;2,2;3,2", "all"},
                                       // Light tracing alone has infinite variance in a medium
                                       // around a pinhole (a point at distance r from the lens
                                       // adds ~1/r^2): its error falls slowly, so its comparisons
                                       // ask for less power (a bias of about 30 % still shows).
                                       {"(1,2)", "(0,3)"}, {"(2,1)", "(0,3)", 0, 0.1}, {"(2,1)", "(1,2)", 0, 0.1}},
                                      kFamilyAlpha);
  report(run, "milky glass in fog, subsets and unweighted techniques");
  test::expectAgreement(run, "milky glass in fog, subsets and unweighted techniques");
}

TEST(BundledAgreement, FogFullLength) {
  Scene scene(loadGltf(assetPath("fog.gltf")));
  const auto run = runEstimators(scene, sceneSettings(16, 16, 6), {0, 256, 256, 4096}, 4,
                                 {{"power", "balance"}, {"lt", "balance", 1}}, emitterOrDelta);
  report(run, "fog");
  test::expectAgreement(run, "fog");
}

}  // namespace
}  // namespace pathlab
