// MIS heuristics for combining two sampling techniques (Veach 1997, sec. 9.2).
#pragma once

#include <algorithm>

namespace pathlab {

// Power heuristic with beta = 2 for one sample from each of two techniques (Veach eq. 9.13).
inline float powerHeuristic(float pdfA, float pdfB) {
  const float a = pdfA * pdfA, b = pdfB * pdfB;
  if (a == 0.f) return 0.f;
  if (!(a + b < 3.4e38f)) return pdfA >= pdfB ? 1.f : 0.f;  // overflow: the larger pdf wins
  return a / (a + b);
}

// The same among three techniques (a zero density: that technique is off or cannot sample the
// path); with one of the others zero it is the two-technique form, to the bit.
inline float powerHeuristic(float pdfA, float pdfB, float pdfC) {
  if (pdfC == 0.f) return powerHeuristic(pdfA, pdfB);
  if (pdfB == 0.f) return powerHeuristic(pdfA, pdfC);
  if (!(pdfA > 0.f)) return 0.f;
  const float m = std::max({pdfA, pdfB, pdfC});
  if (!(m < 3.4e38f)) return pdfA >= m ? 1.f : 0.f;  // an infinite density wins
  const float a = pdfA / m, b = pdfB / m, c = pdfC / m;  // in [0, 1]: the squares cannot overflow
  return a * a / (a * a + b * b + c * c);
}

}  // namespace pathlab
