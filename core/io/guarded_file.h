// The one place pathlab reads a file from disk (scenes, buffers, textures, environment maps,
// references, presets, converge configs, shaders): regular files only, never a FIFO or a device,
// and never more than a byte budget. tests/scene/guarded_readers_test.cpp fails on any other reader.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab {

// The most pathlab reads from one file: a GLB cannot be larger (its length field is 32 bits), and
// an external buffer this large already holds more triangles than the default limit admits.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 32;

// "PATH: problem" as what(), and the problem alone for callers that name the file their own way.
class FileError : public std::runtime_error {
 public:
  FileError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem), problem_(problem) {}
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
};

// The whole of `path` if it is a regular file (symlinks followed) of at most `maxBytes`; otherwise
// FileError saying what it is ("is a FIFO, not a regular file", "file not found", "is N bytes, more
// than ..."). Never blocks on a special file: the type is checked before and after a non-blocking open.
std::vector<unsigned char> readGuardedFile(const std::string& path, uint64_t maxBytes = kMaxFileBytes);
std::string readGuardedText(const std::string& path, uint64_t maxBytes = kMaxFileBytes);

}  // namespace pathlab
