// `render --technique-maps L` output: the dominant technique (every length up to L, and each
// length), each technique's share of the image and where each cannot sample, as EXR (the numbers)
// and PNG (colours with a legend or colour bar) next to the output (core/maps/).
#pragma once

#include "core/maps/technique_maps.h"
#include "core/render/render_session.h"

#include <string>
#include <vector>

namespace pathlab::app {

// Every file the maps of length L write next to `output` (OUT.ext -> OUT-dominant.exr, .png,
// OUT-dominant-k1.exr, ..., OUT-share-s0-t2.exr, ..., OUT-share.png, OUT-cannot-s0-t2.exr, ...,
// OUT-cannot-sample.png).
// Merges (when `families` has them) as OUT-share-m-s2-t2.exr, ..., and the share of every merge
// together, OUT-share-merges.exr and .png.
std::vector<std::string> techniqueMapPaths(const std::string& output, int length,
                                           TechniqueFamilies families = TechniqueFamilies::Connections);
// The session must keep the maps' films (settings.techniqueMaps, pyramid length >= length).
void writeTechniqueMaps(const std::string& output, const RenderSession& session, int length);

// Shared with the variance maps (variance_maps_output.h):
// OUT.ext -> OUT<suffix> in the same directory.
std::string besideOutput(const std::string& output, const std::string& suffix);
// The EXR of a dominant map: (s, t, the winner's share) for a connection, (s, -t, share) for a
// merge M(s, t) (s >= 2, so never confused with what follows); (-1, -1, 0) without light and
// (-2, -2, share) for a tie.
Image dominantValues(const DominantMap& m);
// One value a pixel in all three channels.
Image grey(const std::vector<float>& v, int width, int height);
// The tiles (by Technique::index()) in the pyramid's layout (rows: length, columns: slot), each
// labelled "(s,t)" or "M(s,t)".
Image labelledMosaic(const std::vector<Image>& tiles, int length, TechniqueFamilies families);

}  // namespace pathlab::app
