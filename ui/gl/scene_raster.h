// The 3D view's triangles (ui/inspect/view3d.h): the scene's meshes rasterised with OpenGL from the view's
// camera into a texture of their own, simply shaded (base colour lit from the eye, emitters in
// their emission's colour, glass see-through). Drawn again only when the scene, the camera, the
// size or the culling changed: llvmpipe rasterises on the CPU the renderer is using.
#pragma once

#include "core/scene/scene.h"
#include "ui/gl/shader_program.h"
#include "ui/gl/texture.h"

#include <memory>
#include <vector>

namespace pathlab::ui {

class SceneRaster {
 public:
  SceneRaster();
  ~SceneRaster();
  SceneRaster(const SceneRaster&) = delete;
  SceneRaster& operator=(const SceneRaster&) = delete;

  // Draws `scene` seen by `view` into the texture at `size` (pixels); the meshes are uploaded once
  // per scene (held here, so a new scene is never mistaken for the one uploaded). Restores the
  // framebuffer binding it found.
  void draw(const std::shared_ptr<const Scene>& scene, const CameraDesc& view, Vec2i size, bool cullBackFaces);
  // RGBA8, bottom row first (OpenGL's): draw it with v flipped.
  const Texture& texture() const { return colour_; }

 private:
  struct Mesh {
    unsigned vertexArray = 0, vertices = 0, indices = 0;
    int indexCount = 0;
    Vec4 colour{1.f};
    bool emitter = false;
  };
  ShaderProgram program_;
  std::vector<Mesh> meshes_;
  std::shared_ptr<const Scene> uploaded_;
  unsigned framebuffer_ = 0, depth_ = 0;
  Texture colour_;
  Vec2i size_{0};
  // What the texture shows.
  Mat4 drawnView_{0.f};
  bool drawnCull_ = false;
  bool drawn_ = false;

  void upload(const Scene& scene);
  void release();
};

}  // namespace pathlab::ui
