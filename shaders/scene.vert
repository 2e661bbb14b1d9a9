// The 3D view's triangles (ui/gl/scene_raster.cpp): world-space positions and normals.
#version 330 core

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 viewProjection;
uniform vec3 eye;

out vec3 worldNormal;
out vec3 toEye;

void main() {
  worldNormal = normal;
  toEye = eye - position;
  gl_Position = viewProjection * vec4(position, 1.0);
}
