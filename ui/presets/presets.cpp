// Named presets: JSON parsing with one-line errors, and applying a preset to the settings.
#include "ui/presets/presets.h"

#include "core/bpt/technique_set.h"
#include "core/sampling/technique_label.h"
#include "core/io/guarded_file.h"
#include "ui/lane/compare.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace pathlab::ui {

namespace {

using Json = nlohmann::json;

// A presets file is a page of JSON written by hand: 16 MiB is far past any real one.
constexpr uint64_t kMaxPresetsBytes = uint64_t(16) << 20;

const std::set<std::string> kKeys = {"name", "integrator", "techniques", "mis", "beta", "minConnection", "maxLength",
                                     "isolate", "unweighted", "camera", "compare", "description", "mediumSampling"};

// A JSON number as a float, refused when it is not finite as a float (1e39 is a double but no float,
// and would come back as "camera transform entry -nan" far from the file).
float finiteFloat(const Json& j, const std::string& what) {
  const double v = j.get<double>();
  if (!(std::abs(v) <= double(std::numeric_limits<float>::max())))
    throw std::invalid_argument(fmt::format("{} {} is not a finite 32-bit number", what, j.dump()));
  return float(v);
}

Vec3 vec3Of(const Json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw std::invalid_argument(what + " must be an array of 3 numbers");
  return {finiteFloat(j[0], what), finiteFloat(j[1], what), finiteFloat(j[2], what)};
}

// A JSON integer in [lo, hi], compared before narrowing (get<int> wraps 4294967300 to 4).
int integerIn(const Json& j, const std::string& what, int lo, int hi) {
  const bool inRange = j.is_number_unsigned() ? j.get<uint64_t>() <= uint64_t(std::max(hi, 0)) && j.get<int64_t>() >= lo
                                              : j.get<int64_t>() >= lo && j.get<int64_t>() <= hi;
  if (!inRange) throw std::invalid_argument(fmt::format("{} must be in [{}, {}], not {}", what, lo, hi, j.dump()));
  return int(j.get<int64_t>());
}

const Json& typed(const Json& p, const char* key, bool (Json::*is)() const noexcept, const char* type) {
  const Json& v = p.at(key);
  if (!(v.*is)()) throw std::invalid_argument(fmt::format("\"{}\" must be {}", key, type));
  return v;
}

// The file's strings (names, keys, values) go into messages as they are, and a JSON string may hold
// a newline ("\n"): control characters are written as escapes, so a message stays one line.
std::string oneLine(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) out += c;
    else if (c == '\n') out += "\\n";
    else out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
  }
  return out;
}

[[noreturn]] void refuse(const std::string& message) { throw PresetError(oneLine(message)); }

