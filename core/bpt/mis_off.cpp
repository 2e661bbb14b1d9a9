// MIS off: the table of constant weights and the scene analysis of where they are biased.
#include "core/bpt/mis_off.h"

#include "core/bpt/mis.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab {

std::vector<float> misOffWeights(const TechniqueSet& techniques, int maxLength, MediumSampling mediumSampling) {
  std::vector<float> weights(static_cast<size_t>(std::max(maxLength, 0) + 1), 0.f);
  for (int k = 1; k <= maxLength; ++k) {
    const int n = techniquesEnabledOfLength(techniques, k, mediumSampling);
    weights[static_cast<size_t>(k)] = n > 0 ? 1.f / static_cast<float>(n) : 0.f;
  }
  return weights;
}

std::string lengthRanges(const std::vector<int>& lengths) {
  std::string out;
  for (size_t i = 0; i < lengths.size();) {
    size_t j = i;
    while (j + 1 < lengths.size() && lengths[j + 1] == lengths[j] + 1) ++j;
    if (!out.empty()) out += ", ";
    out += j == i ? fmt::format("{}", lengths[i]) : fmt::format("{}-{}", lengths[i], lengths[j]);
    i = j + 1;
  }
  return out;
}

namespace {

// Whether some path of length k has 0 < c(x) < n_k when the techniques in `impossible` (by s)
// cannot sample it and every other one can.
bool splits(const TechniqueSet& techniques, int k, const std::vector<int>& impossible) {
  int blind = 0, able = 0;
  for (int s = 0; s <= k; ++s) {
    if (!techniques.contains(s, k + 1 - s)) continue;
    const bool cannot = std::find(impossible.begin(), impossible.end(), s) != impossible.end();
    (cannot ? blind : able) += 1;
  }
  return blind > 0 && able > 0;
}

std::string quotedList(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < 3; ++i) out += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > 3) out += fmt::format(" and {} more", names.size() - 3);
  return out;
}

}  // namespace

MisOffBias misOffBias(const Scene& scene, const TechniqueSet& techniques, int maxLength, bool pinhole,
                      bool orthographic, MediumSampling mediumSampling) {
  MisOffBias bias;
  std::vector<bool> biased(static_cast<size_t>(std::max(maxLength, 0) + 1), false);
  auto note = [&](const std::vector<int>& lengths, const std::string& why) {
    if (lengths.empty()) return;
    for (int k : lengths) biased[static_cast<size_t>(k)] = true;
    bias.reasons.push_back(fmt::format("{}: length{} {}", why, lengths.size() > 1 ? "s" : "", lengthRanges(lengths)));
  };

  // Delta lights: a path starting on one is missed by s = 0 alone.
  int point = 0, spot = 0, directional = 0;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const LightType type = scene.lights()[i].type();
    point += type == LightType::Point;
    spot += type == LightType::Spot;
    directional += type == LightType::Directional;
  }
  if (point + spot + directional > 0) {
    std::vector<int> lengths;
    for (int k = 1; k <= maxLength; ++k)
      if (splits(techniques, k, {0})) lengths.push_back(k);
    std::vector<std::string> kinds;
    auto kind = [&](int n, const char* name) {
      if (n > 0) kinds.push_back(n == 1 ? fmt::format("the {} light", name) : fmt::format("the {} {} lights", n, name));
    };
    kind(point, "point");
    kind(spot, "spot");
    kind(directional, "directional");
    std::string what = kinds[0];
    for (size_t i = 1; i < kinds.size(); ++i) what += (i + 1 == kinds.size() ? " and " : ", ") + kinds[i];
    note(lengths, fmt::format("s = 0 cannot hit {} (delta)", what));
  }

  // Delta BSDFs: at an interior vertex x_i of a length-k path, s = i and s = i + 1 connect there.
  std::vector<std::string> deltaMaterials;
  for (size_t m = 0; m < scene.materials().size(); ++m) {
    const Bsdf bsdf = scene.bsdf(static_cast<int>(m), Vec2(0.5f), Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, 1.f));
    if (bsdf.hasDelta()) deltaMaterials.push_back(scene.materials()[m].name.empty() ? fmt::format("#{}", m)
                                                                                     : scene.materials()[m].name);
  }
  if (!deltaMaterials.empty()) {
    std::vector<int> lengths;
    for (int k = 2; k <= maxLength; ++k)
      for (int i = 1; i <= k - 1; ++i)
        if (splits(techniques, k, {i, i + 1})) {
          lengths.push_back(k);
          break;
        }
    note(lengths, fmt::format("s = i and i + 1 cannot connect at a delta-BSDF vertex x_i ({})", quotedList(deltaMaterials)));
  }

  // An orthographic camera's importance is a delta in direction: s = k (t = 1) never joins it.
  if (orthographic) {
    std::vector<int> lengths;
    for (int k = 1; k <= maxLength; ++k)
      if (splits(techniques, k, {k})) lengths.push_back(k);
    note(lengths, "t = 1 cannot connect to the orthographic camera (a delta direction)");
  }

  // bpt's equiangular techniques (issue 35): E(1, k) counts in n_k wherever it is enabled but
  // samples only the paths whose vertex next to the light lies in a homogeneous scattering medium.
  if (mediumSampling != MediumSampling::Distance) {
    std::vector<int> lengths;
    for (int k = 2; k <= maxLength; ++k)
      if (techniques.contains(Technique::equiangular(k))) lengths.push_back(k);
    note(lengths, "E(1,k) samples only paths whose vertex next to the light is in a homogeneous scattering medium");
  }

  for (int k = 1; k <= maxLength; ++k)
    if (biased[static_cast<size_t>(k)]) bias.lengths.push_back(k);
  if (pinhole && !orthographic && bias.biased()) bias.reasons.push_back("the pinhole cannot be hit, but there is no t = 0 technique: no bias");
  return bias;
}

std::string misOffWarning(const MisOffBias& bias) {
  if (!bias.biased()) return "";
  std::string out = fmt::format("mis off: length{} {} biased (1/n_k also goes to the techniques that cannot sample a path): ",
                                bias.lengths.size() > 1 ? "s" : "", lengthRanges(bias.lengths));
  for (size_t i = 0; i < bias.reasons.size(); ++i) out += (i ? "; " : "") + bias.reasons[i];
  return out;
}

}  // namespace pathlab
