// Which medium (homogeneous, or scaled by a density grid) fills which part of a scene (issue 16): built once from the scene's
// meshes. A closed mesh whose material has KHR_materials_volume (thickness > 0) and transmission
// bounds a medium; volumes may nest (fog around a milky sphere) but not overlap. Every mesh gets a
// MediumInterface: the medium on the side its geometric normals point to (outside) and on the
// other (inside), so that a ray leaving a surface point knows the medium it travels in from its
// direction alone (pbrt-v4 MediumInterface).
#pragma once

#include "core/media/medium.h"
#include "core/media/volume_grid.h"
#include "core/math/medium_interface.h"
#include "core/scene/crossing_grid.h"
#include "core/scene/scene_desc.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace pathlab {

class SceneMedia {
 public:
  SceneMedia() = default;
  explicit SceneMedia(const SceneDesc& desc);

  bool empty() const { return media_.empty(); }
  const std::vector<HomogeneousMedium>& media() const { return media_; }
  const HomogeneousMedium& operator[](int i) const { return media_[static_cast<size_t>(i)]; }
  // Medium i's density grid (PATHLAB_materials_volume_grid), its coefficients then those at
  // density 1; nullptr for a homogeneous medium.
  const VolumeGrid* grid(int i) const { return grids_[static_cast<size_t>(i)].get(); }
  bool hasHeterogeneous() const { return heterogeneous_; }
  const MediumInterface& mesh(size_t m) const { return meshes_[m]; }
  // An index-matched boundary (ior 1, smooth, fully transmissive): rays pass straight through it
  // and only the medium changes; it is never a path vertex.
  bool indexMatched(size_t m) const { return indexMatched_[m] != 0; }
  // The innermost medium containing point p (-1: none): for the camera and punctual lights.
  int mediumAt(const Vec3& p) const;

 private:
  struct Volume {
    int material = -1;
    int medium = -1;                // index in media_, or -1 for a glass solid without a medium
    Vec3 lo{0.f}, hi{0.f};          // bounds of its triangles
    float size = 0.f;               // bounding-box volume, to find the innermost container
    CrossingGrid boundary;          // its triangles, for the parity of crossings
  };
  // Whether p is inside volume v: the parity of the crossings of a ray from p with its triangles.
  bool contains(const Volume& v, const Vec3& p) const;
  // The innermost volume containing p other than `exclude` (a material index), or nullptr.
  const Volume* innermost(const Vec3& p, int excludeMaterial) const;

  std::vector<HomogeneousMedium> media_;
  std::vector<std::shared_ptr<const VolumeGrid>> grids_;  // per medium; null: homogeneous
  bool heterogeneous_ = false;
  std::vector<Volume> volumes_;
  std::vector<MediumInterface> meshes_;
  std::vector<uint8_t> indexMatched_;
};

}  // namespace pathlab
