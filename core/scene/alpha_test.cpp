// Embree filter callbacks for glTF alpha modes (see alpha_test.h).
#include "core/scene/alpha_test.h"

#include "core/math/rng.h"

#include <bit>

namespace pathlab {

bool alphaCovers(const AlphaGeometry& g, uint32_t prim, float b1, float b2, float u) {
  const TriangleMesh& mesh = *g.mesh;
  const Material& m = *g.material;
  const uint32_t* tri = &mesh.indices[3 * size_t(prim)];
  const float b0 = 1.f - b1 - b2;
  auto interpolate = [&](const auto& values) {
    return b0 * values[tri[0]] + b1 * values[tri[1]] + b2 * values[tri[2]];
  };
  const Vec2 uv0 = mesh.uvs.empty() ? Vec2(0.f) : interpolate(mesh.uvs);
  const Vec2 uv1 = mesh.uvs1.empty() ? uv0 : interpolate(mesh.uvs1);
  const float vertexAlpha = mesh.colors.empty() ? 1.f : interpolate(mesh.colors).a;
  const float alpha = evalAlpha(m, uv0, uv1, vertexAlpha, *g.textures);
  if (m.alphaMode == AlphaMode::Mask) return alpha >= m.alphaCutoff;
  return u < alpha;
}

namespace {

// A uniform number in [0, 1) that is a function of the ray and the triangle only: a BLEND
// surface then answers the same for the same ray however often Embree asks (it may call a
// filter more than once for one triangle), and differently for every other ray.
float blendDecision(const RTCFilterFunctionNArguments* args, unsigned i, uint32_t geom,
                    uint32_t prim) {
  const float values[6] = {RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                           RTCRayN_org_z(args->ray, args->N, i), RTCRayN_dir_x(args->ray, args->N, i),
                           RTCRayN_dir_y(args->ray, args->N, i), RTCRayN_dir_z(args->ray, args->N, i)};
  uint64_t h = mixBits((uint64_t(geom) << 32) | prim);
  for (float v : values) h = mixBits(h ^ std::bit_cast<uint32_t>(v));
  return float(h >> 40) * 0x1p-24f;
}

void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const AlphaGeometry*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const uint32_t geom = RTCHitN_geomID(args->hit, args->N, i);
    const float u = g->material->alphaMode == AlphaMode::Blend ? blendDecision(args, i, geom, prim) : 0.f;
    if (!alphaCovers(*g, prim, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i), u))
      args->valid[i] = 0;
  }
}

}  // namespace

void attachAlphaFilter(RTCGeometry geometry, const AlphaGeometry* g) {
  rtcSetGeometryUserData(geometry, const_cast<AlphaGeometry*>(g));
  rtcSetGeometryIntersectFilterFunction(geometry, alphaFilter);
  rtcSetGeometryOccludedFilterFunction(geometry, alphaFilter);
}

}  // namespace pathlab
