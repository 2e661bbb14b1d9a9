// OpenVDB density grids (issue 35): a written grid reads back voxel for voxel with its transform;
// the bundled smoke.vdb is what `pathlab make-volume smoke` writes; and every bad grid is one
// line naming the file and the problem (missing, corrupt, no such grid, another value type, a
// non-zero background, NaN, negative or huge densities), as is every bad reference to one from a
// glTF material (PATHLAB_materials_volume_grid).
#include "core/io/vdb_file.h"
#include "core/media/procedural_volumes.h"
#include "core/media/volume_grid.h"
#include "core/scene/gltf_loader.h"

#include <openvdb/openvdb.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace pathlab {
namespace {

namespace fs = std::filesystem;

class VdbFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pathlab-vdb-test-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // The message readDensityVdb throws, or "" when it reads.
  static std::string readError(const std::string& file, const std::string& grid = "density") {
    try {
      readDensityVdb(file, grid);
    } catch (const VdbError& e) {
      return e.what();
    }
    return "";
  }
  void writeGrid(const std::string& file, const openvdb::GridBase::Ptr& grid) {
    openvdb::initialize();
    openvdb::io::File f(file);
    f.write({grid});
    f.close();
  }
  fs::path dir_;
};

TEST_F(VdbFile, WrittenGridReadsBackWithItsTransform) {
  DensityGrid g;
  g.origin = glm::ivec3(-2, 0, 3);
  g.size = glm::ivec3(5, 4, 3);
  g.values.resize(g.voxelCount());
  for (size_t i = 0; i < g.values.size(); ++i) g.values[i] = (i % 7 == 0) ? 0.f : 0.25f * float(i);
  writeDensityVdb(path("g.vdb"), "density", g, 0.5f, Vec3(1.f, 2.f, 3.f));
  VdbDensity r = readDensityVdb(path("g.vdb"), "density", 2.f);
  // The reader stores the active block from index 0 and folds its first voxel into the
  // transform: compare in world space, where written voxel (i, j, k) of index g.origin + (i, j, k)
  // lies at (1, 2, 3) + 0.5 (g.origin + (i, j, k)).
  const VolumeGrid read(std::move(r.grid), r.indexToWorld);
  for (int k = 0; k < g.size.z; ++k)
    for (int j = 0; j < g.size.y; ++j)
      for (int i = 0; i < g.size.x; ++i) {
        const Vec3 world = Vec3(1.f, 2.f, 3.f) + 0.5f * Vec3(g.origin + glm::ivec3(i, j, k));
        EXPECT_NEAR(read.densityAt(world), 2.f * g.voxel(i, j, k), 1e-4f) << i << j << k;
      }
}

TEST_F(VdbFile, BundledSmokeIsWhatMakeVolumeWrites) {
  VdbDensity r = readDensityVdb(std::string(PATHLAB_SOURCE_DIR) + "/assets/smoke.vdb", "density");
  ASSERT_GT(r.grid.voxelCount(), 0u);
  const VolumeGrid read(std::move(r.grid), r.indexToWorld);
  const DensityGrid made = makeProceduralVolume(ProceduralVolume::Smoke, 64);
  size_t nonZero = 0;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const Vec3 world = proceduralOrigin(64) + proceduralVoxelSize(64) * Vec3(float(i), float(j), float(k));
        ASSERT_NEAR(read.densityAt(world), made.voxel(i, j, k), 1e-5f) << i << " " << j << " " << k;
        nonZero += made.voxel(i, j, k) > 0.f;
      }
  EXPECT_GT(nonZero, 10000u);
}

