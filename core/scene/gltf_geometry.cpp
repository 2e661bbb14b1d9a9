// Triangle primitives: decoding in mesh-local space (indices, normals, uvs) and instancing into
// world space with the node's transform.
#include "core/scene/gltf_internal.h"
#include "core/scene/tangents.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pathlab::gltf {
namespace {

int attribute(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it != primitive.attributes.end() ? it->second : -1;
}

bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// glTF 2.0 spec, sec. 3.7.2.1: "When normals are not specified, client implementations MUST
// calculate flat normals". Each triangle gets its own three vertices.
void makeFlat(LocalPrimitive& p) {
  const size_t triangles = p.indices.size() / 3;
  std::vector<Vec3> positions(3 * triangles), normals(3 * triangles);
  std::vector<Vec2> uvs(p.uvs.empty() ? 0 : 3 * triangles);
  std::vector<Vec2> uvs1(p.uvs1.empty() ? 0 : 3 * triangles);
  std::vector<Vec4> colors(p.colors.empty() ? 0 : 3 * triangles);
  std::vector<Vec4> tangents(p.tangents.empty() ? 0 : 3 * triangles);
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* idx = &p.indices[3 * t];
    Vec3 n = glm::cross(p.positions[idx[1]] - p.positions[idx[0]],
                        p.positions[idx[2]] - p.positions[idx[0]]);
    const float len = glm::length(n);
    // A zero-area triangle is dropped at instancing; any unit vector will do until then.
    n = len > 0.f && std::isfinite(len) ? n / len : Vec3(0.f, 0.f, 1.f);
    for (size_t k = 0; k < 3; ++k) {
      positions[3 * t + k] = p.positions[idx[k]];
      normals[3 * t + k] = n;
      if (!uvs.empty()) uvs[3 * t + k] = p.uvs[idx[k]];
      if (!uvs1.empty()) uvs1[3 * t + k] = p.uvs1[idx[k]];
      if (!colors.empty()) colors[3 * t + k] = p.colors[idx[k]];
      if (!tangents.empty()) tangents[3 * t + k] = p.tangents[idx[k]];
    }
  }
  p.positions = std::move(positions);
  p.normals = std::move(normals);
  p.uvs = std::move(uvs);
  p.uvs1 = std::move(uvs1);
  p.colors = std::move(colors);
  p.tangents = std::move(tangents);
  std::iota(p.indices.begin(), p.indices.end(), 0u);
}

// Authored normals that are zero or non-finite take the normal of a triangle that uses them.
size_t repairNormals(LocalPrimitive& p) {
  std::vector<char> invalid(p.normals.size());
  size_t count = 0;
  for (size_t i = 0; i < p.normals.size(); ++i) {
    const Vec3& n = p.normals[i];
    invalid[i] = !isFinite(n) || glm::dot(n, n) == 0.f;
    count += invalid[i];
  }
  if (count == 0) return 0;
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const uint32_t* idx = &p.indices[t];
    const Vec3 n = glm::cross(p.positions[idx[1]] - p.positions[idx[0]],
                              p.positions[idx[2]] - p.positions[idx[0]]);
    for (size_t k = 0; k < 3; ++k) {
      if (invalid[idx[k]]) p.normals[idx[k]] = n;
    }
  }
  for (size_t i = 0; i < p.normals.size(); ++i) {
    if (!isFinite(p.normals[i]) || glm::dot(p.normals[i], p.normals[i]) == 0.f) {
      p.normals[i] = Vec3(0.f, 0.f, 1.f);
    }
  }
  return count;
}

}  // namespace

const std::vector<Vec3>& AttributeCache::positions(const tinygltf::Model& model, int accessor,
                                                   const std::string& label) {
  if (auto it = vec3_.find(accessor); it != vec3_.end()) return it->second;
  std::vector<Vec3> p = readVec3(model, accessor, "POSITION of " + label);
  for (size_t i = 0; i < p.size(); ++i) {
    if (!isFinite(p[i])) {
      throw LoadError(label + ": accessor " + std::to_string(accessor) +
                      " (POSITION) has a non-finite vertex position at vertex " +
                      std::to_string(i));
    }
  }
  return vec3_.emplace(accessor, std::move(p)).first->second;
}

namespace {
// The decoded accessor from `cache`, decoded by `read` on first use.
template <class V, class Read>
const std::vector<V>& cached(std::unordered_map<int, std::vector<V>>& cache, int accessor,
                             Read read) {
  if (auto it = cache.find(accessor); it != cache.end()) return it->second;
  return cache.emplace(accessor, read()).first->second;
}
}  // namespace

