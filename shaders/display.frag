// Display transform of the linear radiance image: exposure, tone map (clamp or the ACES filmic
// fit), sRGB encoding; or false colour of log10 luminance; or the per-pixel error against a
// reference in viridis. Mirrors ui/display/display_settings.cpp, which the tests check.
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
uniform sampler2D reference;  // RGB32F, the full-resolution reference (errorView only)
uniform int errorView;        // 0 off, 1 relative squared error, 2 absolute error
uniform int errorLog;         // 1: errorMin..errorMax are decades; 0: linear 0..errorMax
uniform float errorMin;
uniform float errorMax;

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

// Viridis, degree-6 polynomial fit (Matt Zucker 2020); t in [0,1].
vec3 viridis(float t) {
  const vec3 c0 = vec3(0.2777273272234177, 0.005407344544966578, 0.3340998053353061);
  const vec3 c1 = vec3(0.1050930431085774, 1.404613529898575, 1.384590162594685);
  const vec3 c2 = vec3(-0.3308618287255563, 0.214847559468213, 0.09509516302823659);
  const vec3 c3 = vec3(-4.634230498983486, -5.799100973351585, -19.33244095627987);
  const vec3 c4 = vec3(6.228269936347081, 14.17993336680509, 56.69055260068105);
  const vec3 c5 = vec3(4.776384997670288, -13.74514537774601, -65.35303263337234);
  const vec3 c6 = vec3(-5.435455855934631, 4.645852612178535, 26.3124352495832);
  t = clamp(t, 0.0, 1.0);
  return c0 + t * (c1 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * c6)))));
}

void main() {
  if (errorView != 0) {
    // Mean over the channels of (x - r)^2 / (r^2 + 0.01) (kRelMseEpsilon) or of |x - r|.
    vec3 x = texture(radiance, vec2(uv.x, 1.0 - uv.y) * uvScale).rgb;
    vec3 r = texture(reference, vec2(uv.x, 1.0 - uv.y)).rgb;
    vec3 d = x - r;
    float e = errorView == 1 ? dot(d * d / (r * r + 0.01), vec3(1.0 / 3.0)) : dot(abs(d), vec3(1.0 / 3.0));
    float t = errorLog == 1 ? (e > 0.0 ? (log(e) / log(10.0) - errorMin) / (errorMax - errorMin) : 0.0) : e / errorMax;
    colour = vec4(viridis(t), 1.0);
    return;
  }
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