TEST_F(VdbFile, MissingOrCorruptFilesAreOneLine) {
  EXPECT_NE(readError(path("none.vdb")).find("none.vdb: file not found"), std::string::npos) << readError(path("none.vdb"));
  std::ofstream(path("junk.vdb")) << "this is not an OpenVDB file";
  EXPECT_NE(readError(path("junk.vdb")).find("junk.vdb: not a readable OpenVDB file"), std::string::npos);
  // A real file cut in half.
  writeDensityVdb(path("whole.vdb"), "density", makeProceduralVolume(ProceduralVolume::Smoke, 16), 1.f, Vec3(0.f));
  std::ifstream in(path("whole.vdb"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(path("cut.vdb"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  // Refused by pathlab's own layout check, before OpenVDB reads lengths past the end.
  const std::string cut = readError(path("cut.vdb"));
  EXPECT_NE(cut.find("cut.vdb: not a readable OpenVDB file (grid 0 lies outside the file (truncated?))"),
            std::string::npos)
      << cut;
  for (const std::string& m : {readError(path("junk.vdb")), cut}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST_F(VdbFile, RefusesGridsItCannotRenderByName) {
  writeDensityVdb(path("g.vdb"), "smoke", makeProceduralVolume(ProceduralVolume::Smoke, 8), 1.f, Vec3(0.f));
  EXPECT_NE(readError(path("g.vdb")).find("g.vdb: no grid named 'density' (the file has 'smoke')"), std::string::npos)
      << readError(path("g.vdb"));
  DensityGrid bad = makeProceduralVolume(ProceduralVolume::Constant, 4, 1.f);
  bad.values[3] = std::nanf("");
  bad.values[5] = -1.f;
  bad.values[6] = -2.f;
  bad.values[7] = 1e9f;
  writeDensityVdb(path("bad.vdb"), "density", bad, 1.f, Vec3(0.f));
  EXPECT_NE(readError(path("bad.vdb")).find("bad.vdb: grid 'density' has 1 NaN value"), std::string::npos)
      << readError(path("bad.vdb"));
  bad.values[3] = 0.5f;
  writeDensityVdb(path("bad.vdb"), "density", bad, 1.f, Vec3(0.f));
  EXPECT_NE(readError(path("bad.vdb")).find("has 2 negative values"), std::string::npos) << readError(path("bad.vdb"));
  bad.values[5] = bad.values[6] = 0.5f;
  writeDensityVdb(path("bad.vdb"), "density", bad, 1.f, Vec3(0.f));
  EXPECT_NE(readError(path("bad.vdb")).find("has 1 huge (above 1e+06) value"), std::string::npos) << readError(path("bad.vdb"));
  // A scale that makes sane densities huge says so.
  try {
    readDensityVdb(path("g.vdb"), "smoke", 1e7f);
    ADD_FAILURE() << "a densityScale of 1e7 read";
  } catch (const VdbError& e) {
    EXPECT_NE(std::string(e.what()).find("(after densityScale)"), std::string::npos) << e.what();
  }

  openvdb::initialize();
  openvdb::Vec3SGrid::Ptr vectors = openvdb::Vec3SGrid::create();
  vectors->setName("density");
  vectors->getAccessor().setValue(openvdb::Coord(0), openvdb::Vec3s(1.f));
  writeGrid(path("vec.vdb"), vectors);
  EXPECT_NE(readError(path("vec.vdb")).find("grid 'density' holds vec3s values; a density grid holds float"),
            std::string::npos)
      << readError(path("vec.vdb"));
  openvdb::FloatGrid::Ptr background = openvdb::FloatGrid::create(0.5f);
  background->setName("density");
  background->getAccessor().setValue(openvdb::Coord(0), 1.f);
  writeGrid(path("bg.vdb"), background);
  EXPECT_NE(readError(path("bg.vdb")).find("has background 0.5; a density grid must be 0 outside"), std::string::npos)
      << readError(path("bg.vdb"));
}

// A file whose second grid is an instance of the first (OpenVDB shares the tree and writes no
// block for the instance), and grids far from the index origin.
TEST_F(VdbFile, InstancedGridsReadAndFarGridsAreRefused) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr a = openvdb::FloatGrid::create(0.f);
  a->setName("density");
  a->getAccessor().setValue(openvdb::Coord(1, 2, 3), 0.75f);
  openvdb::GridBase::Ptr b = a->copyGrid();  // shares a's tree: written as an instance
  b->setName("copy");
  {
    openvdb::io::File f(path("instanced.vdb"));
    f.write({a, b});
    f.close();
  }
  EXPECT_EQ(readError(path("instanced.vdb"), "copy"), "");
  EXPECT_FLOAT_EQ(readDensityVdb(path("instanced.vdb"), "copy").grid.maxValue(), 0.75f);
  DensityGrid far = makeProceduralVolume(ProceduralVolume::Constant, 2);
  far.origin = glm::ivec3(1 << 25, 0, 0);
  writeDensityVdb(path("far.vdb"), "density", far, 1.f, Vec3(0.f));
  EXPECT_NE(readError(path("far.vdb")).find("has active voxels beyond index 16777216 from the origin"), std::string::npos)
      << readError(path("far.vdb"));
}

// The glTF side: a scene whose material names a missing .vdb, or another grid, fails to load
// with one line naming the scene, the material and the .vdb.
TEST_F(VdbFile, SceneReferencesToBadGridsAreOneLine) {
  const fs::path source = fs::path(PATHLAB_SOURCE_DIR) / "tests/scenes/grid-fog-constant.gltf";
  fs::copy_file(source, dir_ / "fog.gltf");
  auto loadError = [&] {
    try {
      loadGltf(path("fog.gltf"));
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string missing = loadError();
  EXPECT_NE(missing.find("fog.gltf: material"), std::string::npos) << missing;
  EXPECT_NE(missing.find("PATHLAB_materials_volume_grid: " + path("constant.vdb") + ": file not found"), std::string::npos)
      << missing;
  writeDensityVdb(path("constant.vdb"), "other", makeProceduralVolume(ProceduralVolume::Constant, 4), 0.25f, Vec3(0.f));
  EXPECT_NE(loadError().find("no grid named 'density'"), std::string::npos) << loadError();
  writeDensityVdb(path("constant.vdb"), "density", makeProceduralVolume(ProceduralVolume::Constant, 4), 0.25f, Vec3(0.f));
  EXPECT_EQ(loadError(), "");
  // densityScale out of range, and a uri that is not a file.
  std::ifstream in(source);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto withReplaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) t.replace(at, from.size(), to);
    std::ofstream(path("fog.gltf")) << t;
  };
  withReplaced("\"densityScale\": 1.0", "\"densityScale\": -2.0");
  EXPECT_NE(loadError().find("densityScale -2 is outside [0, 1e6]"), std::string::npos) << loadError();
  withReplaced("\"uri\": \"constant.vdb\"", "\"uri\": \"data:application/octet-stream;base64,AAAA\"");
  EXPECT_NE(loadError().find("uri must name a .vdb file, not a data URI"), std::string::npos) << loadError();
  withReplaced("\"uri\": \"constant.vdb\"", "\"uri\": 3");
  EXPECT_NE(loadError().find("uri is not a non-empty string"), std::string::npos) << loadError();
}

}  // namespace
}  // namespace pathlab