const std::vector<Vec3>& AttributeCache::vec3(const tinygltf::Model& model, int accessor,
                                              const std::string& what) {
  return cached(vec3_, accessor, [&] { return readVec3(model, accessor, what); });
}

const std::vector<Vec2>& AttributeCache::vec2(const tinygltf::Model& model, int accessor,
                                              const std::string& what) {
  return cached(vec2_, accessor, [&] { return readVec2(model, accessor, what); });
}

const std::vector<Vec4>& AttributeCache::vec4(const tinygltf::Model& model, int accessor,
                                              const std::string& what) {
  return cached(vec4_, accessor, [&] { return readVec4(model, accessor, what); });
}

const std::vector<Vec4>& AttributeCache::colors(const tinygltf::Model& model, int accessor,
                                                const std::string& what) {
  return cached(colors_, accessor, [&] { return readColors(model, accessor, what); });
}

std::vector<uint32_t>& AttributeCache::remap(size_t size) {
  if (remap_.size() < size) remap_.resize(size, kUnused);
  return remap_;
}

LocalPrimitive decodePrimitive(const tinygltf::Model& model, int meshIndex, int primitiveIndex,
                               const VertexNeeds& needs, AttributeCache& cache,
                               Warnings& warnings) {
  const tinygltf::Mesh& mesh = model.meshes[size_t(meshIndex)];
  const tinygltf::Primitive& prim = mesh.primitives[size_t(primitiveIndex)];
  std::string label = "mesh " + std::to_string(meshIndex) + quotedName(mesh.name);
  if (mesh.primitives.size() > 1) label += " primitive " + std::to_string(primitiveIndex);

  LocalPrimitive out;
  out.name = !mesh.name.empty() ? mesh.name : "mesh " + std::to_string(meshIndex);
  if (mesh.primitives.size() > 1) out.name += "." + std::to_string(primitiveIndex);

  const int positionAccessor = attribute(prim, "POSITION");
  if (positionAccessor < 0) {
    // glTF 2.0 spec, sec. 3.7.2.1: without positions a client SHOULD skip the primitive.
    warnings.add(label, "no POSITION attribute; skipped");
    return out;
  }
  const std::vector<Vec3>& positions = cache.positions(model, positionAccessor, label);
  const size_t vertexCount = positions.size();
  const std::vector<Vec3>* normals = nullptr;
  if (const int accessor = attribute(prim, "NORMAL"); accessor >= 0) {
    normals = &cache.vec3(model, accessor, "NORMAL of " + label);
    if (normals->size() != vertexCount) {
      throw LoadError(label + ": NORMAL has " + std::to_string(normals->size()) +
                      " elements but POSITION has " + std::to_string(vertexCount));
    }
  }
  // An optional attribute's data, checked to have one element per vertex.
  auto optional = [&](const char* name, auto read) -> decltype(read(0, std::string())) {
    const int accessor = attribute(prim, name);
    if (accessor < 0) return nullptr;
    const auto* data = read(accessor, std::string(name) + " of " + label);
    if (data->size() != vertexCount) {
      throw LoadError(label + ": " + name + " has " + std::to_string(data->size()) +
                      " elements but POSITION has " + std::to_string(vertexCount));
    }
    return data;
  };
  auto readUv = [&](int a, const std::string& what) { return &cache.vec2(model, a, what); };
  const std::vector<Vec2>* uvs = optional("TEXCOORD_0", readUv);
  const std::vector<Vec2>* uvs1 = optional("TEXCOORD_1", readUv);
  const std::vector<Vec4>* colors =
      optional("COLOR_0", [&](int a, const std::string& what) { return &cache.colors(model, a, what); });
  const std::vector<Vec4>* tangents =
      needs.tangents && normals
          ? optional("TANGENT", [&](int a, const std::string& what) { return &cache.vec4(model, a, what); })
          : nullptr;

  if (prim.indices >= 0) {
    out.indices = readIndices(model, prim.indices, "indices of " + label);
    for (size_t i = 0; i < out.indices.size(); ++i) {
      if (out.indices[i] >= vertexCount) {
        throw LoadError(label + ": index " + std::to_string(out.indices[i]) + " (accessor " +
                        std::to_string(prim.indices) + ", element " + std::to_string(i) +
                        ") is out of range of the vertex count " + std::to_string(vertexCount));
      }
    }
  } else {
    out.indices.resize(vertexCount);
    std::iota(out.indices.begin(), out.indices.end(), 0u);
  }
  if (const size_t extra = out.indices.size() % 3; extra != 0) {
    warnings.add(label, std::to_string(out.indices.size()) +
                 " indices is not a multiple of 3; the last " + std::to_string(extra) + " ignored");
    out.indices.resize(out.indices.size() - extra);
  }

  // Keep the vertices this primitive uses, renumbered in order of first use.
  std::vector<uint32_t>& remap = cache.remap(vertexCount);
  std::vector<uint32_t> used;
  used.reserve(std::min(vertexCount, out.indices.size()));
  for (uint32_t& i : out.indices) {
    if (remap[i] == AttributeCache::kUnused) {
      remap[i] = uint32_t(used.size());
      used.push_back(i);
    }
    i = remap[i];
  }
  for (uint32_t v : used) remap[v] = AttributeCache::kUnused;
  out.positions.reserve(used.size());
  for (uint32_t v : used) out.positions.push_back(positions[v]);
  // Non-finite texture coordinates and colours would poison every lookup: repaired, counted.
  auto gatherUvs = [&](const std::vector<Vec2>* from, std::vector<Vec2>& to, const char* name) {
    if (!from) return;
    to.reserve(used.size());
    size_t bad = 0;
    for (uint32_t v : used) {
      const Vec2 uv = (*from)[v];
      const bool finite = std::isfinite(uv.x) && std::isfinite(uv.y);
      to.push_back(finite ? uv : Vec2(0.f));
      bad += !finite;
    }
    if (bad > 0) warnings.add(label, std::to_string(bad) + " non-finite " + name + " set to 0");
  };
  gatherUvs(uvs, out.uvs, "TEXCOORD_0");
  gatherUvs(uvs1, out.uvs1, "TEXCOORD_1");
  if (colors) {
    out.colors.reserve(used.size());
    for (uint32_t v : used) {
      const Vec4 c = (*colors)[v];
      const bool finite = std::isfinite(c.x + c.y + c.z + c.w);
      out.colors.push_back(finite ? glm::clamp(c, Vec4(0.f), Vec4(1.f)) : Vec4(1.f));
    }
  }
  if (tangents) {
    out.tangents.reserve(used.size());
    for (uint32_t v : used) out.tangents.push_back((*tangents)[v]);
  }
  if (normals) {
    out.normals.reserve(used.size());
    for (uint32_t v : used) out.normals.push_back((*normals)[v]);
    if (const size_t repaired = repairNormals(out); repaired > 0) {
      warnings.add(label, std::to_string(repaired) +
                   " zero or non-finite normals replaced by face normals");
    }
  } else {
    makeFlat(out);
  }
  if (needs.tangents) {
    const std::vector<Vec2>& tangentUvs = needs.tangentUvSet == 1 ? out.uvs1 : out.uvs;
    if (out.tangents.empty()) {
      out.tangents = generateTangents(out.positions, out.normals, tangentUvs, out.indices);
    } else {
      // The file's tangents, made unit and perpendicular to the normal; a degenerate one (zero,
      // non-finite, parallel to the normal) is replaced by an arbitrary perpendicular.
      for (size_t v = 0; v < out.tangents.size(); ++v) {
        const Vec4 t = out.tangents[v];
        const Vec3 xyz = std::isfinite(t.x + t.y + t.z) ? Vec3(t) : Vec3(0.f);
        out.tangents[v] = Vec4(orthogonalTangent(out.normals[v], xyz), t.w < 0.f ? -1.f : 1.f);
      }
    }
  }
  return out;
}

