// Reading a whole regular file with the type and size checked before a byte is read (guarded_file.h).
#include "core/io/guarded_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pathlab {
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
void checkRegular(const std::string& path, const struct stat& st) {
  if (S_ISREG(st.st_mode)) return;
  const std::string kind = fileKind(st.st_mode);
  throw FileError(path, kind == "not a regular file" ? "is not a regular file" : "is " + kind + ", not a regular file");
}

std::string systemError(const char* what) { return std::string(what) + " (" + std::strerror(errno) + ")"; }

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

std::vector<unsigned char> readGuardedFile(const std::string& path, uint64_t maxBytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw FileError(path, "file not found");
    throw FileError(path, systemError("cannot open file"));
  }
  checkRegular(path, st);
  // O_NONBLOCK: should the path be swapped for a FIFO between stat and open, open returns
  // instead of waiting for a writer; fstat below then refuses it.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw FileError(path, systemError("cannot open file"));
  if (::fstat(fd.get(), &st) != 0) throw FileError(path, systemError("cannot read file"));
  checkRegular(path, st);
  if (uint64_t(st.st_size) > maxBytes) {
    throw FileError(path, "is " + std::to_string(st.st_size) + " bytes, more than the " + std::to_string(maxBytes) +
                              " pathlab reads from this file");
  }
  std::vector<unsigned char> bytes(size_t(st.st_size));
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd.get(), bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileError(path, systemError("cannot read file"));
    if (n == 0) break;  // shrank since fstat: what is there is the file
    got += size_t(n);
  }
  bytes.resize(got);
  return bytes;
}

std::string readGuardedText(const std::string& path, uint64_t maxBytes) {
  const std::vector<unsigned char> bytes = readGuardedFile(path, maxBytes);
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace pathlab
