// Shared by the emitter tests (light_test.cpp: sampleLi; light_emission_test.cpp: sampleLe, power
// and the LightSet): their family-wise chi-square significance, the spot falloff written out
// from the spec, and a small area light.
#pragma once

#include "core/lights/light.h"
#include "tests/support/chi2.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pathlab::light_test {

// Ten chi-square tests in light_test.cpp (3) and light_emission_test.cpp (7) share one
// family-wise significance of 1%.
inline const double kChi2Significance = test::sidakSignificance(0.01, 10);

// KHR_lights_punctual falloff, written out again from the spec (in double; the cone's cosines
// are rounded to float first, as the light stores them).
inline double khrSpotFalloff(double cd, float inner, float outer) {
  const double cosInner = std::cos(inner), cosOuter = std::cos(outer);
  const double lightAngleScale = 1.0 / std::max(0.001, cosInner - cosOuter);
  const double lightAngleOffset = -cosOuter * lightAngleScale;
  const double a = std::clamp(cd * lightAngleScale + lightAngleOffset, 0.0, 1.0);
  return a * a;
}

inline Light makeArea(const std::array<Vec3, 3>& p, const Spectrum& L, bool twoSided,
                      const Texture* tex = nullptr) {
  return Light::area(p[0], p[1], p[2], Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), L, tex, twoSided);
}

inline const std::array<Vec3, 3> kTri = {Vec3(-0.4f, 1.f, -0.3f), Vec3(0.6f, 1.2f, -0.2f),
                                         Vec3(0.1f, 0.9f, 0.7f)};

}  // namespace pathlab::light_test
