// The glTF metallic-roughness BSDF: lobe weights, evaluation, densities and sampling.
//
// Lobes (Khronos glTF 2.0 appendix B with KHR_materials_ior, _specular, _transmission):
//  - metal, weight metallic: GGX conductor, Schlick Fresnel with F0 = baseColor, F90 = 1;
//  - specular, weight (1 - metallic)(1 - transmission): GGX reflection with Schlick Fresnel,
//    F0 = min(((ior - 1) / (ior + 1))^2 specularColor, 1) specularFactor, F90 = specularFactor;
//  - diffuse, same weight: Lambert with albedo baseColor under that layer;
//  - transmission, weight (1 - metallic) transmission: a rough dielectric interface (Walter et al.
//    2007) whose exact Fresnel, scaled by specularFactor, splits reflection from refraction;
//    refraction is tinted by baseColor. For this fraction the interface's own reflection takes
//    the place of the Schlick layer, so reflection is not counted twice and smooth glass is
//    exactly Fresnel's.
// All microfacet lobes use the height-correlated Smith G2 = 1 / (1 + Lambda(o) + Lambda(i)),
// symmetric in its arguments and therefore reciprocal.
//
// Deviation from the appendix: its fresnel_mix weights the diffuse base by 1 - F(VdotH), which
// exceeds albedo 1 at grazing angles and is not reciprocal. The base here is weighted by
// (1 - F(cos theta_o)) (1 - F(cos theta_i)) with the scalar Schlick F of max(F0): symmetric, and
// since the layer reflects no more than F(cos theta_o), layer plus base stays below 1.
//
// Sides: ng points to the outside of a solid (index 1; the inside has index ior). A direction
// whose side by ns disagrees with its side by ng gets zero, so light never leaks through; the
// sign of dot(wo, ng) dot(wi, ng) alone decides reflection versus transmission. Reflection lobes
// are two-sided; the transmission lobe uses eta = ior entering and 1 / ior leaving.
#include "core/bsdf/bsdf.h"

#include "core/bsdf/fresnel.h"
#include "core/bsdf/microfacet.h"
#include "core/sampling/warp.h"