NamedPreset parseOne(const Json& p) {
  if (!p.is_object()) throw std::invalid_argument("is not an object");
  for (const auto& [key, value] : p.items())
    if (!kKeys.count(key)) throw std::invalid_argument(fmt::format("unknown key \"{}\"", key));
  NamedPreset out;
  if (!p.contains("name")) throw std::invalid_argument("has no \"name\"");
  out.name = typed(p, "name", &Json::is_string, "a string").get<std::string>();
  if (out.name.empty()) throw std::invalid_argument("\"name\" is empty");
  if (p.contains("integrator")) {
    const std::string v = typed(p, "integrator", &Json::is_string, "a string").get<std::string>();
    // vcm, bpm and ppm are bpt with a technique set of their own, as on the command line.
    const char* own = nullptr;
    if (v == "bpt") out.integrator = IntegratorKind::Bpt;
    else if (v == "pt") out.integrator = IntegratorKind::Pt;
    else if (v == "lt") out.integrator = IntegratorKind::Lt;
    else if (v == "mlt") out.integrator = IntegratorKind::Mlt;
    else if (v == "vcm") own = "all;m=all";
    else if (v == "bpm") own = "m=all";
    else if (v == "ppm") own = "s=0;m=all";
    else throw std::invalid_argument(fmt::format("integrator \"{}\" is not bpt, pt, lt, mlt, vcm, bpm or ppm", v));
    if (own) {
      if (p.contains("techniques"))
        throw std::invalid_argument(fmt::format("integrator \"{}\" sets the techniques ({}): for another set use "
                                                "\"bpt\" with \"techniques\"", v, own));
      out.integrator = IntegratorKind::Bpt;
      out.techniques = TechniqueSet::parse(own);
      if (v == "ppm") out.mergeSite = MergeSite::FirstNonSpecular;
    }
  }
  if (p.contains("techniques"))
    out.techniques = TechniqueSet::parse(typed(p, "techniques", &Json::is_string, "a string").get<std::string>());
  if (p.contains("mis")) {
    const std::string v = typed(p, "mis", &Json::is_string, "a string").get<std::string>();
    if (const std::optional<MisHeuristic> h = misHeuristicFromName(v)) out.mis.heuristic = *h;
    else throw std::invalid_argument(fmt::format("mis \"{}\" is not {}", v, kMisHeuristicNames));
  }
  if (p.contains("beta")) {
    out.mis.beta = finiteFloat(typed(p, "beta", &Json::is_number, "a number"), "\"beta\"");
    if (!(out.mis.beta >= 0.01f && out.mis.beta <= 100.f)) throw std::invalid_argument("\"beta\" must be in [0.01, 100]");
  }
  if (p.contains("minConnection")) {
    out.mis.minConnection = finiteFloat(typed(p, "minConnection", &Json::is_number, "a number"), "\"minConnection\"");
    if (!(out.mis.minConnection >= 0.f && out.mis.minConnection <= 1.f))
      throw std::invalid_argument("\"minConnection\" must be in [0, 1]");
  }
  if (p.contains("mediumSampling")) {
    const std::string v = typed(p, "mediumSampling", &Json::is_string, "a string").get<std::string>();
    out.mediumSampling = parseMediumSampling(v);
    if (!out.mediumSampling)
      throw std::invalid_argument(fmt::format("mediumSampling \"{}\" is not distance, equiangular or mis", v));
  }
  if (p.contains("maxLength")) {
    out.maxLength = integerIn(typed(p, "maxLength", &Json::is_number_integer, "an integer"), "\"maxLength\"", 1, 1000);
  }
  out.techniques.checkFits(out.maxLength);  // throws "techniques: ..." on a set that does not fit
  if (p.contains("isolate")) {
    const Json& v = p.at("isolate");
    Isolation iso;
    if (v.is_string()) {
      iso = parseIsolation(v.get<std::string>());
    } else {
      if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer())
        throw std::invalid_argument("\"isolate\" must be [s, t] or \"S,T\" or \"MS,T\" (a merge)");
      iso = Isolation{integerIn(v[0], "\"isolate\" s", 0, out.maxLength),
                      integerIn(v[1], "\"isolate\" t", 1, out.maxLength + 1), false};
    }
    const Technique x = iso.technique();
    if (!x.valid() || x.length() > out.maxLength)
      throw std::invalid_argument(fmt::format("isolated technique {} is not a technique of length {}..{}",
                                              techniqueLabel(x), x.isMerge() ? 2 : 1, out.maxLength));
    if (out.integrator == IntegratorKind::Pt || out.integrator == IntegratorKind::Mlt)
      throw std::invalid_argument("\"isolate\" needs integrator bpt or lt");
    if (out.integrator == IntegratorKind::Lt && x.isMerge())
      throw std::invalid_argument(
          fmt::format("\"isolate\" {}: light tracing has only the t = 1 techniques (a merge needs bpt)", techniqueLabel(x)));
    out.isolate = iso;
  }
  if (p.contains("unweighted")) {
    const bool u = typed(p, "unweighted", &Json::is_boolean, "true or false").get<bool>();
    if (!out.isolate && u) throw std::invalid_argument("\"unweighted\" needs \"isolate\"");
    if (out.isolate) out.isolate->unweighted = u;
  }
  if (p.contains("camera")) {
    const Json& c = p.at("camera");
    if (!c.is_object()) throw std::invalid_argument("\"camera\" must be an object");
    for (const auto& [key, value] : c.items())
      if (key != "eye" && key != "target" && key != "yfovDegrees")
        throw std::invalid_argument(fmt::format("unknown camera key \"{}\"", key));
    if (!c.contains("eye") || !c.contains("target")) throw std::invalid_argument("\"camera\" needs \"eye\" and \"target\"");
    const Vec3 eye = vec3Of(c.at("eye"), "camera eye"), target = vec3Of(c.at("target"), "camera target");
    float yfovDegrees = 39.6f;
    if (c.contains("yfovDegrees")) {
      if (!c.at("yfovDegrees").is_number()) throw std::invalid_argument("camera \"yfovDegrees\" must be a number");
      yfovDegrees = finiteFloat(c.at("yfovDegrees"), "camera \"yfovDegrees\"");
    }
    if (!(yfovDegrees > 0.1f && yfovDegrees < 179.f)) throw std::invalid_argument("camera \"yfovDegrees\" must be in (0.1, 179)");
    const Vec3 d = target - eye;
    if (!(glm::length(d) > 0.f)) throw std::invalid_argument("camera eye and target coincide");
    if (glm::length(glm::cross(glm::normalize(d), Vec3(0.f, 1.f, 0.f))) < 1e-4f)
      throw std::invalid_argument("camera looks straight up or down (the up direction is +y)");
    out.camera = lookAtCamera(eye, target, glm::radians(yfovDegrees));
  }
  if (p.contains("compare")) {
    // Side B of the A/B comparison as a converge CONFIG, checked now (at this preset's length).
    const std::string config = typed(p, "compare", &Json::is_string, "a string").get<std::string>();
    RenderSettings a;
    a.maxLength = out.maxLength;
    compareEstimator(config, a, "\"compare\"");  // throws the parser's line
    out.compare = config;
  }
  // Everything the command line's settings check refuses (e.g. isolating (1,2) under light tracing).
  validateSettings(out.applyTo(RenderSettings{}));
  return out;
}

}  // namespace

