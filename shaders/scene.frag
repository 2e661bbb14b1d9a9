// The 3D view's shading: the base colour lit by a light at the eye (|cos| so that both sides of a
// surface show), emitters unlit in their colour; linear colours encoded as sRGB for the display.
#version 330 core

in vec3 worldNormal;
in vec3 toEye;

uniform vec4 colour;  // linear RGB, alpha
uniform bool emitter;

out vec4 fragColour;

vec3 srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
  if (emitter) {
    fragColour = vec4(srgb(colour.rgb), 1.0);
    return;
  }
  float facing = abs(dot(normalize(worldNormal), normalize(toEye)));
  fragColour = vec4(srgb(colour.rgb * (0.2 + 0.8 * facing)), colour.a);
}
