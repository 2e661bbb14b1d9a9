// libFuzzer target for the glTF loader and scene construction: any byte string, as .gltf text
// or .glb binary, must load or throw SceneError with one line; never crash, hang or leak (run
// under ASan + UBSan, see tests/fuzz/run_fuzz.sh). Every crash found becomes a file in
// tests/scenes/bad/, which the loader and CLI tests replay.
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // tinygltf reads from files (external buffers resolve next to them): one scratch file per
  // process, named by what the bytes look like.
  const bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  static const std::string base = "/tmp/pathlab-fuzz-" + std::to_string(getpid());
  const std::string path = base + (binary ? ".glb" : ".gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    pathlab::Scene scene(pathlab::loadGltf(path));
    (void)scene.triangleCount();
  } catch (const pathlab::SceneError& e) {
    // The one-line promise: a message naming the file, without a newline inside.
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.rfind(path, 0) != 0) __builtin_trap();
  }
  std::remove(path.c_str());
  return 0;
}