CameraDesc lookAtCamera(const Vec3& eye, const Vec3& target, float yfov) {
  const Vec3 f = glm::normalize(target - eye);
  const Vec3 right = glm::normalize(glm::cross(f, Vec3(0.f, 1.f, 0.f)));
  const Vec3 up = glm::cross(right, f);
  CameraDesc d;
  d.cameraToWorld = Mat4(Vec4(right, 0.f), Vec4(up, 0.f), Vec4(-f, 0.f), Vec4(eye, 1.f));
  d.yfov = yfov;
  d.name = "preset";
  return d;
}

RenderSettings NamedPreset::applyTo(const RenderSettings& current) const {
  RenderSettings s = current;
  s.integrator = integrator;
  s.techniques = techniques;
  s.mis = mis;
  s.maxLength = maxLength;
  s.isolate = isolate;
  s.mergeSite = mergeSite;
  s.mediumSampling = mediumSampling;
  if (camera) s.camera = camera;
  return s;
}

std::vector<NamedPreset> parsePresets(const std::string& text, const std::string& path) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line 3, ..."
    // (or out_of_range.406 for a number such as 1e999 that overflows a double).
    std::string what = e.what();
    if (const size_t p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    refuse(path + ": " + what);
  }
  if (!root.is_object() || !root.contains("presets") || !root.at("presets").is_array())
    refuse(path + ": expected an object with an array \"presets\"");
  std::vector<NamedPreset> out;
  std::set<std::string> names;
  size_t index = 0;
  for (const Json& p : root.at("presets")) {
    const std::string label = p.is_object() && p.contains("name") && p.at("name").is_string()
                                  ? fmt::format("preset {} (\"{}\")", index, p.at("name").get<std::string>())
                                  : fmt::format("preset {}", index);
    try {
      out.push_back(parseOne(p));
    } catch (const std::exception& e) {
      refuse(fmt::format("{}: {}: {}", path, label, e.what()));
    }
    if (!names.insert(out.back().name).second) refuse(fmt::format("{}: {}: duplicate name", path, label));
    ++index;
  }
  return out;
}

std::vector<NamedPreset> loadPresets(const std::string& path) {
  std::string text;
  try {
    text = readGuardedText(path, kMaxPresetsBytes);
  } catch (const FileError& e) {
    refuse(path + ": cannot read the presets file: " + e.problem());
  }
  return parsePresets(text, path);
}

const NamedPreset& findPreset(const std::vector<NamedPreset>& presets, const std::string& name, const std::string& path) {
  std::string known;
  for (const NamedPreset& p : presets) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + ("\"" + p.name + "\"");
  }
  refuse(fmt::format("{}: no preset \"{}\" (known: {})", path, name, known.empty() ? "none" : known));
}

}  // namespace pathlab::ui
