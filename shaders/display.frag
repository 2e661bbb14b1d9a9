// Display transform of the linear radiance image: exposure, tone map (clamp or the ACES filmic
// fit), sRGB encoding; or false colour of log10 luminance. Mirrors ui/display_settings.cpp, which
// the tests check.
#version 330 core

in vec2 uv;
out vec4 colour;

uniform sampler2D radiance;  // RGB32F, row 0 = top image row
uniform vec2 uvScale;        // the part of the texture that holds the image (previews round up)
uniform float exposureScale; // 2^stops
uniform int toneMap;         // 0 clamp, 1 ACES filmic
uniform int falseColour;     // 0 off, 1 log10 luminance
uniform float logMin;        // false colour range in decades of luminance (after exposure)
uniform float logMax;

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
vec3 acesFilmic(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 srgbEncode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Turbo colour map, polynomial fit by Google (Mikhailov 2019); t in [0,1].
vec3 turbo(float t) {
  const vec4 kR4 = vec4(0.13572138, 4.61539260, -42.66032258, 132.13108234);
  const vec4 kG4 = vec4(0.09140261, 2.19418839, 4.84296658, -14.18503333);
  const vec4 kB4 = vec4(0.10667330, 12.64194608, -60.58204836, 110.36276771);
  const vec2 kR2 = vec2(-152.94239396, 59.28637943);
  const vec2 kG2 = vec2(4.27729857, 2.82956604);
  const vec2 kB2 = vec2(-89.90310912, 27.34824973);
  t = clamp(t, 0.0, 1.0);
  vec4 v4 = vec4(1.0, t, t * t, t * t * t);
  vec2 v2 = v4.zw * v4.z;
  return vec3(dot(v4, kR4) + dot(v2, kR2), dot(v4, kG4) + dot(v2, kG2), dot(v4, kB4) + dot(v2, kB2));
}

void main() {
  vec3 L = texture(radiance, vec2(uv.x, 1.0 - uv.y) * uvScale).rgb * exposureScale;
  if (falseColour == 1) {
    float Y = dot(L, vec3(0.2126, 0.7152, 0.0722));
    // Black below the range (including zero), so "no contribution" stays distinguishable.
    if (Y <= 0.0 || log(Y) / log(10.0) < logMin) { colour = vec4(0.0, 0.0, 0.0, 1.0); return; }
    float t = (log(Y) / log(10.0) - logMin) / (logMax - logMin);
    colour = vec4(turbo(t), 1.0);  // the colour map is already perceptual: no sRGB encoding
    return;
  }
  if (toneMap == 1) L = acesFilmic(L);
  colour = vec4(srgbEncode(L), 1.0);
}
