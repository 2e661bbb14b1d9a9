// What the viewer's end-to-end tests share: running the pathlab binary as a child process with its
// standard error captured, and reading the PNG screenshots it writes.
#pragma once

#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pathlab::test {

struct CommandRun {
  int exitCode = -1;
  std::string err;
};

// `pathlab ARGS` with no standard input; its standard error goes through a file in `dir`, one per
// test process (CTest runs the tests of a binary in parallel). `prefix` goes before the command in
// the shell line: "cd DIR &&" or "PATH=... " for tests of the working directory or $PATH.
inline CommandRun runPathlab(const std::string& dir, const std::string& args, const std::string& prefix = "") {
  std::filesystem::create_directories(dir);
  const std::string errFile = std::filesystem::absolute(dir + "/stderr-" + std::to_string(getpid()) + ".txt").string();
  const std::string command = prefix + " " + std::string(PATHLAB_BINARY) + " " + args + " 2>" + errFile + " </dev/null";
  const int status = std::system(command.c_str());
  std::ifstream in(errFile);
  std::stringstream err;
  err << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), err.str()};
}

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;

  size_t index(int x, int y, int c) const {
    return 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) + static_cast<size_t>(c);
  }
  // Mean absolute difference of two equally sized regions, per channel value in [0,255].
  double meanDifference(const Png& o, int x0, int y0, int x1, int y1) const {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c)
          sum += std::abs(static_cast<int>(rgb[index(x, y, c)]) - static_cast<int>(o.rgb[index(x, y, c)]));
    return sum / (3.0 * (x1 - x0) * (y1 - y0));
  }
  // Variance of the green channel over a region.
  double variance(int x0, int y0, int x1, int y1) const {
    double s = 0.0, s2 = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const double v = rgb[index(x, y, 1)];
        s += v;
        s2 += v * v;
      }
    const double n = static_cast<double>(x1 - x0) * (y1 - y0);
    return s2 / n - (s / n) * (s / n);
  }
};

// Empty (0 x 0) when the file cannot be read.
inline Png readPng(const std::string& path) {
  Png png;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 3);
  if (!data) return png;
  png.rgb.assign(data, data + static_cast<size_t>(png.width) * static_cast<size_t>(png.height) * 3);
  stbi_image_free(data);
  return png;
}

}  // namespace pathlab::test
