// OpenVDB's reader and writer, behind vdb_file.h (the only file that includes OpenVDB: its
// headers cost about 15 s of compile time each).
#include "core/io/vdb_file.h"

#include "core/io/guarded_file.h"

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <streambuf>
#include <unistd.h>

namespace pathlab {

namespace {

void initializeOnce() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The file's layout checked before OpenVDB reads it: OpenVDB trusts every length and offset it
// reads, so a truncated or damaged file makes it allocate what garbage says (a file cut in half
// took 18 s and 4 GB before failing). Walked here with bounds: the header (OpenVDB
// io/Archive.cc, readHeader), the file's metadata (MetaMap::readMeta) and the grid descriptors
// (GridDescriptor::read), whose offsets must lie in the file in order. Returns the problem, or "".
std::string layoutProblem(const std::vector<unsigned char>& b) {
  size_t at = 0;
  auto take = [&](size_t n) {
    if (n > b.size() - at) throw std::string("ends early (truncated?)");
    const size_t start = at;
    at += n;
    return start;
  };
  auto u32 = [&] {
    uint32_t v;
    std::memcpy(&v, &b[take(4)], 4);
    return v;
  };
  auto i64 = [&] {
    int64_t v;
    std::memcpy(&v, &b[take(8)], 8);
    return v;
  };
  auto text = [&] {
    const uint32_t n = u32();
    take(n);
    return n;
  };
  try {
    if (i64() != 0x56444220) return "no VDB magic number";
    const uint32_t version = u32();
    if (version < 213) return "OpenVDB file version " + std::to_string(version) + " is older than pathlab reads (213)";
    take(8);  // library major and minor version
    const bool offsets = b[take(1)] != 0;
    if (version >= 220 && version < 222) take(1);  // whole-file compression flag
    take(version >= 218 ? 36 : 16);                // uuid: ASCII from 218, bytes before
    const uint32_t metadata = u32();
    for (uint32_t i = 0; i < metadata; ++i) {
      text();  // name
      text();  // type
      take(u32());  // value
    }
    if (!offsets) return "";  // written as a stream: no descriptors to check
    const uint32_t grids = u32();
    if (grids > b.size()) return "claims " + std::to_string(grids) + " grids";
    for (uint32_t i = 0; i < grids; ++i) {
      text();  // unique name
      text();  // type
      const bool instance = version >= 216 && text() > 0;  // instance parent: shares its tree
      const int64_t gridPos = i64(), blockPos = i64(), endPos = i64();
      // An instance has no tree block of its own (OpenVDB leaves blockPos 0).
      const bool blockInside = instance ? blockPos == 0 || (gridPos <= blockPos && blockPos <= endPos)
                                        : gridPos <= blockPos && blockPos <= endPos;
      if (!(gridPos >= int64_t(at) && blockInside && gridPos <= endPos && endPos <= int64_t(b.size())))
        return "grid " + std::to_string(i) + " lies outside the file (truncated?)";
      at = size_t(endPos);
    }
  } catch (const std::string& problem) {
    return problem;
  }
  return "";
}

// The file's bytes as a read-only stream buffer, without a copy.
class BytesBuffer : public std::streambuf {
 public:
  explicit BytesBuffer(std::vector<unsigned char>& bytes) {
    char* begin = reinterpret_cast<char*>(bytes.data());
    setg(begin, begin, begin + bytes.size());
  }

