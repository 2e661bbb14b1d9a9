// stat and access checks of output paths (no file is created to find out).
#include "app/output_check.h"

#include <fmt/core.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <linux/magic.h>
#include <stdexcept>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

namespace pathlab::app {

namespace {

// Kernel file systems where no ordinary file can be created. access() cannot tell: for root it
// reports /proc and /sys as writable.
const char* pseudoFileSystem(const std::string& dir) {
  struct statfs fs {};
  if (statfs(dir.c_str(), &fs) != 0) return nullptr;
  switch (fs.f_type) {
    case PROC_SUPER_MAGIC: return "proc";
    case SYSFS_MAGIC: return "sysfs";
    case CGROUP_SUPER_MAGIC:
    case CGROUP2_SUPER_MAGIC: return "cgroup";
    case DEVPTS_SUPER_MAGIC: return "devpts";
    case DEBUGFS_MAGIC: return "debugfs";
    case TRACEFS_MAGIC: return "tracefs";
    case SECURITYFS_MAGIC: return "securityfs";
    case BPF_FS_MAGIC: return "bpf";
    default: return nullptr;
  }
}

// `what` names the output in the message; `dir` is where its temporary file would be created.
void checkWritableDirectory(const std::string& what, const std::string& dir) {
  struct stat st {};
  if (stat(dir.c_str(), &st) != 0) {
    if (errno == ENOENT) throw std::runtime_error(fmt::format("{}: the directory {} does not exist", what, dir));
    throw std::runtime_error(fmt::format("{}: the directory {}: {}", what, dir, std::strerror(errno)));
  }
  if (!S_ISDIR(st.st_mode)) throw std::runtime_error(fmt::format("{}: {} is not a directory", what, dir));
  // The effective ids decide, as they will when the file is created.
  if (faccessat(AT_FDCWD, dir.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    throw std::runtime_error(fmt::format("{}: the directory {} is not writable ({})", what, dir, std::strerror(errno)));
  if (const char* fs = pseudoFileSystem(dir))
    throw std::runtime_error(
        fmt::format("{}: the directory {} is on the {} pseudo file system, where no file can be created", what, dir, fs));
}

}  // namespace

void checkOutputWritable(const std::string& path) {
  if (path.empty()) throw std::runtime_error("an output path is empty");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  checkWritableDirectory(path, parent.empty() ? "." : parent.string());
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return;  // absent: it will be created
  if (S_ISDIR(st.st_mode)) throw std::runtime_error(fmt::format("{}: is a directory", path));
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(fmt::format("{}: is not a regular file", path));
}

void refuseExisting(const std::string& path, bool force) {
  if (!force && std::filesystem::exists(path))
    throw std::runtime_error(path + ": file exists (pass --force to overwrite it)");
}

void checkOutputDirectory(const std::string& dir) {
  if (dir.empty()) throw std::runtime_error("an output directory is empty");
  struct stat st {};
  if (stat(dir.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) throw std::runtime_error(fmt::format("{}: exists and is not a directory", dir));
    checkWritableDirectory(dir, dir);
    return;
  }
  std::filesystem::path missing(dir);
  if (!missing.has_filename()) missing = missing.parent_path();  // "out/" is "out"
  const std::filesystem::path parent = missing.parent_path();
  checkWritableDirectory(dir, parent.empty() ? "." : parent.string());
}

}  // namespace pathlab::app
