// Tests of the one guarded reader (core/io/guarded_file.h): special files refused at once without
// blocking, the byte budget, and a scan of the sources that fails on any file reader outside it.
#include "core/io/guarded_file.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <thread>

namespace pathlab {
namespace {

namespace fs = std::filesystem;

fs::path guardedPath(const std::string& name) {
  const fs::path dir = fs::path(PATHLAB_TEST_TMP) / "guarded_file";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

std::string guardRefusal(const std::string& path, uint64_t maxBytes = kMaxFileBytes) {
  try {
    readGuardedFile(path, maxBytes);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

TEST(GuardedFile, ReadsARegularFileWhole) {
  const fs::path p = guardedPath("plain.txt");
  std::ofstream(p) << "hello";
  EXPECT_EQ(readGuardedText(p.string()), "hello");
}

// A thread blocked in open() on a FIFO cannot be stopped: the read runs detached, and a hang fails
// the test at the deadline (the process then exits with the thread still blocked).
TEST(GuardedFile, RefusesAFifoWithoutBlocking) {
  const fs::path p = guardedPath("fifo");
  ASSERT_EQ(mkfifo(p.c_str(), 0600), 0);
  auto promise = std::make_shared<std::promise<std::string>>();
  std::future<std::string> message = promise->get_future();
  std::thread([promise, path = p.string()] { promise->set_value(guardRefusal(path)); }).detach();
  ASSERT_EQ(message.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "the read blocked on a FIFO";
  EXPECT_EQ(message.get(), p.string() + ": is a FIFO, not a regular file");
}

TEST(GuardedFile, RefusesDirectoriesDevicesMissingAndOversizedFiles) {
  const fs::path dir = guardedPath("dir");
  fs::create_directory(dir);
  EXPECT_EQ(guardRefusal(dir.string()), dir.string() + ": is a directory, not a regular file");
  EXPECT_EQ(guardRefusal("/dev/zero"), "/dev/zero: is a character device, not a regular file");
  EXPECT_EQ(guardRefusal(guardedPath("missing").string()), guardedPath("missing").string() + ": file not found");
  const fs::path big = guardedPath("big.txt");
  std::ofstream(big) << std::string(100, 'x');
  EXPECT_NE(guardRefusal(big.string(), 99).find("is 100 bytes, more than the 99"), std::string::npos);
  EXPECT_EQ(guardRefusal(big.string(), 100), "");
}

// Every way the sources open a file by name, outside core/io/guarded_file.cpp. A new reader must
// go through readGuardedFile or be listed here with the reason it cannot.
TEST(GuardedFile, EveryReaderInTheSourcesIsGuarded) {
  const std::regex opener(
      R"(std::ifstream|std::fstream|\bfopen\s*\(|\bstbi_loadf?(_16)?\s*\(|\bstbi_info\s*\(|\bLoadEXR\s*\(|)"
      R"(LoadEXR[A-Za-z]*FromFile|ParseEXR[A-Za-z]*FromFile|ReadWholeFile|FileExists|Load(ASCII|Binary)FromFile|(^|[^:\w])::open\s*\()");
  const std::set<std::string> allowed = {
      "core/io/guarded_file.cpp",     // the guarded reader itself
      "ui/lane/thread_priority.cpp",  // /proc/self/task/*/comm: procfs reports size 0, and it is no user input
  };
  std::vector<std::string> unguarded;
  size_t scanned = 0;
  for (const char* top : {"core", "app", "ui"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(PATHLAB_SOURCE_DIR) / top)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      const std::string rel = fs::relative(entry.path(), PATHLAB_SOURCE_DIR).string();
      ++scanned;
      if (allowed.count(rel)) continue;
      std::ifstream in(entry.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n) {
        const std::string code = line.substr(0, line.find("//"));
        if (std::regex_search(code, opener)) unguarded.push_back(rel + ":" + std::to_string(n) + ": " + line);
      }
    }
  }
  EXPECT_GT(scanned, 100u);
  std::string list;
  for (const std::string& u : unguarded) list += "\n  " + u;
  EXPECT_TRUE(unguarded.empty()) << "files opened outside core/io/guarded_file.h:" << list;
}

}  // namespace
}  // namespace pathlab
