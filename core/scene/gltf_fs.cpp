// Every byte the loader reads from disk: the scene file and, through tinygltf's file-system
// callbacks, the buffers and images it references, all through core/io/guarded_file.h.
#include "core/scene/gltf_internal.h"

#include "core/io/guarded_file.h"

#include <sys/stat.h>

namespace pathlab::gltf {

std::vector<unsigned char> readRegularFile(const std::string& path) {
  try {
    return readGuardedFile(path);
  } catch (const FileError& e) {
    throw LoadError(e.problem());
  }
}

ExternalFiles::ExternalFiles(std::string baseDir)
    : baseDir_(baseDir.empty() ? "." : std::move(baseDir)) {}

tinygltf::FsCallbacks ExternalFiles::callbacks() {
  return tinygltf::FsCallbacks{&ExternalFiles::exists, &ExternalFiles::expand,
                               &ExternalFiles::read, &ExternalFiles::write, this};
}

std::string ExternalFiles::relative(const std::string& path) const {
  const std::string prefix = baseDir_.back() == '/' ? baseDir_ : baseDir_ + "/";
  return path.rfind(prefix, 0) == 0 ? path.substr(prefix.size()) : path;
}

// tinygltf looks for a URI under the base directory and then under "." (the working
// directory); a relative URI means the scene's directory, so only candidates under it exist.
// Existence is stat(), never an open: the read refuses what is not a regular file, by name.
bool ExternalFiles::exists(const std::string& path, void* self) {
  const auto& files = *static_cast<const ExternalFiles*>(self);
  const std::string prefix = files.baseDir_.back() == '/' ? files.baseDir_ : files.baseDir_ + "/";
  struct stat st {};
  return path.rfind(prefix, 0) == 0 && ::stat(path.c_str(), &st) == 0;
}

// No expansion: a URI is not a shell word (tinygltf 2.7 dropped wordexp for the same reason).
std::string ExternalFiles::expand(const std::string& path, void*) { return path; }

bool ExternalFiles::read(std::vector<unsigned char>* out, std::string* err,
                         const std::string& path, void* self) {
  auto& files = *static_cast<ExternalFiles*>(self);
  try {
    *out = readRegularFile(path);
    return true;
  } catch (const LoadError& e) {
    files.refusals_.push_back({path, files.relative(path), e.what()});
    if (err) *err += e.what();
    return false;
  }
}

bool ExternalFiles::write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                          void*) {
  if (err) *err += "pathlab's loader writes no files";
  return false;
}

}  // namespace pathlab::gltf
