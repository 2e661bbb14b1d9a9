// TechniqueCheck: per-pass sums of each technique's estimate restricted to each partner's paths.
#include "core/check/technique_check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlab {

TechniqueCheck::TechniqueCheck(int width, int height, int maxLength, int blocks)
    : width_(width), height_(height), maxLength_(maxLength), blocks_(blocks) {
  if (width < 1 || height < 1 || maxLength < 1 || maxLength > 62 /* a bit per technique of a length: kSampleableBits */ || blocks < 1 || blocks > 64)
    throw std::invalid_argument("TechniqueCheck: bad size, length or blocks");
  enabled_.assign(Technique::countUpTo(maxLength), 0);
  firstPair_.assign(static_cast<size_t>(maxLength) + 2, 0);
  for (int k = 1; k <= maxLength; ++k)
    firstPair_[static_cast<size_t>(k) + 1] = firstPair_[static_cast<size_t>(k)] + static_cast<size_t>((k + 1) * (k + 1));
  pairCount_ = firstPair_[static_cast<size_t>(maxLength) + 1];
  blockPixels_.resize(static_cast<size_t>(blocks * blocks));
  for (int b = 0; b < blocks * blocks; ++b) {
    int x0, y0, x1, y1;
    blockBounds(b, x0, y0, x1, y1);
    blockPixels_[static_cast<size_t>(b)] = static_cast<double>(x1 - x0) * static_cast<double>(y1 - y0);
  }
  pass_.assign(passValues(), 0.0);
  sums_.assign(pairCount_ * static_cast<size_t>(regions()), PairSums{});
}

size_t TechniqueCheck::pairIndex(Technique i, Technique j) const {
  const int k = i.length();
  return firstPair_[static_cast<size_t>(k)] + static_cast<size_t>(i.s * (k + 1) + j.s);
}

int TechniqueCheck::blockOf(Vec2 p) const {
  // By the pixel the position lies in, so that blockBounds counts every pixel of a block.
  const int px = std::clamp(static_cast<int>(std::floor(p.x)), 0, width_ - 1);
  const int py = std::clamp(static_cast<int>(std::floor(p.y)), 0, height_ - 1);
  return (py * blocks_ / height_) * blocks_ + px * blocks_ / width_;
}

void TechniqueCheck::blockBounds(int block, int& x0, int& y0, int& x1, int& y1) const {
  const int bx = block % blocks_, by = block / blocks_;
  // The same split blockOf inverts: pixel x is in block floor(x * blocks / width).
  auto edge = [&](int i, int size) { return (i * size + blocks_ - 1) / blocks_; };
  x0 = edge(bx, width_), x1 = edge(bx + 1, width_);
  y0 = edge(by, height_), y1 = edge(by + 1, height_);
}

void TechniqueCheck::PassSums::add(Technique x, Vec2 pRaster, float luminance, uint64_t sampleableBy) {
  const TechniqueCheck& c = *check_;
  if (!c.enabled(x) || !(luminance != 0.f)) return;
  const int k = x.length();
  const size_t block = static_cast<size_t>(c.blockOf(pRaster));
  const size_t blocks = static_cast<size_t>(c.blocks_ * c.blocks_);
  for (int sp = 0; sp <= k; ++sp) {
    const Technique partner{sp, k + 1 - sp};
    if (sp == x.s || !((sampleableBy >> sp) & 1u) || !c.enabled(partner)) continue;
    a_[c.pairIndex(x, partner) * blocks + block] += luminance;
  }
}

void TechniqueCheck::finishPass(std::vector<PassSums*> threads) {
  std::fill(pass_.begin(), pass_.end(), 0.0);
  for (PassSums* t : threads) {
    for (size_t i = 0; i < pass_.size(); ++i) pass_[i] += t->a_[i];
    t->clear();
  }
  const int blocks = blocks_ * blocks_, whole = wholeImage(blocks_);
  const double pixels = static_cast<double>(width_) * static_cast<double>(height_);
  auto accumulate = [](PairSums& p, double a, double b) {
    p.sumA += a, p.sumB += b;
    const double d = a - b;
    p.sumD += d, p.sumD2 += d * d;
    p.nonzeroA += a != 0.0 ? 1 : 0;
    p.nonzeroB += b != 0.0 ? 1 : 0;
  };
  for (int k = 1; k <= maxLength_; ++k)
    for (int si = 0; si <= k; ++si)
      for (int sj = si + 1; sj <= k; ++sj) {
        const Technique i{si, k + 1 - si}, j{sj, k + 1 - sj};
        if (!enabled(i) || !enabled(j)) continue;
        const size_t ij = pairIndex(i, j), ji = pairIndex(j, i);
        double totalA = 0.0, totalB = 0.0;
        for (int b = 0; b < blocks; ++b) {
          const double a = pass_[ij * static_cast<size_t>(blocks) + static_cast<size_t>(b)];
          const double bb = pass_[ji * static_cast<size_t>(blocks) + static_cast<size_t>(b)];
          totalA += a, totalB += bb;
          const double n = blockPixels_[static_cast<size_t>(b)];
          if (n > 0.0) accumulate(sums_[ij * static_cast<size_t>(regions()) + static_cast<size_t>(b)], a / n, bb / n);
        }
        accumulate(sums_[ij * static_cast<size_t>(regions()) + static_cast<size_t>(whole)], totalA / pixels, totalB / pixels);
      }
  ++passes_;
}

PairSums TechniqueCheck::pair(Technique i, Technique j, int region) const {
  // Stored once per unordered pair, under (lower s, higher s); the other order is its mirror.
  if (i.s < j.s) return sums_[pairIndex(i, j) * static_cast<size_t>(regions()) + static_cast<size_t>(region)];
  const PairSums& p = sums_[pairIndex(j, i) * static_cast<size_t>(regions()) + static_cast<size_t>(region)];
  return PairSums{p.sumB, p.sumA, -p.sumD, p.sumD2, p.nonzeroB, p.nonzeroA};
}

}  // namespace pathlab
