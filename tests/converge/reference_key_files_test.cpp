// The reference key hashes the scene's external files through the guarded reader: a buffer that is
// a FIFO is refused at once (tinygltf's own FileExists and ReadWholeFile would wait for a writer).
#include "core/converge/reference_key.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <sys/stat.h>
#include <thread>

namespace pathlab {
namespace {

TEST(ReferenceKeyFiles, AFifoBufferIsRefusedWithoutBlocking) {
  const std::filesystem::path dir = std::filesystem::path(PATHLAB_TEST_TMP) / "reference_key_fifo";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_EQ(mkfifo((dir / "data.bin").c_str(), 0600), 0);
  const std::string scene = (dir / "scene.gltf").string();
  std::ofstream(scene) << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"data.bin","byteLength":4}]})";
  auto done = std::make_shared<std::promise<std::string>>();
  std::future<std::string> message = done->get_future();
  std::thread([done, scene] {
    try {
      referenceKey(scene, RenderSettings{}, "spp=1");
      done->set_value("");
    } catch (const std::exception& e) {
      done->set_value(e.what());
    }
  }).detach();
  ASSERT_EQ(message.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "blocked on a FIFO";
  const std::string what = message.get();
  EXPECT_EQ(what.rfind(scene + ": cannot read the scene's files", 0), 0u) << what;
  EXPECT_NE(what.find("is a FIFO, not a regular file"), std::string::npos) << what;
}

}  // namespace
}  // namespace pathlab
