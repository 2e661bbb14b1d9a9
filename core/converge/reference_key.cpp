// FNV-1a hashing of the reference's inputs.
#include "core/converge/reference_key.h"

#include "core/io/guarded_file.h"

#include <fmt/core.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <sys/stat.h>
#include <string_view>
#include <vector>

namespace pathlab {

namespace {

// FNV-1a, 64-bit (Fowler, Noll, Vo): enough to tell inputs apart, not a security hash.
struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 0x100000001b3ull;
    }
  }
};

// Hashes every external file (buffer or image URI) tinygltf reads while parsing the scene, in the
// order it reads them, through its own file callbacks: the same URI decoding and search paths as
// the loader (core/scene/gltf_file.cpp). Images are read but not decoded. Data URIs and a .glb's
// own binary chunk are part of the scene file's bytes already.
struct ExternalFiles {
  Fnv1a* hash;

  static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self) {
    try {
      *out = readGuardedFile(path);
    } catch (const FileError& e) {
      if (err) *err += e.what();
      return false;
    }
    Fnv1a& h = *static_cast<ExternalFiles*>(self)->hash;
    h.add(fmt::format("\nfile {}\n", out->size()));
    h.add(std::string_view(reinterpret_cast<const char*>(out->data()), out->size()));
    return true;
  }
  // Existence by stat(), never an open: tinygltf::FileExists fopens the path, which waits forever
  // on a FIFO; the read then refuses what is not a regular file.
  static bool exists(const std::string& path, void*) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
  }
  static bool skipImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                                const unsigned char*, int, void*) {
    return true;
  }
};

void hashExternalFiles(const std::string& scenePath, const std::string& bytes, Fnv1a& hash) {
  ExternalFiles files{&hash};
  tinygltf::TinyGLTF context;
  context.SetFsCallbacks({&ExternalFiles::exists, &tinygltf::ExpandFilePath, &ExternalFiles::read,
                          &tinygltf::WriteWholeFile, &files});
  context.SetImageLoader(&ExternalFiles::skipImageDecoding, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string baseDir = std::filesystem::path(scenePath).parent_path().string();
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  bool ok = false;
  try {
    ok = binary ? context.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                               static_cast<unsigned>(bytes.size()), baseDir)
                : context.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                              baseDir);
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (!ok) {
    const std::string reason = err.substr(0, err.find('\n'));
    throw std::runtime_error(scenePath + ": cannot read the scene's files (" + reason + ")");
  }
}

std::string describe(const RenderSettings& s) {
  std::string text = fmt::format(
      "pathlab-reference-1 size={}x{} maxLength={} rr={} seed={} integrator={} techniques={} mis={} beta={} "
      "minConnection={} aperture={} focus={} pyramid={}",
      s.width, s.height, s.maxLength, s.russianRoulette, s.seed, integratorName(s.integrator), s.techniques.toString(),
      misHeuristicName(s.mis.heuristic), s.mis.beta, s.mis.minConnection, s.lens.apertureRadius, s.lens.focusDistance,
      s.pyramidLength);
  // A merge's isolation is marked M, an equiangular technique's E (connections' keys keep their
  // text, so their cached references stay valid). An isolated weighted share depends on whether
  // the equiangular techniques E(1, k) are among the weights: the medium sampling joins the key
  // when it is not distance.
  if (s.isolate) {
    text += fmt::format(" isolate={}{},{},{}",
                        s.isolate->kind == TechniqueKind::Merge         ? "M"
                        : s.isolate->kind == TechniqueKind::Equiangular ? "E"
                                                                        : "",
                        s.isolate->s, s.isolate->t, s.isolate->unweighted);
    if (mediumSampling(s) != MediumSampling::Distance) text += fmt::format(" media={}", mediumSamplingName(mediumSampling(s)));
  }
  // Only when not the default, so the keys of existing caches stay what they were.
  if (s.connect != ConnectStrategy::All) text += fmt::format(" connect={}", connectStrategyName(s.connect));
  if (covers(s.techniques.families(), TechniqueKind::Merge)) {
    text += fmt::format(" radius={} alpha={}", firstMergeRadius(s), s.mergeRadiusAlpha);
    // Only below one, so that the keys of caches made when every vertex was kept stay theirs.
    if (mergeNonCaustic(s) != 1.f) text += fmt::format(" noncaustic={}", mergeNonCaustic(s));
  }
  if (s.mergeSite != MergeSite::Every) text += fmt::format(" mergeSite={}", mergeSiteName(s.mergeSite));
  if (s.camera) {
    text += fmt::format(" yfov={} aspect={} camera=", s.camera->yfov, s.camera->aspectRatio.value_or(0.f));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) text += fmt::format("{},", s.camera->cameraToWorld[c][r]);
  }
  return text;
}

}  // namespace

std::string referenceKey(const std::string& scenePath, const RenderSettings& settings, const std::string& budget) {
  std::string bytes;
  try {
    bytes = readGuardedText(scenePath);
  } catch (const FileError& e) {
    throw std::runtime_error(scenePath + ": cannot read the scene file: " + e.problem());
  }
  Fnv1a hash;
  hash.add(bytes);
  hashExternalFiles(scenePath, bytes, hash);
  hash.add("\n" + describe(settings) + "\n" + budget);
  return fmt::format("{:016x}", hash.h);
}

}  // namespace pathlab
