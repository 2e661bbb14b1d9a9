// TechniqueCheck: per-pass sums of each technique's estimate restricted to each partner's paths.
#include "core/check/technique_check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlab {

TechniqueCheck::TechniqueCheck(int width, int height, int maxLength, int blocks, TechniqueFamilies families)
    : width_(width), height_(height), maxLength_(maxLength), blocks_(blocks), families_(families) {
  // sampleableBy has a bit per slot of a length: slots(maxLength) <= 63.
  if (width < 1 || height < 1 || maxLength < 1 || maxLength > 62 || slots(maxLength) > 63 || blocks < 1 || blocks > 64)
    throw std::invalid_argument("TechniqueCheck: bad size, length or blocks");
  enabled_.assign(Technique::countUpTo(maxLength), 0);
  firstPair_.assign(static_cast<size_t>(maxLength) + 2, 0);
  for (int k = 1; k <= maxLength; ++k)
    firstPair_[static_cast<size_t>(k) + 1] = firstPair_[static_cast<size_t>(k)] + static_cast<size_t>(slots(k) * slots(k));
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
  return firstPair_[static_cast<size_t>(k)] + static_cast<size_t>(i.slot() * slots(k) + j.slot());
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

void TechniqueCheck::PassSums::add(Technique x, Vec2 pRaster, float luminance, uint64_t sampleableBy,
                                   const double* densityRatios) {
  const TechniqueCheck& c = *check_;
  if (!c.enabled(x) || !(luminance != 0.f)) return;
  const int k = x.length();
  const size_t block = static_cast<size_t>(c.blockOf(pRaster));
  const size_t blocks = static_cast<size_t>(c.blocks_ * c.blocks_);
  const double v = luminance, v2 = v * v;
  for (const Technique partner : techniquesOfLength(k, c.families_)) {
    const int sp = partner.slot();
    if (partner == x || !((sampleableBy >> sp) & 1u) || !c.enabled(partner)) continue;
    double* a = &a_[3 * (c.pairIndex(x, partner) * blocks + block)];
    a[0] += v;
    a[1] += v2;
    // p_i / p_j = 1 / (p_j / p_i); a partner able to sample the path has p_j > 0. The ratios are
    // the connections' (one per connection slot): a merge's or an equiangular technique's second
    // moment is its own samples'.
    const bool connections = x.kind == TechniqueKind::Connection && partner.kind == TechniqueKind::Connection;
    const double ratio = densityRatios && connections ? densityRatios[sp] : 0.0;
    if (ratio > 0.0 && std::isfinite(ratio)) a[2] += v2 / ratio;
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
  struct Values {
    double sum = 0.0, own2 = 0.0, cross2 = 0.0;  // of one ordered pair in one region
    Values& operator+=(const Values& o) {
      sum += o.sum, own2 += o.own2, cross2 += o.cross2;
      return *this;
    }
  };
  // a: i restricted to j (its own second moment, and j's estimated from i's samples); b: j to i.
  auto accumulate = [&](PairSums& p, const Values& a, const Values& b, double n, Technique i, Technique j) {
    const double ma = a.sum / n, mb = b.sum / n;
    p.sumA += ma, p.sumB += mb;
    const double d = ma - mb;
    p.sumD += d, p.sumD2 += d * d;
    p.nonzeroA += ma != 0.0 ? 1 : 0;
    p.nonzeroB += mb != 0.0 ? 1 : 0;
    p.ownA2 += a.own2 / (n * n), p.crossA2 += b.cross2 / (n * n);
    p.ownB2 += b.own2 / (n * n), p.crossB2 += a.cross2 / (n * n);
    // A camera-side technique has one sample per pixel of the region, light tracing one light
    // subpath per pixel of the image, wherever it lands.
    p.samplesA = i.t == 1 && !i.isMerge() ? pixels : n;
    p.samplesB = j.t == 1 && !j.isMerge() ? pixels : n;
    p.pixels = n;
  };
  for (int k = 1; k <= maxLength_; ++k)
    for (const Technique i : techniquesOfLength(k, families_))
      for (const Technique j : techniquesOfLength(k, families_)) {
        if (j.slot() <= i.slot() || !enabled(i) || !enabled(j)) continue;
        const size_t ij = pairIndex(i, j), ji = pairIndex(j, i);
        Values totalA, totalB;
        for (int b = 0; b < blocks; ++b) {
          const double* pa = &pass_[3 * (ij * static_cast<size_t>(blocks) + static_cast<size_t>(b))];
          const double* pb = &pass_[3 * (ji * static_cast<size_t>(blocks) + static_cast<size_t>(b))];
          const Values a{pa[0], pa[1], pa[2]}, bb{pb[0], pb[1], pb[2]};
          totalA += a, totalB += bb;
          const double n = blockPixels_[static_cast<size_t>(b)];
          if (n > 0.0) accumulate(sums_[ij * static_cast<size_t>(regions()) + static_cast<size_t>(b)], a, bb, n, i, j);
        }
        accumulate(sums_[ij * static_cast<size_t>(regions()) + static_cast<size_t>(whole)], totalA, totalB, pixels, i, j);
      }
  ++passes_;
}

void TechniqueCheck::absorb(const TechniqueCheck& other) {
  if (other.width_ != width_ || other.height_ != height_ || other.maxLength_ != maxLength_ || other.blocks_ != blocks_ ||
      other.families_ != families_ || other.enabled_ != enabled_)
    throw std::invalid_argument("TechniqueCheck::absorb: the checks differ in shape");
  for (size_t i = 0; i < sums_.size(); ++i) {
    PairSums& p = sums_[i];
    const PairSums& q = other.sums_[i];
    p.sumA += q.sumA, p.sumB += q.sumB, p.sumD += q.sumD, p.sumD2 += q.sumD2;
    p.nonzeroA += q.nonzeroA, p.nonzeroB += q.nonzeroB;
    p.ownA2 += q.ownA2, p.crossA2 += q.crossA2, p.ownB2 += q.ownB2, p.crossB2 += q.crossB2;
    p.samplesA = std::max(p.samplesA, q.samplesA), p.samplesB = std::max(p.samplesB, q.samplesB);
    p.pixels = std::max(p.pixels, q.pixels);
  }
  passes_ += other.passes_;
}

PairSums TechniqueCheck::pair(Technique i, Technique j, int region) const {
  // Stored once per unordered pair, under (lower slot, higher slot) as finishPass writes them; the
  // other order is its mirror. (A connection's slot is its s; a merge's follows every connection's.)
  if (i.slot() < j.slot()) return sums_[pairIndex(i, j) * static_cast<size_t>(regions()) + static_cast<size_t>(region)];
  const PairSums& p = sums_[pairIndex(j, i) * static_cast<size_t>(regions()) + static_cast<size_t>(region)];
  return PairSums{.sumA = p.sumB,
                  .sumB = p.sumA,
                  .sumD = -p.sumD,
                  .sumD2 = p.sumD2,
                  .nonzeroA = p.nonzeroB,
                  .nonzeroB = p.nonzeroA,
                  .ownA2 = p.ownB2,
                  .crossA2 = p.crossB2,
                  .ownB2 = p.ownA2,
                  .crossB2 = p.crossA2,
                  .samplesA = p.samplesB,
                  .samplesB = p.samplesA,
                  .pixels = p.pixels};
}

}  // namespace pathlab