namespace pathlab {

namespace {

// Below this |cos theta| a direction is treated as grazing: all values are zero there.
constexpr float kMinCos = 1e-6f;
// Below this |ior - 1| refraction does not bend light: rough transmission degenerates to a delta.
constexpr float kMinIorDelta = 1e-3f;

Spectrum sanitize(const Spectrum& f) { return isValidContribution(f) ? f : Spectrum(0.f); }
float sanitize(float p) { return std::isfinite(p) && p > 0.f ? p : 0.f; }

}  // namespace

void Bsdf::setFrame(const Vec3& ns, const Vec3& ng) {
  ng_ = glm::normalize(ng);
  Vec3 n = glm::normalize(ns);
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = ng_;
  if (glm::dot(n, ng_) < 0.f) n = -n;
  frame_ = Frame(n);
  flatShading_ = frame_.n == ng_;
}

Bsdf::Bsdf(const Vec3& ns, const Vec3& ng, const Bsdf& lobes) : Bsdf(lobes) { setFrame(ns, ng); }

Bsdf::Bsdf(const Vec3& ns, const Vec3& ng, const MaterialPoint& material) : m_(material) {
  setFrame(ns, ng);
  m_.baseColor = glm::clamp(m_.baseColor, Spectrum(0.f), Spectrum(1.f));
  m_.metallic = glm::clamp(m_.metallic, 0.f, 1.f);
  m_.roughness = glm::clamp(m_.roughness, 0.f, 1.f);
  m_.ior = glm::max(m_.ior, 1.f);
  m_.specularFactor = glm::clamp(m_.specularFactor, 0.f, 1.f);
  m_.specularColor = glm::max(m_.specularColor, Spectrum(0.f));
  m_.transmission = glm::clamp(m_.transmission, 0.f, 1.f);

  alpha_ = m_.roughness * m_.roughness;
  reflectionDelta_ = alpha_ < kDeltaAlpha;
  transmissionDelta_ = reflectionDelta_ || m_.ior - 1.f < kMinIorDelta;

  weight_[kMetal] = m_.metallic;
  weight_[kSpecular] = weight_[kDiffuse] = (1.f - m_.metallic) * (1.f - m_.transmission);
  weight_[kTransmission] = (1.f - m_.metallic) * m_.transmission;

  const float r0 = sqr((m_.ior - 1.f) / (m_.ior + 1.f));
  f0Dielectric_ = glm::min(r0 * m_.specularColor, Spectrum(1.f)) * m_.specularFactor;
  f90Dielectric_ = m_.specularFactor;
  f0DielectricMax_ = maxComponent(f0Dielectric_);

  const float base = maxComponent(m_.baseColor);
  active_[kMetal] = weight_[kMetal] > 0.f;
  active_[kSpecular] = weight_[kSpecular] > 0.f && f90Dielectric_ > 0.f;
  active_[kDiffuse] = weight_[kDiffuse] > 0.f && base > 0.f &&
                      !(f0DielectricMax_ >= 1.f && f90Dielectric_ >= 1.f);
  active_[kTransmission] = weight_[kTransmission] > 0.f && (base > 0.f || m_.specularFactor > 0.f);
  diffuseOnly_ = active_[kDiffuse] && !active_[kMetal] && !active_[kSpecular] && !active_[kTransmission];
  // With no dielectric layer (specularFactor 0, hence F0 = F90 = 0) both Fresnel factors of the
  // base are exactly zero: the diffuse lobe is the constant below, the same expression evalLocal
  // forms with (1 - 0) (1 - 0), so the same bits.
  lambertian_ = diffuseOnly_ && f0DielectricMax_ == 0.f && f90Dielectric_ == 0.f;
  lambertianF_ = sanitize(weight_[kDiffuse] * m_.baseColor * (kInvPi * (1.f - 0.f) * (1.f - 0.f)));
  hasNonDelta_ = active_[kDiffuse] ||
                 (!reflectionDelta_ && (active_[kMetal] || active_[kSpecular])) ||
                 (!transmissionDelta_ && active_[kTransmission]);
}

// w in the shading frame, flipped so that the side ng assigns to w is +z; nullopt at grazing
// angles and where ns and ng disagree about w's side.
inline std::optional<Bsdf::Oriented> Bsdf::orient(const Vec3& w) const {
  const Vec3 local = frame_.toLocal(w);
  const float cosG = glm::dot(w, ng_);
  if (std::abs(local.z) < kMinCos || std::abs(cosG) < kMinCos || local.z * cosG <= 0.f)
    return std::nullopt;
  const float side = cosG > 0.f ? 1.f : -1.f;
  return Oriented{local * side, side};
}

// orient() for the lobes that read only the cosine to the shading normal (the diffuse lobe): the
// same z and side, bit for bit, without the two tangent components (left zero).
inline std::optional<Bsdf::Oriented> Bsdf::orientCosine(const Vec3& w) const {
  const float z = glm::dot(w, frame_.n);
  const float cosG = glm::dot(w, ng_);
  if (std::abs(z) < kMinCos || std::abs(cosG) < kMinCos || z * cosG <= 0.f) return std::nullopt;
  const float side = cosG > 0.f ? 1.f : -1.f;
  return Oriented{Vec3(0.f, 0.f, z * side), side};
}

float Bsdf::transmissionFresnel(float cosTheta, float etap) const {
  const float f = fresnelDielectric(cosTheta, etap);
  return f >= 1.f ? 1.f : m_.specularFactor * f;
}

// 1 - transmissionFresnel for a refraction pair, from both cosines (see
// fresnelDielectricTransmittance): symmetric, hence reciprocal, even next to the critical angle.
float Bsdf::transmissionTransmittance(float cosThetaI, float cosThetaT, float etap) const {
  const float k = m_.specularFactor;
  return (1.f - k) + k * fresnelDielectricTransmittance(cosThetaI, cosThetaT, etap);
}

// Proportional to each lobe's albedo at the macro-normal angle; the floors keep a lobe that can
// be non-zero samplable (a black conductor still reflects at grazing microfacets).
Bsdf::LobeProbabilities Bsdf::lobeProbabilities(float cosTheta, float etap) const {
  LobeProbabilities p{};
  if (diffuseOnly_) {  // the common Lambertian case, without the Fresnel terms that cancel
    p[kDiffuse] = 1.f;
    return p;
  }
  const float base = maxComponent(m_.baseColor);
  if (active_[kMetal]) {
    p[kMetal] = weight_[kMetal] *
                glm::max(maxComponent(fresnelSchlick(m_.baseColor, 1.f, cosTheta)), 1e-3f);
  }
  const float fs = fresnelSchlick(f0DielectricMax_, f90Dielectric_, cosTheta);
  if (active_[kSpecular]) p[kSpecular] = weight_[kSpecular] * glm::max(fs, 1e-3f);
  if (active_[kDiffuse]) p[kDiffuse] = weight_[kDiffuse] * base * (1.f - fs);
  if (active_[kTransmission]) {
    const float ft = transmissionFresnel(cosTheta, etap);
    p[kTransmission] = weight_[kTransmission] * glm::max(ft + (1.f - ft) * base, 1e-3f);
  }
  const float sum = p[0] + p[1] + p[2] + p[3];
  if (!(sum > 0.f)) return LobeProbabilities{};
  for (float& x : p) x /= sum;
  return p;
}

Spectrum Bsdf::evalLocal(const Vec3& o, const Vec3& i, float etap, TransportMode mode) const {
  Spectrum f(0.f);
  if (i.z > 0.f) {
    const bool glossyReflection =
        (!reflectionDelta_ && (active_[kMetal] || active_[kSpecular])) ||
        (!transmissionDelta_ && active_[kTransmission]);
    if (glossyReflection) {
      const Vec3 h = glm::normalize(o + i);
      const float cosH = glm::dot(o, h);
      const float common = ggx::D(h, alpha_) * ggx::G2(o, i, alpha_) / (4.f * o.z * i.z);
      if (!reflectionDelta_ && active_[kMetal])
        f += weight_[kMetal] * fresnelSchlick(m_.baseColor, 1.f, cosH) * common;
      if (!reflectionDelta_ && active_[kSpecular])
        f += weight_[kSpecular] * fresnelSchlick(f0Dielectric_, f90Dielectric_, cosH) * common;
      if (!transmissionDelta_ && active_[kTransmission])
        f += weight_[kTransmission] * transmissionFresnel(cosH, etap) * common;
    }
    if (active_[kDiffuse]) {
      const float fo = fresnelSchlick(f0DielectricMax_, f90Dielectric_, o.z);
      const float fi = fresnelSchlick(f0DielectricMax_, f90Dielectric_, i.z);
      f += weight_[kDiffuse] * m_.baseColor * (kInvPi * (1.f - fo) * (1.f - fi));
    }
    return f;
  }
  if (transmissionDelta_ || !active_[kTransmission]) return f;
  // Walter et al. 2007, eq. 21, with the generalized half vector h ~ -(o + etap i) (eq. 16).
  Vec3 h = etap * i + o;
  if (glm::dot(h, h) < 1e-12f) return f;
  h = glm::normalize(h);
  if (h.z < 0.f) h = -h;
  const float cosHo = glm::dot(o, h), cosHi = glm::dot(i, h);
  if (cosHo <= 0.f || cosHi >= 0.f) return f;  // back-facing microfacet
  const float denom = sqr(etap * cosHi + cosHo);
  if (denom < 1e-12f) return f;
  const float t = transmissionTransmittance(cosHo, -cosHi, etap);
  float ft = ggx::D(h, alpha_) * ggx::G2(o, i, alpha_) * t * std::abs(cosHi) * cosHo /
             (o.z * std::abs(i.z) * denom);
  // Radiance is compressed into the denser medium by 1 / eta^2 (Veach 1997, sec. 5.2); the
  // adjoint carries no such factor. With denom = (etap (i.h) + o.h)^2 the radiance form above
  // already equals Walter's eta_o^2-weighted one, so importance multiplies back by etap^2.
  if (mode == TransportMode::Importance) ft *= etap * etap;
  return weight_[kTransmission] * m_.baseColor * ft;
}

float Bsdf::pdfLocal(const Vec3& o, const Vec3& i, float etap) const {
  if (diffuseOnly_) return i.z > 0.f ? cosineHemispherePdf(i.z) : 0.f;
  const LobeProbabilities p = lobeProbabilities(o.z, etap);
  float pdf = 0.f;
  if (i.z > 0.f) {
    float glossy = 0.f;
    const Vec3 h = glm::normalize(o + i);
    const float cosH = glm::dot(o, h);
    if (!reflectionDelta_) glossy += p[kMetal] + p[kSpecular];
    if (!transmissionDelta_) glossy += p[kTransmission] * transmissionFresnel(cosH, etap);
    // Heitz 2018, eq. 17: the reflection Jacobian 1 / (4 o.h).
    if (glossy > 0.f && cosH > 0.f)
      pdf += glossy * ggx::visibleNormalPdf(o, h, alpha_) / (4.f * cosH);
    pdf += p[kDiffuse] * cosineHemispherePdf(i.z);
    return pdf;
  }
  if (transmissionDelta_ || p[kTransmission] == 0.f) return 0.f;
  Vec3 h = etap * i + o;
  if (glm::dot(h, h) < 1e-12f) return 0.f;
  h = glm::normalize(h);
  if (h.z < 0.f) h = -h;
  const float cosHo = glm::dot(o, h), cosHi = glm::dot(i, h);
  if (cosHo <= 0.f || cosHi >= 0.f) return 0.f;
  const float denom = sqr(etap * cosHi + cosHo);
  if (denom < 1e-12f) return 0.f;
  // Walter et al. 2007, eq. 17: d omega_h / d omega_i = etap^2 |i.h| / (etap (i.h) + o.h)^2.
  const float jacobian = etap * etap * std::abs(cosHi) / denom;
  const float t = transmissionTransmittance(cosHo, -cosHi, etap);
  return p[kTransmission] * t * ggx::visibleNormalPdf(o, h, alpha_) * jacobian;
}

float Bsdf::pdfWorld(const Vec3& wo, const Vec3& wi) const {
  const std::optional<Oriented> o = orient(wo);
  const std::optional<Oriented> i = orient(wi);
  if (!o || !i) return 0.f;
  const float etap = o->side > 0.f ? m_.ior : 1.f / m_.ior;
  return sanitize(pdfLocal(o->local, i->local * o->side * i->side, etap));
}

// Veach 1997, eq. 5.19 (pbrt-v3's CorrectShadingNormal): the adjoint BSDF with shading normals.
float Bsdf::shadingCorrection(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
  if (mode == TransportMode::Radiance) return 1.f;
  // Flat shading (ns = ng bit for bit): num and den below are the same product, and den > 0 for
  // every direction orient() accepted, so the ratio is exactly one.
  if (flatShading_) return 1.f;
  const float num = absDot(wo, frame_.n) * absDot(wi, ng_);
  const float den = absDot(wo, ng_) * absDot(wi, frame_.n);
  return den > 0.f ? num / den : 0.f;
}

BsdfEval Bsdf::eval(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
  if (!hasNonDelta_) return BsdfEval{};
  // A Lambertian surface's value and densities read only the cosines (evalOriented).
  const std::optional<Oriented> o = lambertian_ ? orientCosine(wo) : orient(wo);
  const std::optional<Oriented> i = lambertian_ ? orientCosine(wi) : orient(wi);
  if (!o || !i) return BsdfEval{};
  return evalOriented(*o, *i, wo, wi, mode);
}

// The reverse density is pdfWorld(wi, wo) with the roles of the two orientations swapped; they
// are computed once for both densities (and, from sample(), once for sample and eval together):
// the same arithmetic as orienting each direction anew, so the same bits.
BsdfDensities Bsdf::densitiesOriented(const Oriented& o, const Oriented& i) const {
  // Both flipped to wo's side: i.z < 0 exactly when ng says transmission (and likewise from wi's).
  const float flip = o.side * i.side;
  if (diffuseOnly_) {
    // pdfLocal's Lambertian case inline (the common one: every surface of the Cornell box).
    const float iz = i.local.z * flip, oz = o.local.z * flip;
    return BsdfDensities{sanitize(iz > 0.f ? cosineHemispherePdf(iz) : 0.f),
                         sanitize(oz > 0.f ? cosineHemispherePdf(oz) : 0.f)};
  }
  const float etapO = o.side > 0.f ? m_.ior : 1.f / m_.ior;
  const float etapI = i.side > 0.f ? m_.ior : 1.f / m_.ior;
  return BsdfDensities{sanitize(pdfLocal(o.local, i.local * flip, etapO)),
                       sanitize(pdfLocal(i.local, o.local * flip, etapI))};
}

// The Lambertian case of evalOriented, the same bits without its guards: f is lambertianF_ (valid
// by construction) or zero and the densities are |cos| / pi with |cos| in [kMinCos, 1], so every
// sanitize() there is the identity, and the shading correction of a flat-shaded surface is one.
BsdfEval Bsdf::evalLambertian(const Oriented& o, const Oriented& i, const Vec3& wo, const Vec3& wi,
                              TransportMode mode) const {
  const float flip = o.side * i.side;
  const float iz = i.local.z * flip, oz = o.local.z * flip;
  BsdfEval result;
  if (iz > 0.f) {
    result.f = lambertianF_;
    result.pdfFwdW = cosineHemispherePdf(iz);
  }
  if (oz > 0.f) result.pdfRevW = cosineHemispherePdf(oz);
  if (mode == TransportMode::Importance && !flatShading_) result.f = sanitize(result.f * shadingCorrection(wo, wi, mode));
  return result;
}

BsdfEval Bsdf::evalOriented(const Oriented& o, const Oriented& i, const Vec3& wo, const Vec3& wi,
                            TransportMode mode) const {
  if (lambertian_) return evalLambertian(o, i, wo, wi, mode);
  const BsdfDensities d = densitiesOriented(o, i);
  BsdfEval result;
  const Vec3 iLocal = i.local * (o.side * i.side);
  // evalLocal's Lambertian case inline; etap is needed only by the other lobes.
  const Spectrum f = evalLocal(o.local, iLocal, o.side > 0.f ? m_.ior : 1.f / m_.ior, mode);
  result.f = sanitize(mode == TransportMode::Radiance ? f : f * shadingCorrection(wo, wi, mode));
  result.pdfFwdW = d.pdfFwdW;
  result.pdfRevW = d.pdfRevW;
  return result;
}

BsdfDensities Bsdf::densities(const Vec3& wo, const Vec3& wi) const {
  if (!hasNonDelta_) return BsdfDensities{};
  // The diffuse lobe's densities read only the cosines (densitiesOriented).
  const std::optional<Oriented> o = diffuseOnly_ ? orientCosine(wo) : orient(wo);
  const std::optional<Oriented> i = diffuseOnly_ ? orientCosine(wi) : orient(wi);
  if (!o || !i) return BsdfDensities{};
  return densitiesOriented(*o, *i);
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi, TransportMode /*mode*/) const {
  return hasNonDelta_ ? pdfWorld(wo, wi) : 0.f;
}

std::optional<BsdfSample> Bsdf::sample(const Vec3& wo, Vec2 u, float uLobe,
                                       TransportMode mode) const {
  if (lambertian_) {
    // The Lambertian case alone (every surface of the Cornell box): the lobe choice below is
    // certain and only cosines are read, so this gives the general path's bits without its lobe
    // selection and tangent components.
    const std::optional<Oriented> oo = orientCosine(wo);
    if (!oo) return std::nullopt;
    const Vec3 i = sampleCosineHemisphere(u);
    if (!(i.z > 0.f)) return std::nullopt;
    BsdfSample s;
    s.wi = glm::normalize(frame_.toWorld(i * oo->side));
    const std::optional<Oriented> oi = orientCosine(s.wi);
    if (!oi || oi->side != oo->side) return std::nullopt;
    const BsdfEval e = evalOriented(*oo, *oi, wo, s.wi, mode);
    s.f = e.f;
    s.pdfFwdW = e.pdfFwdW;
    s.pdfRevW = e.pdfRevW;
    if (!(s.pdfFwdW > 0.f) || isBlack(s.f)) return std::nullopt;
    return s;
  }
  const std::optional<Oriented> oo = orient(wo);
  if (!oo) return std::nullopt;
  const Vec3 o = oo->local;
  const float etap = oo->side > 0.f ? m_.ior : 1.f / m_.ior;
  const LobeProbabilities p = lobeProbabilities(o.z, etap);

  int last = kLobeCount - 1;
  while (last >= 0 && p[last] == 0.f) --last;
  if (last < 0) return std::nullopt;
  int lobe = 0;
  float cdf = 0.f;
  while (lobe < last && (p[lobe] == 0.f || uLobe >= cdf + p[lobe])) cdf += p[lobe++];
  // The rest of uLobe chooses between reflection and refraction inside the transmission lobe.
  const float uSplit = glm::clamp((uLobe - cdf) / p[lobe], 0.f, kOneMinusEpsilon);

  const bool delta = lobe == kTransmission ? transmissionDelta_
                                           : (lobe != kDiffuse && reflectionDelta_);
  Vec3 i;
  bool reflection = true;
  float split = 1.f;  // for a delta lobe: the probability of the chosen event within the lobe
  Spectrum f(0.f);
  if (delta) {
    i = Vec3(-o.x, -o.y, o.z);
    if (lobe == kMetal) {
      f = weight_[kMetal] * fresnelSchlick(m_.baseColor, 1.f, o.z);
    } else if (lobe == kSpecular) {
      f = weight_[kSpecular] * fresnelSchlick(f0Dielectric_, f90Dielectric_, o.z);
    } else {
      const float fr = transmissionFresnel(o.z, etap);
      if (uSplit < fr) {
        split = fr;
        f = Spectrum(weight_[kTransmission] * fr);
      } else {
        const std::optional<Vec3> t = refract(o, Vec3(0.f, 0.f, 1.f), etap);
        if (!t) return std::nullopt;
        i = *t;
        reflection = false;
        split = 1.f - fr;
        f = weight_[kTransmission] * split * m_.baseColor;
        if (mode == TransportMode::Radiance) f /= etap * etap;
      }
    }
    if (std::abs(i.z) < kMinCos) return std::nullopt;
    f /= std::abs(i.z);
  } else if (lobe == kDiffuse) {
    i = sampleCosineHemisphere(u);
  } else {
    const Vec3 h = ggx::sampleVisibleNormal(o, alpha_, u);
    const float fr = lobe == kTransmission ? transmissionFresnel(glm::dot(o, h), etap) : 1.f;
    if (uSplit < fr) {
      i = reflect(o, h);
    } else {
      const std::optional<Vec3> t = refract(o, h, etap);
      if (!t) return std::nullopt;
      i = *t;
      reflection = false;
    }
  }
  if ((i.z > 0.f) != reflection) return std::nullopt;

  BsdfSample s;
  s.wi = glm::normalize(frame_.toWorld(i * oo->side));
  const std::optional<Oriented> oi = orient(s.wi);
  // The sampled direction must lie where ng agrees with the chosen event.
  if (!oi || (oi->side == oo->side) != reflection) return std::nullopt;
  s.isTransmission = !reflection;
  if (delta) {
    // Delta densities are the discrete probabilities of the event; the reverse one chooses the
    // same lobe and event from wi's side (Fresnel is the same on both sides of a refraction).
    const float etapRev = oi->side > 0.f ? m_.ior : 1.f / m_.ior;
    s.isDelta = true;
    s.f = sanitize(f * shadingCorrection(wo, s.wi, mode));
    s.pdfFwdW = p[lobe] * split;
    s.pdfRevW = lobeProbabilities(oi->local.z, etapRev)[lobe] * split;
  } else {
    // Like pbrt's BSDF::Sample over all matching components: the full non-delta value and the
    // mixture densities, consistent with eval and pdf.
    // Both directions are oriented already (oo, oi): eval(wo, s.wi) without orienting them again.
    const BsdfEval e = hasNonDelta_ ? evalOriented(*oo, *oi, wo, s.wi, mode) : BsdfEval{};
    s.f = e.f;
    s.pdfFwdW = e.pdfFwdW;
    s.pdfRevW = e.pdfRevW;
  }
  if (!(s.pdfFwdW > 0.f) || isBlack(s.f)) return std::nullopt;
  return s;
}

}  // namespace pathlab
