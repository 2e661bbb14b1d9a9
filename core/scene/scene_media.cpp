// Media of a scene: the volumes' media, each mesh's interface, point containment.
#include "core/scene/scene_media.h"

#include <algorithm>
#include <limits>

namespace pathlab {

namespace {

bool isVolumeMaterial(const Material& m) { return m.volume && m.transmissionFactor > 0.f; }

}  // namespace

SceneMedia::SceneMedia(const SceneDesc& desc) {
  const size_t meshCount = desc.meshes.size();
  meshes_.assign(meshCount, MediumInterface{});
  indexMatched_.assign(meshCount, 0);
  // One medium per volume material: the closed surfaces of all its meshes bound it.
  std::vector<int> materialVolume(desc.materials.size(), -1);
  for (size_t i = 0; i < desc.materials.size(); ++i) {
    const Material& m = desc.materials[i];
    if (!isVolumeMaterial(m)) continue;
    Volume v;
    v.material = static_cast<int>(i);
    const HomogeneousMedium medium = HomogeneousMedium::fromVolume(*m.volume);
    if (!medium.isVacuum()) {
      v.medium = static_cast<int>(media_.size());
      media_.push_back(medium);
      grids_.push_back(m.volume->grid ? m.volume->grid->data : nullptr);
      if (grids_.back()) heterogeneous_ = true;
    }
    v.lo = Vec3(std::numeric_limits<float>::max());
    v.hi = Vec3(-std::numeric_limits<float>::max());
    materialVolume[i] = static_cast<int>(volumes_.size());
    volumes_.push_back(v);
  }
  if (media_.empty()) {  // nothing to track: a scene pays nothing for media it does not have
    volumes_.clear();
    return;
  }
  std::vector<std::vector<CrossingGrid::Triangle>> volumeTriangles(volumes_.size());
  for (size_t m = 0; m < meshCount; ++m) {
    const int vi = materialVolume[static_cast<size_t>(desc.meshes[m].material)];
    if (vi < 0) continue;
    Volume& v = volumes_[static_cast<size_t>(vi)];
    const TriangleMesh& mesh = desc.meshes[m];
    for (const Vec3& p : mesh.positions) {
      v.lo = glm::min(v.lo, p);
      v.hi = glm::max(v.hi, p);
    }
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t* i = &mesh.indices[3 * t];
      volumeTriangles[size_t(vi)].push_back({mesh.positions[i[0]], mesh.positions[i[1]], mesh.positions[i[2]]});
    }
  }
  for (size_t i = 0; i < volumes_.size(); ++i) {
    Volume& v = volumes_[i];
    const Vec3 e = glm::max(v.hi - v.lo, Vec3(0.f));
    v.size = e.x * e.y * e.z;
    v.boundary = CrossingGrid(std::move(volumeTriangles[i]));
  }
  for (size_t m = 0; m < meshCount; ++m) {
    const TriangleMesh& mesh = desc.meshes[m];
    if (mesh.triangleCount() == 0) continue;
    const Material& mat = desc.materials[static_cast<size_t>(mesh.material)];
    // A point of the mesh: its first triangle's centroid.
    const Vec3 c = (mesh.positions[mesh.indices[0]] + mesh.positions[mesh.indices[1]] + mesh.positions[mesh.indices[2]]) / 3.f;
    const Volume* around = innermost(c, mesh.material);
    const int16_t outside = static_cast<int16_t>(around ? around->medium : -1);
    MediumInterface& mi = meshes_[m];
    mi.outside = outside;
    mi.inside = outside;  // an opaque surface, or an invisible one: the same medium on both sides
    const int vi = materialVolume[static_cast<size_t>(mesh.material)];
    if (vi >= 0) mi.inside = static_cast<int16_t>(volumes_[static_cast<size_t>(vi)].medium);
    else if (mat.transmissionFactor > 0.f && !mat.isIndexMatched()) mi.inside = -1;  // solid glass, no medium in it
    indexMatched_[m] = mat.isIndexMatched() ? 1 : 0;
  }
}

bool SceneMedia::contains(const Volume& v, const Vec3& p) const {
  if (glm::any(glm::lessThan(p, v.lo)) || glm::any(glm::greaterThan(p, v.hi))) return false;
  return v.boundary.crossings(p) % 2 == 1;
}

const SceneMedia::Volume* SceneMedia::innermost(const Vec3& p, int excludeMaterial) const {
  const Volume* best = nullptr;
  for (const Volume& v : volumes_)
    if (v.material != excludeMaterial && (!best || v.size < best->size) && contains(v, p)) best = &v;
  return best;
}

int SceneMedia::mediumAt(const Vec3& p) const {
  if (media_.empty()) return -1;
  const Volume* v = innermost(p, -1);
  return v ? v->medium : -1;
}

}  // namespace pathlab
