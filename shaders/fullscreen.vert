// One triangle that covers the viewport (no vertex buffer: positions from gl_VertexID).
#version 330 core

out vec2 uv;  // 0..1 over the viewport, y up

void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
