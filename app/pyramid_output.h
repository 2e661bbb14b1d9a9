// `render --pyramid L` output: one image per technique (s, t), weighted and unweighted, and two
// mosaics laid out like Veach's figure 10.3 (rows: path length k = 1..L; columns: s = 0..k).
#pragma once

#include "core/render/render_session.h"

#include <string>
#include <vector>

namespace pathlab::app {

// Every file a pyramid of length L writes next to `output` (OUT.ext -> OUT-s0-t2.ext,
// OUT-s0-t2-unweighted.ext, ..., OUT-pyramid.png, OUT-pyramid-unweighted.png).
// Merges (when `families` has them) as OUT-m-s2-t2.ext.
std::vector<std::string> pyramidPaths(const std::string& output, int length,
                                      TechniqueFamilies families = TechniqueFamilies::Connections);
// Techniques up to `length` (at most the session's pyramid length).
void writePyramid(const std::string& output, const RenderSession& session, float exposure, int length);

// The mosaic column of technique x among lengths 1..length: its slot (connections by s, then the
// merges when there are any), the equiangular techniques E(1, k) in one column after the longest
// row's connections.
inline int mosaicColumn(Technique x, int length, bool merges) {
  return x.isEquiangular() ? (merges ? 2 * length : length + 1) : x.slot();
}

// Tiles of one mosaic by Technique::index() (an empty image: no tile), laid out by length (rows)
// and Technique::slot() (columns), with a gap of `gap` pixels of value `background`.
// labelValue > 0: each tile carries "(s,t) k=K" in its corner, drawn at that value.
Image techniqueMosaic(const std::vector<Image>& tiles, int length, int gap = 4, float background = 0.02f,
                      float labelValue = 0.f);

}  // namespace pathlab::app
