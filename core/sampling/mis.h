// MIS heuristics for combining two sampling techniques (Veach 1997, sec. 9.2).
#pragma once

namespace pathlab {

// Power heuristic with beta = 2 for one sample from each of two techniques (Veach eq. 9.13).
inline float powerHeuristic(float pdfA, float pdfB) {
  const float a = pdfA * pdfA, b = pdfB * pdfB;
  if (a == 0.f) return 0.f;
  if (!(a + b < 3.4e38f)) return pdfA >= pdfB ? 1.f : 0.f;  // overflow: the larger pdf wins
  return a / (a + b);
}

}  // namespace pathlab
