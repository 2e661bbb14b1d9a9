// Every byte the loader reads from disk: the scene file and, through tinygltf's file-system
// callbacks, the buffers and images it references. Regular files only, with a size limit.
#include "core/scene/gltf_internal.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pathlab::gltf {
namespace {

std::string fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Opening a FIFO blocks until a writer appears and a device such as /dev/zero never ends, so
// the type is checked before open (stat follows symlinks, as open does).
void checkRegular(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return;
  const std::string kind = fileKind(st.st_mode);
  throw LoadError(kind == "not a regular file" ? "is not a regular file"
                                               : "is " + kind + ", not a regular file");
}

std::string systemError(const char* what) {
  return std::string(what) + " (" + std::strerror(errno) + ")";
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::vector<unsigned char> readRegularFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw LoadError("file not found");
    throw LoadError(systemError("cannot open file"));
  }
  checkRegular(st);
  // O_NONBLOCK: should the path be swapped for a FIFO between stat and open, open returns
  // instead of waiting for a writer; fstat below then refuses it.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw LoadError(systemError("cannot open file"));
  if (::fstat(fd.get(), &st) != 0) throw LoadError(systemError("cannot read file"));
  checkRegular(st);
  if (uint64_t(st.st_size) > kMaxFileBytes) {
    throw LoadError("is " + std::to_string(st.st_size) + " bytes, more than the " +
                    std::to_string(kMaxFileBytes) + " pathlab reads from one file");
  }
  std::vector<unsigned char> bytes(size_t(st.st_size));
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd.get(), bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw LoadError(systemError("cannot read file"));
    if (n == 0) break;  // shrank since fstat: what is there is the file
    got += size_t(n);
  }
  bytes.resize(got);
  return bytes;
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
