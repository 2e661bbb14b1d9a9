// Writing a text file through a temporary and a rename.
#include "core/io/text_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace pathlab {

void writeTextAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(tmp + ": cannot write");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace pathlab
