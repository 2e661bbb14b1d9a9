// OpenVDB's reader and writer, behind vdb_file.h (the only file that includes OpenVDB: its
// headers cost about 15 s of compile time each).
#include "core/io/vdb_file.h"

#include "core/io/guarded_file.h"

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>
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
  auto text = [&] { take(u32()); };
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
      if (version >= 216) text();  // instance parent
      const int64_t gridPos = i64(), blockPos = i64(), endPos = i64();
      if (!(gridPos >= 0 && gridPos <= blockPos && blockPos <= endPos && endPos <= int64_t(b.size())))
        return "grid " + std::to_string(i) + " lies outside the file (truncated?)";
      at = size_t(endPos);
    }
  } catch (const std::string& problem) {
    return problem;
  }
  return "";
}

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
    std::istringstream in(std::string(bytes.begin(), bytes.end()), std::ios::binary);
    // A read past the end throws at once: OpenVDB does not check its reads, and a truncated file
    // otherwise hands it uninitialised lengths (a cut file took 70 s and 11 GB before failing).
    in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
    openvdb::io::Stream stream(in);
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
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out.indexToWorld[i][j] = static_cast<float>(m(i, j));
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) return out;  // no active voxel: a medium with nothing in it
  const openvdb::Coord dim = box.dim();
  const double voxels = double(dim.x()) * double(dim.y()) * double(dim.z());
  if (voxels > double(kMaxDensityVoxels))
    throw VdbError(label + " spans " + std::to_string(dim.x()) + " x " + std::to_string(dim.y()) + " x " +
                   std::to_string(dim.z()) + " voxels, more than pathlab densifies (" +
                   std::to_string(kMaxDensityVoxels) + ")");
  DensityGrid& g = out.grid;
  g.origin = glm::ivec3(box.min().x(), box.min().y(), box.min().z());
  g.size = glm::ivec3(dim.x(), dim.y(), dim.z());
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
          g.values[(size_t(z - g.origin.z) * size_t(g.size.y) + size_t(y - g.origin.y)) * size_t(g.size.x) +
                   size_t(x - g.origin.x)] = float(v);
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

std::vector<std::string> vdbGridNames(const std::string& path) {
  std::vector<std::string> out;
  const openvdb::GridPtrVecPtr grids = readGrids(path);  // held: *readGrids() would dangle in the loop
  for (const auto& g : *grids) out.push_back(g->getName());
  return out;
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
