// The 3D view's raster: the scene's meshes uploaded when the scene changes, drawn into a framebuffer of its own.
#include "ui/gl/scene_raster.h"

#include "ui/gl/gl.h"
#include "ui/inspect/view3d.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace pathlab::ui {

SceneRaster::SceneRaster() : program_("scene.vert", "scene.frag") {
  glGenFramebuffers(1, &framebuffer_);
  glGenRenderbuffers(1, &depth_);
}

SceneRaster::~SceneRaster() {
  release();
  glDeleteRenderbuffers(1, &depth_);
  glDeleteFramebuffers(1, &framebuffer_);
}

void SceneRaster::release() {
  for (Mesh& m : meshes_) {
    glDeleteVertexArrays(1, &m.vertexArray);
    glDeleteBuffers(1, &m.vertices);
    glDeleteBuffers(1, &m.indices);
  }
  meshes_.clear();
  uploaded_.reset();
  drawn_ = false;
}

void SceneRaster::upload(const Scene& scene) {
  release();
  std::vector<float> interleaved;
  const std::vector<PreviewColour> colours = previewColours(scene);
  for (const TriangleMesh& mesh : scene.meshes()) {
    if (mesh.indices.empty()) continue;
    Mesh m;
    const PreviewColour c = mesh.material >= 0 && static_cast<size_t>(mesh.material) < colours.size()
                                ? colours[static_cast<size_t>(mesh.material)]
                                : PreviewColour{};
    m.colour = c.rgba;
    m.emitter = c.emitter;
    m.indexCount = static_cast<int>(mesh.indices.size());
    interleaved.resize(6 * mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3 n = i < mesh.normals.size() ? mesh.normals[i] : Vec3(0.f, 1.f, 0.f);
      for (int k = 0; k < 3; ++k) {
        interleaved[6 * i + static_cast<size_t>(k)] = mesh.positions[i][k];
        interleaved[6 * i + 3 + static_cast<size_t>(k)] = n[k];
      }
    }
    glGenVertexArrays(1, &m.vertexArray);
    glBindVertexArray(m.vertexArray);
    glGenBuffers(1, &m.vertices);
    glBindBuffer(GL_ARRAY_BUFFER, m.vertices);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    glGenBuffers(1, &m.indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    meshes_.push_back(m);
  }
}

void SceneRaster::draw(const std::shared_ptr<const Scene>& shared, const CameraDesc& view, Vec2i size, bool cullBackFaces) {
  if (size.x <= 0 || size.y <= 0 || !shared) return;
  if (uploaded_ != shared) {
    upload(*shared);
    uploaded_ = shared;
  }
  const Scene& scene = *shared;
  const Mat4 worldToCamera = glm::inverse(view.cameraToWorld);
  if (size == size_ && drawn_ && drawnView_ == worldToCamera && drawnCull_ == cullBackFaces) return;
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  if (size != size_) {
    colour_.uploadRgba8(size.x, size.y, nullptr);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size.x, size.y);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_.id(), 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    size_ = size;
  }
  glViewport(0, 0, size.x, size.y);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.13f, 0.13f, 0.15f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // glTF's front faces wind counter-clockwise (sec. 3.7.2.1).
  if (cullBackFaces) glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  // A pinhole like core/camera: the vertical field of view is the camera's, the aspect the area's.
  const Vec2 range = view3DDepthRange(scene, view);
  const Mat4 projection =
      glm::perspective(view.yfov, static_cast<float>(size.x) / static_cast<float>(size.y), range.x, range.y);
  const Mat4 viewProjection = projection * worldToCamera;
  glUseProgram(program_.id());
  glUniformMatrix4fv(program_.uniform("viewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
  const Vec3 eye(view.cameraToWorld[3]);
  glUniform3f(program_.uniform("eye"), eye.x, eye.y, eye.z);
  // Opaque surfaces first, then the see-through ones blended over them without writing depth.
  for (const bool seeThrough : {false, true}) {
    if (seeThrough) {
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      glDepthMask(GL_FALSE);
    }
    for (const Mesh& m : meshes_) {
      if ((m.colour.a < 1.f) != seeThrough) continue;
      glUniform4f(program_.uniform("colour"), m.colour.r, m.colour.g, m.colour.b, m.colour.a);
      glUniform1i(program_.uniform("emitter"), m.emitter ? 1 : 0);
      // Lights show from every side: a one-sided ceiling lamp stays visible from above.
      if (cullBackFaces) (m.emitter ? glDisable : glEnable)(GL_CULL_FACE);
      glBindVertexArray(m.vertexArray);
      glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
    }
  }
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
  drawnView_ = worldToCamera;
  drawnCull_ = cullBackFaces;
  drawn_ = true;
}

}  // namespace pathlab::ui
