// The glTF 2.0 metallic-roughness BSDF at one surface point: eval, sample and pdf in both
// transport directions, each returning the forward and the reverse solid-angle density.
//
// Conventions (pbrt's, Veach 1997 ch. 5):
//  - All directions are world space, unit length, pointing away from the surface.
//  - `wo` points back along the subpath being traced (toward the camera on a camera subpath,
//    toward the light on a light subpath); `wi` is the direction the subpath continues in.
//  - TransportMode::Radiance evaluates f(wi -> wo) (light arrives along wi and leaves along wo);
//    TransportMode::Importance evaluates the adjoint BSDF f*(wo -> wi), including Veach's
//    correction for shading normals (1997, eq. 5.19) and without the 1/eta^2 radiance scaling
//    of refraction (sec. 5.2), so light tracing and path tracing agree.
//  - `f` excludes the cosine; the integrator multiplies by |dot(wi, ns)|.
//  - pdfFwdW is the density of sampling wi given wo, pdfRevW that of sampling wo given wi, both in
//    solid angle and both including the probability of choosing the lobe.
#pragma once

#include "core/math/frame.h"
#include "core/math/types.h"

#include <array>
#include <optional>

namespace pathlab {

enum class TransportMode { Radiance, Importance };

// glTF metallic-roughness parameters after texture lookup, at one point (Khronos glTF 2.0 spec,
// appendix B, with KHR_materials_ior, _specular and _transmission).
struct MaterialPoint {
  Spectrum baseColor{0.8f};
  float metallic = 0.f;
  float roughness = 0.5f;        // perceptual; GGX alpha = roughness^2
  float ior = 1.5f;
  float specularFactor = 1.f;     // KHR_materials_specular: 0 gives a pure Lambertian dielectric
  Spectrum specularColor{1.f};
  float transmission = 0.f;       // KHR_materials_transmission
};

// Below this GGX alpha a lobe is an exact delta (mirror / smooth glass), flagged as such.
inline constexpr float kDeltaAlpha = 1e-3f;

struct BsdfEval {
  Spectrum f{0.f};
  float pdfFwdW = 0.f;
  float pdfRevW = 0.f;
};

// Both solid-angle densities of a direction pair, without the BSDF value: what a random walk needs
// to fill in the reverse density of the vertex it leaves (pbrt-v4 RandomWalk's bsdf.PDF calls).
struct BsdfDensities {
  float pdfFwdW = 0.f;
  float pdfRevW = 0.f;
};

struct BsdfSample {
  Spectrum f{0.f};        // for a delta lobe: the weight such that f * |cos| / pdfFwdW is the throughput
  Vec3 wi{0.f};
  float pdfFwdW = 0.f;    // for a delta lobe: the discrete probability of choosing it
  float pdfRevW = 0.f;
  bool isDelta = false;
  bool isTransmission = false;
};

class Bsdf {
 public:
  // ns: shading normal (interpolated); ng: geometric normal. Neither need face the viewer. For
  // transmission, ng points to the outside of the solid (ior is inside relative to outside).
  Bsdf(const Vec3& ns, const Vec3& ng, const MaterialPoint& material);
  // `lobes` (built from the same MaterialPoint) at another surface point: only the frame is new.
  // The lobe set-up depends on the material alone, so this equals Bsdf(ns, ng, material) bit
  // for bit, at the cost of the two normalisations (Scene::bsdf caches `lobes` per material).
  Bsdf(const Vec3& ns, const Vec3& ng, const Bsdf& lobes);
  Bsdf() = default;  // a black placeholder (subpath buffers); assign a real one before use

  // Non-delta part only; zero for delta-only materials.
  BsdfEval eval(const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  // u: a 2D sample for the direction; uLobe: a 1D sample choosing the lobe.
  std::optional<BsdfSample> sample(const Vec3& wo, Vec2 u, float uLobe, TransportMode mode) const;
  // Forward density of the non-delta part (pdfFwdW of eval).
  float pdf(const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  // pdfFwdW and pdfRevW of eval, bit for bit, without evaluating f.
  BsdfDensities densities(const Vec3& wo, const Vec3& wi) const;

  bool hasNonDelta() const { return hasNonDelta_; }
  bool isDeltaOnly() const { return !hasNonDelta_; }
  // Some lobe is a delta (smooth mirror, metal, coat or glass): a path can scatter here by it.
  bool hasDelta() const {
    return (reflectionDelta_ && (active_[kMetal] || active_[kSpecular])) || (transmissionDelta_ && active_[kTransmission]);
  }
  const Frame& shadingFrame() const { return frame_; }
  const Vec3& geometricNormal() const { return ng_; }

 private:
  enum Lobe { kMetal, kSpecular, kDiffuse, kTransmission, kLobeCount };
  using LobeProbabilities = std::array<float, kLobeCount>;

  // Selection probabilities of all lobes (delta ones included) for a direction at cosTheta to the
  // shading normal, on the side whose relative index is etap.
  LobeProbabilities lobeProbabilities(float cosTheta, float etap) const;
  // Reflectance of the transmission lobe's interface: the exact dielectric Fresnel scaled by
  // specularFactor, and 1 under total internal reflection.
  float transmissionFresnel(float cosTheta, float etap) const;
  float transmissionTransmittance(float cosThetaI, float cosThetaT, float etap) const;
  // The non-delta lobes in the shading frame flipped so that o.z > 0 (etap: index on i's side
  // over index on o's side).
  Spectrum evalLocal(const Vec3& o, const Vec3& i, float etap, TransportMode mode) const;
  float pdfLocal(const Vec3& o, const Vec3& i, float etap) const;
  float pdfWorld(const Vec3& wo, const Vec3& wi) const;
  float shadingCorrection(const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  void setFrame(const Vec3& ns, const Vec3& ng);
  struct Oriented {
    Vec3 local;  // in the shading frame, flipped so that the side ng assigns to the direction is +z
    float side;  // +1 outside (the side ng points to), -1 inside
  };
  std::optional<Oriented> orient(const Vec3& w) const;
  std::optional<Oriented> orientCosine(const Vec3& w) const;
  // eval and densities once both directions are oriented (o for wo, i for wi): each direction is
  // oriented once per call, and sample() passes on the orientations it has made already.
  BsdfEval evalOriented(const Oriented& o, const Oriented& i, const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  BsdfEval evalLambertian(const Oriented& o, const Oriented& i, const Vec3& wo, const Vec3& wi, TransportMode mode) const;
  BsdfDensities densitiesOriented(const Oriented& o, const Oriented& i) const;

  Frame frame_;
  Vec3 ng_{0.f, 0.f, 1.f};
  MaterialPoint m_;
  float alpha_ = 0.f;
  bool hasNonDelta_ = true;
  bool flatShading_ = false;        // the shading normal is the geometric one (shadingCorrection = 1)
  bool diffuseOnly_ = false;        // only the diffuse lobe is active: densities are cosine's
  bool lambertian_ = false;         // diffuse only, without a dielectric layer: f is lambertianF_
  Spectrum lambertianF_{0.f};
  float weight_[kLobeCount] = {};   // lobe weights from metallic and transmission
  bool active_[kLobeCount] = {};    // the lobe can be non-zero somewhere
  bool reflectionDelta_ = false;    // metal and specular layer are mirrors
  bool transmissionDelta_ = false;  // the transmission lobe is smooth glass
  Spectrum f0Dielectric_{0.f};
  float f90Dielectric_ = 0.f;
  float f0DielectricMax_ = 0.f;
};

}  // namespace pathlab