 protected:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : egptr() - eback();
    return seekpos(pos_type(base + off), std::ios_base::in);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override {
    if (off_type(pos) < 0 || off_type(pos) > egptr() - eback()) return pos_type(off_type(-1));
    setg(eback(), eback() + off_type(pos), egptr());
    return pos;
  }
};

openvdb::GridPtrVecPtr readGrids(const std::string& path) {
  std::vector<unsigned char> bytes;
  try {
    bytes = readGuardedFile(path);
  } catch (const FileError& e) {
    throw VdbError(e.what());
  }
  if (const std::string problem = layoutProblem(bytes); !problem.empty())
    throw VdbError(path + ": not a readable OpenVDB file (" + problem + ")");
  initializeOnce();
  try {
    BytesBuffer buffer(bytes);
    std::istream in(&buffer);
    // A read past the end throws at once: OpenVDB does not check its reads.
    in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
    // delayLoad off: read the grids from the stream now (on, OpenVDB copies the stream into a
    // temporary file to map it).
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    return stream.getGrids();
  } catch (const std::exception& e) {
    throw VdbError(path + ": not a readable OpenVDB file (" + e.what() + ")");
  }
}

std::string names(const openvdb::GridPtrVec& grids) {
  std::string list;
  for (const auto& g : grids) list += (list.empty() ? "'" : ", '") + g->getName() + "'";
  return list.empty() ? "none" : list;
}

template <class GridT>
VdbDensity densify(const std::string& path, const GridT& grid, float scale) {
  const std::string label = path + ": grid '" + grid.getName() + "'";
  if (!grid.transform().isLinear()) throw VdbError(label + " has a non-linear (frustum) transform; pathlab reads affine ones");
  if (grid.background() != 0) {
    std::ostringstream s;
    s << grid.background();
    throw VdbError(label + " has background " + s.str() + "; a density grid must be 0 outside its active voxels");
  }
  VdbDensity out;
  const openvdb::Mat4d m = grid.transform().baseMap()->getAffineMap()->getMat4();
  // OpenVDB maps row vectors (p' = p M, translation in row 3); glm column vectors with the
  // translation in column 3: the same numbers, m[i][j] = M(i, j).
  glm::dmat4 indexToWorld(1.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) indexToWorld[i][j] = m(i, j);
  out.indexToWorld = Mat4(indexToWorld);
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) return out;  // no active voxel: a medium with nothing in it
  // Index coordinates beyond 2^24 have no sub-voxel precision in float, and spans beyond 2^31
  // overflow OpenVDB's Int32 dimensions.
  constexpr int64_t kMaxCoordinate = int64_t(1) << 24;
  for (int a = 0; a < 3; ++a)
    if (std::abs(int64_t(box.min()[a])) > kMaxCoordinate || std::abs(int64_t(box.max()[a])) > kMaxCoordinate)
      throw VdbError(label + " has active voxels beyond index " + std::to_string(kMaxCoordinate) + " from the origin");
  const int64_t dx = int64_t(box.max().x()) - box.min().x() + 1, dy = int64_t(box.max().y()) - box.min().y() + 1,
                dz = int64_t(box.max().z()) - box.min().z() + 1;
  if (double(dx) * double(dy) * double(dz) > double(kMaxDensityVoxels))
    throw VdbError(label + " spans " + std::to_string(dx) + " x " + std::to_string(dy) + " x " + std::to_string(dz) +
                   " voxels, more than pathlab densifies (" + std::to_string(kMaxDensityVoxels) + ")");
  DensityGrid& g = out.grid;
  // The stored block starts at index 0: its first voxel's index is folded into the transform
  // (composed in double), so that index-space positions stay small and precise in float.
  const openvdb::Coord first = box.min();
  g.origin = glm::ivec3(0);
  g.size = glm::ivec3(int(dx), int(dy), int(dz));
  g.values.assign(g.voxelCount(), 0.f);
  size_t nan = 0, negative = 0, huge = 0;
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    const double v = double(*it) * double(scale);
    const openvdb::CoordBBox b = it.getBoundingBox();  // a voxel, or a tile of many
    if (std::isnan(v)) ++nan;
    else if (v < 0.0) ++negative;
    else if (!(v <= double(kMaxDensityValue))) ++huge;
    if (!(v >= 0.0 && v <= double(kMaxDensityValue))) continue;
    for (int z = b.min().z(); z <= b.max().z(); ++z)
      for (int y = b.min().y(); y <= b.max().y(); ++y)
        for (int x = b.min().x(); x <= b.max().x(); ++x)
          g.values[(size_t(z - first.z()) * size_t(g.size.y) + size_t(y - first.y())) * size_t(g.size.x) +
                   size_t(x - first.x())] = float(v);
  }
  auto refuse = [&](size_t n, const char* what) {
    if (n > 0)
      throw VdbError(label + " has " + std::to_string(n) + " " + what + " value" + (n > 1 ? "s" : "") +
                     (scale != 1.f ? " (after densityScale)" : ""));
  };
  refuse(nan, "NaN");
  refuse(negative, "negative");
  std::ostringstream limit;
  limit << "huge (above " << kMaxDensityValue << ")";
  refuse(huge, limit.str().c_str());
  out.indexToWorld = Mat4(indexToWorld * glm::translate(glm::dmat4(1.0), glm::dvec3(first.x(), first.y(), first.z())));
  return out;
}

}  // namespace

VdbDensity readDensityVdb(const std::string& path, const std::string& gridName, float scale) {
  const openvdb::GridPtrVecPtr grids = readGrids(path);
  for (const openvdb::GridBase::Ptr& base : *grids) {
    if (base->getName() != gridName) continue;
    if (const auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) return densify(path, *f, scale);
    if (const auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(base)) return densify(path, *d, scale);
    throw VdbError(path + ": grid '" + gridName + "' holds " + base->valueType() + " values; a density grid holds float");
  }
  throw VdbError(path + ": no grid named '" + gridName + "' (the file has " + names(*grids) + ")");
}

void writeDensityVdb(const std::string& path, const std::string& gridName, const DensityGrid& grid, float voxelSize,
                     const Vec3& origin) {
  initializeOnce();
  openvdb::FloatGrid::Ptr out = openvdb::FloatGrid::create(0.f);
  out->setName(gridName);
  out->setGridClass(openvdb::GRID_FOG_VOLUME);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(double(voxelSize));
  xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
  out->setTransform(xform);
  auto acc = out->getAccessor();
  for (int k = 0; k < grid.size.z; ++k)
    for (int j = 0; j < grid.size.y; ++j)
      for (int i = 0; i < grid.size.x; ++i)
        if (const float v = grid.voxel(i, j, k); v != 0.f)
          acc.setValue(openvdb::Coord(grid.origin.x + i, grid.origin.y + j, grid.origin.z + k), v);
  const std::filesystem::path target(path);
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const std::filesystem::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()));
  try {
    openvdb::io::File file(tmp.string());
    file.write({out});
    file.close();
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw VdbError(path + ": cannot write (" + e.what() + ")");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw VdbError(path + ": cannot write (" + ec.message() + ")");
  }
}

}  // namespace pathlab
