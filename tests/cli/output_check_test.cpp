// Output paths refused before any work (issue 18, class 4): what cannot be created, refused with
// one line naming the path and the problem; what can, accepted without creating anything.
#include "app/output_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace pathlab::app {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::path(PATHLAB_TEST_TMP) / ("output_check_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string refusal(const std::string& path) {
  try {
    checkOutputWritable(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

void expectRefused(const std::string& path, const std::string& problem) {
  const std::string message = refusal(path);
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "does not start with the path: '" << message << "'";
  EXPECT_NE(message.find(problem), std::string::npos) << "'" << message << "' does not say '" << problem << "'";
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(OutputCheck, RefusesWhatCannotBeCreated) {
  const fs::path dir = scratch();
  expectRefused("/proc/pathlab.png", "pseudo file system");
  expectRefused("/sys/pathlab.exr", "pseudo file system");
  expectRefused(dir.string(), "is a directory");
  expectRefused((dir / "missing" / "x.png").string(), "does not exist");
  std::ofstream((dir / "file").string()) << "x";
  expectRefused((dir / "file" / "x.png").string(), "is not a directory");
  ASSERT_EQ(mkfifo((dir / "fifo.pfm").c_str(), 0600), 0);
  expectRefused((dir / "fifo.pfm").string(), "not a regular file");
  expectRefused("/dev/null", "not a regular file");
  fs::remove_all(dir);
}

TEST(OutputCheck, AcceptsNewAndExistingRegularFiles) {
  const fs::path dir = scratch();
  EXPECT_EQ(refusal((dir / "new.png").string()), "");
  EXPECT_FALSE(fs::exists(dir / "new.png")) << "the check created the file";
  EXPECT_EQ(fs::directory_iterator(dir), fs::directory_iterator()) << "the check left a file behind";
  std::ofstream((dir / "old.png").string()) << "x";
  EXPECT_EQ(refusal((dir / "old.png").string()), "");  // replacing it is --force's business
  fs::remove_all(dir);
}

TEST(OutputCheck, Directories) {
  const fs::path dir = scratch();
  EXPECT_NO_THROW(checkOutputDirectory(dir.string()));
  EXPECT_NO_THROW(checkOutputDirectory((dir / "new").string()));
  EXPECT_NO_THROW(checkOutputDirectory((dir / "new").string() + "/"));
  EXPECT_THROW(checkOutputDirectory((dir / "missing" / "new").string()), std::runtime_error);
  EXPECT_THROW(checkOutputDirectory("/proc/pathlab-results"), std::runtime_error);
  EXPECT_THROW(checkOutputDirectory("/proc"), std::runtime_error);
  std::ofstream((dir / "file").string()) << "x";
  EXPECT_THROW(checkOutputDirectory((dir / "file").string()), std::runtime_error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab::app