DroppedTriangles instantiatePrimitive(const LocalPrimitive& local, const glm::dmat4& toWorld,
                                     const std::string& label, TriangleMesh& out) {
  const size_t n = local.positions.size();
  const glm::dmat3 linear(toWorld);
  const double det = glm::determinant(linear);
  // Normals transform by the inverse transpose, here as the cofactor matrix
  // [c1 x c2, c2 x c0, c0 x c1] = det * M^-T, which stays defined for singular M; the sign of det
  // is folded in so a mirroring transform does not turn normals inside out.
  const double sign = det < 0.0 ? -1.0 : 1.0;
  const glm::dmat3 normalMatrix(sign * glm::cross(linear[1], linear[2]),
                                sign * glm::cross(linear[2], linear[0]),
                                sign * glm::cross(linear[0], linear[1]));
  // A mirroring transform reverses the winding; swapping two corners restores agreement between
  // the winding's geometric normal and the transformed shading normals.
  const bool flip = det < 0.0;

  out.positions.resize(n);
  out.normals.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec4 p = toWorld * glm::dvec4(glm::dvec3(local.positions[i]), 1.0);
    for (int k = 0; k < 3; ++k) {
      out.positions[i][k] = toFiniteFloat(
          p[k], label + ": after the node transform, vertex " + std::to_string(i) + " coordinate");
    }
    const glm::dvec3 nw = normalMatrix * glm::dvec3(local.normals[i]);
    const double len = glm::length(nw);
    out.normals[i] = len > 0.0 && std::isfinite(len) ? Vec3(nw / len) : Vec3(0.f);
  }
  out.uvs = local.uvs;
  out.uvs1 = local.uvs1;
  out.colors = local.colors;
  // A tangent is a surface direction: it transforms by the linear part itself. Under a mirroring
  // transform M, cross(M n, M t) = det(M) M (n x t) for the (sign-corrected) normal, so the
  // handedness flips with the sign of det to keep bitangent = w cross(n, t) = M b.
  out.tangents.resize(local.tangents.size());
  for (size_t i = 0; i < local.tangents.size(); ++i) {
    const Vec4 t = local.tangents[i];
    const glm::dvec3 tw = linear * glm::dvec3(Vec3(t));
    out.tangents[i] = Vec4(orthogonalTangent(out.normals[i] == Vec3(0.f) ? Vec3(0.f, 0.f, 1.f)
                                                                         : out.normals[i],
                                             Vec3(tw / std::max(glm::length(tw), 1e-300))),
                           float(sign) * t.w);
  }

  out.indices.clear();
  out.indices.reserve(local.indices.size());
  DroppedTriangles dropped;
  for (size_t t = 0; t + 2 < local.indices.size(); t += 3) {
    uint32_t i0 = local.indices[t], i1 = local.indices[t + 1], i2 = local.indices[t + 2];
    if (flip) std::swap(i1, i2);
    // The renderer's geometric normal and area light, exactly: normalize(cross(p1 - p0, p2 - p0))
    // in float, whose squared length overflows long before the corners do.
    const Vec3& p0 = out.positions[i0];
    const Vec3 ng = glm::cross(out.positions[i1] - p0, out.positions[i2] - p0);
    const float len2 = glm::dot(ng, ng);
    if (!std::isfinite(len2)) {
      const double edge = std::max({glm::length(glm::dvec3(out.positions[i1]) - glm::dvec3(p0)),
                                    glm::length(glm::dvec3(out.positions[i2]) - glm::dvec3(p0))});
      throw LoadError(label + ": triangle " + std::to_string(t / 3) + " (an edge of " +
                      formatNumber(edge) + ") is too large: its area " + overflowText());
    }
    if (!(len2 > 0.f)) {
      const uint32_t* idx = &local.indices[t];
      const Vec3 q0 = local.positions[idx[0]];
      const Vec3 localNg = glm::cross(local.positions[idx[1]] - q0, local.positions[idx[2]] - q0);
      ++(glm::dot(localNg, localNg) > 0.f ? dropped.collapsed : dropped.zeroArea);
      continue;
    }
    for (uint32_t i : {i0, i1, i2}) {
      if (out.normals[i] == Vec3(0.f)) out.normals[i] = ng / std::sqrt(len2);
    }
    out.indices.push_back(i0);
    out.indices.push_back(i1);
    out.indices.push_back(i2);
  }
  if (dropped.zeroArea + dropped.collapsed > 0) {
    // Drop the vertices only dropped triangles used: they would widen the scene's bounds.
    std::vector<uint32_t> remap(n, AttributeCache::kUnused);
    uint32_t kept = 0;
    for (uint32_t& i : out.indices) {
      if (remap[i] == AttributeCache::kUnused) remap[i] = kept++;
      i = remap[i];
    }
    auto compact = [&](auto& attribute) {
      if (attribute.empty()) return;
      std::remove_reference_t<decltype(attribute)> packed(kept);
      for (size_t v = 0; v < n; ++v) {
        if (remap[v] != AttributeCache::kUnused) packed[remap[v]] = attribute[v];
      }
      attribute = std::move(packed);
    };
    compact(out.positions);
    compact(out.normals);
    compact(out.uvs);
    compact(out.uvs1);
    compact(out.colors);
    compact(out.tangents);
  }
  return dropped;
}

}  // namespace pathlab::gltf
