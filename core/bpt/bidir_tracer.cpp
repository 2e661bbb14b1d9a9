// BidirTracer: generate, connect, weigh, accumulate.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"

namespace pathlab {

TechniqueSet techniquesOf(const RenderSettings& settings) {
  TechniqueSet set = TechniqueSet::parse(settings.techniques, settings.maxLength);
  if (settings.integrator == IntegratorKind::Lt)
    for (int k = 1; k <= settings.maxLength; ++k)
      for (int s = 0; s <= k; ++s)
        if (k + 1 - s != 1) set.disable(s, k + 1 - s);
  return set;
}

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const RenderSettings& settings)
    : scene_(scene),
      camera_(camera),
      maxLength_(settings.maxLength),
      russianRoulette_(settings.russianRoulette),
      techniques_(techniquesOf(settings)),
      mis_(settings.mis),
      isolate_(settings.isolate),
      pyramidLength_(std::min(settings.pyramidLength, settings.maxLength)),
      checkMis_(settings.checkMis) {
  // The walks need t camera vertices and s light vertices for technique (s, t), except that s = 1
  // with t >= 2 samples its light vertex afresh (next-event estimation).
  auto need = [&](int s, int t) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, t);
    if (!(s == 1 && t >= 2)) lightVerticesNeeded_ = std::max(lightVerticesNeeded_, s);
  };
  for (int k = 1; k <= maxLength_; ++k)
    for (int s = 0; s <= k; ++s)
      if (techniques_.contains(s, k + 1 - s) || k <= pyramidLength_) need(s, k + 1 - s);
  if (isolate_) need(isolate_->s, isolate_->t);
}

Spectrum BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                             Counters& counters) const {
  // Each connection draws its fresh light or lens sample from a stream of its own, keyed by the
  // sample and (s, t): a technique's estimate does not depend on which other techniques are
  // evaluated, so an isolated render, the pyramid and the full image see the same connections.
  // Drawn first, so that how long the walks below are allowed to grow changes nothing either.
  const uint64_t keyHigh = cameraRng.nextU32();  // two statements: operand order is unspecified
  const uint64_t connectionKey = keyHigh << 32 | cameraRng.nextU32();

  // Per-thread buffers sized once: no allocation per sample. Each walk stops at the longest
  // prefix any technique in use needs (light tracing needs no camera walk at all).
  thread_local CameraSubpath cameraPath;
  thread_local LightSubpath lightPath;
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, cameraRng,
                                       WalkOptions{cameraVerticesNeeded_, russianRoulette_}, cameraPath, counters);
  const int ns = lightVerticesNeeded_ > 0
                     ? generateLightSubpath(scene_, lightRng, WalkOptions{lightVerticesNeeded_, russianRoulette_},
                                            lightPath, counters)
                     : 0;

  const int pyramidLength = targets.pyramid ? pyramidLength_ : 0;
  if (targets.trace) {
    targets.trace->cameraVertices = nt;
    targets.trace->lightVertices = ns;
    targets.trace->records.clear();
  }
  auto discard = [&](const Spectrum& value, int s, int t, TechniqueCounters& tc) {
    countDiscarded(value, tc.discarded);
    counters.noteDiscard(DiscardExample{targets.id.x, targets.id.y, targets.id.sample, s, t, value});
  };
  Spectrum L(0.f);
  const float ratio = lightTracingRatio();
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= std::max(ns, 1); ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > maxLength_) continue;
      if (s > ns && !(s == 1 && t >= 2)) continue;  // next-event estimation needs no light subpath
      const bool enabled = techniques_.contains(s, t);
      const bool isolated = isolate_ && isolate_->s == s && isolate_->t == t;
      const bool inImage = isolate_ ? isolated && (enabled || isolate_->unweighted) : enabled;
      const bool inPyramid = k <= pyramidLength;
      if (!inImage && !inPyramid) continue;

      TechniqueCounters& tc = counters.technique(s, t);
      ++tc.tried;
      Pcg32 connectionRng(mixBits(connectionKey ^ (static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t))),
                          connectionKey);
      const Connection c = connect(scene_, camera_, lightPath, s, cameraPath, t, connectionRng, counters);
      if (isBlack(c.L)) {
        ++(c.blocked ? tc.blocked : tc.zero);
        if (targets.trace) targets.trace->records.push_back({s, t, c.L, 0.f, pRaster, c.blocked, false});
        continue;
      }
      ++tc.contributed;
      if (!isValidContribution(c.L)) {
        discard(c.L, s, t, tc);
        continue;
      }
      // The weight is computed over the enabled set; a disabled technique's share is zero.
      float w = 0.f;
      if (enabled) {
        const MisPath path{lightPath.data(), s, cameraPath.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
        w = misWeight(scene_, camera_, path, techniques_, mis_, ratio);
        if (checkMis_) {
          ++counters.misPartitionChecks;
          const double sum = misWeightSum(scene_, camera_, path, techniques_, mis_, ratio);
          if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
        }
      }
      if (targets.trace)
        targets.trace->records.push_back({s, t, c.L, w, t == 1 ? c.pRaster : pRaster, false, inImage});
      const Spectrum weighted = c.L * w;
      if (inPyramid) targets.pyramid->add(s, t, t == 1 ? c.pRaster : pRaster, weighted, c.L);
      if (!inImage) continue;
      const Spectrum contribution = isolated && isolate_->unweighted ? c.L : weighted;
      if (isBlack(contribution)) continue;
      if (t == 1) {
        if (targets.film && !targets.film->splat(c.pRaster, contribution)) discard(contribution, s, t, tc);
      } else {
        L += contribution;
      }
    }
  return L;
}

}  // namespace pathlab
