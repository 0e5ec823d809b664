// VDB writer and reader: one dense FloatGrid per channel (layout in vdb.hpp).
// The only translation unit of src/ that includes OpenVDB (its headers cost
// 4-12 s per file; docs/architecture.md "Build").
#include "io/vdb.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "core/error.hpp"
#include "core/hash.hpp"

namespace skybake {

namespace {

const std::string kPrefix = "skybake:";
using DenseXYZ = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;

// The header written by io::Archive::writeHeader: magic (8 bytes), file
// format version (4), library major and minor versions (4 + 4), the
// "has grid offsets" flag (1), then the UUID as 36 ASCII characters.
constexpr size_t kUuidOffset = 21;
constexpr size_t kUuidLength = 36;

void init_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

void check_writable(const std::string& path, const Texture& tex, double voxel_size) {
  if (tex.width < 1 || tex.height < 1 || tex.depth < 1 || tex.channels.empty())
    throw IoError(fmt::format("{}: expected a non-empty texture, got {} with {} channels", path,
                              tex.shape_string(), tex.channels.size()));
  if (tex.is_array())
    throw IoError(fmt::format("{}: expected a 2D texture or a volume, got a 2D array ({})", path,
                              tex.shape_string()));
  if (tex.data.size() != tex.texel_count() * tex.channels.size())
    throw Error(fmt::format("{}: expected {} floats for {}, got {}", path,
                            tex.texel_count() * tex.channels.size(), tex.shape_string(),
                            tex.data.size()));
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size))
    throw Error(fmt::format("{}: expected a positive voxel size, got {}", path, voxel_size));
  const std::string names = fmt::format("{}", fmt::join(tex.channels, ","));
  if (std::set<std::string>(tex.channels.begin(), tex.channels.end()).size() !=
          tex.channels.size() ||
      std::count(names.begin(), names.end(), ',') + 1 != tex.channel_count())
    throw IoError(
        fmt::format("{}: expected distinct channel names without commas (VDB grid names), got {}",
                    path, names));
  for (const char* key : {"shape", "channels"})
    if (tex.metadata.count(key))
      throw Error(fmt::format("{}: expected a metadata key other than the reserved '{}{}'", path,
                              kPrefix, key));
  check_finite(tex, path);
}

// One channel as a grid whose every voxel in the texture's box is active.
openvdb::FloatGrid::Ptr make_grid(const Texture& tex, int c,
                                  const openvdb::math::Transform& xform) {
  const size_t nc = tex.channels.size(), texels = tex.texel_count();
  std::vector<float> plane(texels);
  for (size_t t = 0; t < texels; ++t) plane[t] = tex.data[t * nc + c];
  const openvdb::CoordBBox box(openvdb::Coord(0),
                               openvdb::Coord(tex.width - 1, tex.height - 1, tex.depth - 1));
  auto grid = openvdb::FloatGrid::create(0.0f);
  openvdb::tools::copyFromDense(DenseXYZ(box, plane.data()), *grid, 0.0f);
  // copyFromDense leaves voxels equal to the background inactive; the union
  // with an all-active box activates them without changing any value, so the
  // grid is dense (vdb.hpp: every voxel of the domain is active) and viewers
  // see the whole domain.
  openvdb::MaskTree box_mask;
  box_mask.fill(box, true, true);
  grid->tree().topologyUnion(box_mask);
  grid->setName(tex.channels[c]);
  grid->setTransform(xform.copy());
  for (const auto& [key, value] : tex.metadata)
    grid->insertMeta(kPrefix + key, openvdb::StringMetadata(value));
  grid->insertMeta(kPrefix + "shape",
                   openvdb::StringMetadata(
                       fmt::format("{}x{}x{}x{}", tex.width, tex.height, tex.depth, tex.layers)));
  grid->insertMeta(kPrefix + "channels",
                   openvdb::StringMetadata(fmt::format("{}", fmt::join(tex.channels, ","))));
  return grid;
}

// Replaces the random UUID OpenVDB wrote with one derived from the file's
// other bytes: same content, same bytes.
void make_uuid_deterministic(const std::string& path) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(file), {});
  const auto is_uuid = [&](const std::string& u) {
    for (size_t i = 0; i < kUuidLength; ++i)
      if ((i == 8 || i == 13 || i == 18 || i == 23) ? u[i] != '-' : !std::isxdigit(u[i]))
        return false;
    return true;
  };
  if (!file || bytes.size() < kUuidOffset + kUuidLength ||
      !is_uuid(bytes.substr(kUuidOffset, kUuidLength)))
    throw Error(
        fmt::format("{}: expected an OpenVDB header with a UUID at byte {}", path, kUuidOffset));
  const std::string head = bytes.substr(0, kUuidOffset);
  const std::string tail = bytes.substr(kUuidOffset + kUuidLength);
  const std::string hex = Hasher().add(head).add(tail).hex() +
                          Hasher().add("skybake vdb uuid").add(head).add(tail).hex();
  const std::string uuid = hex.substr(0, 8) + "-" + hex.substr(8, 4) + "-" + hex.substr(12, 4) +
                           "-" + hex.substr(16, 4) + "-" + hex.substr(20, 12);
  file.clear();
  file.seekp(kUuidOffset);
  file.write(uuid.data(), std::streamsize(uuid.size()));
  if (!file.flush()) throw IoError(fmt::format("{}: cannot rewrite the VDB header", path));
}

std::string string_meta(const openvdb::GridBase& grid, const std::string& name) {
  const auto meta = grid[name];
  return meta && meta->typeName() == openvdb::StringMetadata::staticTypeName() ? meta->str() : "";
}

}  // namespace

void write_vdb(const std::string& path, const Texture& tex, double voxel_size) {
  check_writable(path, tex, voxel_size);
  init_openvdb();
  auto xform = openvdb::math::Transform::createLinearTransform(voxel_size);
  xform->postTranslate(openvdb::Vec3d(0.5 * voxel_size));  // voxel i covers [i s, (i + 1) s]
  openvdb::GridCPtrVec grids;
  for (int c = 0; c < tex.channel_count(); ++c) grids.push_back(make_grid(tex, c, *xform));
  try {
    openvdb::io::File(path).write(grids);
    make_uuid_deterministic(path);
  } catch (const openvdb::Exception& e) {
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: cannot write VDB: {}", path, e.what()));
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
}

Texture read_vdb(const std::string& path) {
  init_openvdb();
  openvdb::GridPtrVecPtr grids;
  try {
    openvdb::io::File file(path);
    file.open(/*delayLoad=*/false);
    grids = file.getGrids();
    file.close();
  } catch (const openvdb::Exception& e) {
    throw IoError(fmt::format("{}: cannot read VDB: {}", path, e.what()));
  }
  if (!grids || grids->empty())
    throw IoError(fmt::format("{}: expected at least one grid, got none", path));

  std::vector<openvdb::FloatGrid::Ptr> floats;
  openvdb::CoordBBox box;
  for (const auto& base : *grids) {
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!grid)
      throw IoError(fmt::format("{}: expected float grids, got a {} grid '{}'", path, base->type(),
                                base->getName()));
    box.expand(grid->evalActiveVoxelBoundingBox());
    floats.push_back(grid);
  }
  const std::string shape_text = string_meta(*floats[0], kPrefix + "shape");
  int w = 0, h = 0, d = 0, layers = 0;
  if (!shape_text.empty()) {
    if (std::sscanf(shape_text.c_str(), "%dx%dx%dx%d", &w, &h, &d, &layers) != 4 || layers != 1 ||
        w < 1 || h < 1 || d < 1)
      throw IoError(fmt::format("{}: expected skybake:shape of the form WxHxDx1, got '{}'", path,
                                shape_text));
    box = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(w - 1, h - 1, d - 1));
  } else if (box.empty()) {
    throw IoError(fmt::format("{}: expected active voxels, got none", path));
  }
  // Put the grids in channel order when the file records it.
  const std::string order = string_meta(*floats[0], kPrefix + "channels");
  if (!order.empty()) {
    std::vector<openvdb::FloatGrid::Ptr> ordered;
    for (size_t start = 0, end = 0; end != std::string::npos; start = end + 1) {
      end = order.find(',', start);
      const std::string name = order.substr(start, end - start);
      const auto it = std::find_if(floats.begin(), floats.end(),
                                   [&](const auto& g) { return g->getName() == name; });
      if (it == floats.end())
        throw IoError(
            fmt::format("{}: expected a grid '{}' (skybake:channels), got none", path, name));
      ordered.push_back(*it);
    }
    floats = ordered;
  }
  std::vector<std::string> channels;
  for (const auto& grid : floats) channels.push_back(grid->getName());
  const openvdb::Coord dim = box.dim();
  Texture tex(dim.x(), dim.y(), dim.z(), 1, channels);
  for (auto it = floats[0]->beginMeta(); it != floats[0]->endMeta(); ++it)
    if (it->first.rfind(kPrefix, 0) == 0 && it->first != kPrefix + "shape" &&
        it->first != kPrefix + "channels" &&
        it->second->typeName() == openvdb::StringMetadata::staticTypeName())
      tex.metadata[it->first.substr(kPrefix.size())] = it->second->str();

  std::vector<float> plane(tex.texel_count());
  const size_t nc = channels.size();
  for (size_t c = 0; c < nc; ++c) {
    DenseXYZ dense(box, plane.data());
    openvdb::tools::copyToDense(*floats[c], dense);
    for (size_t t = 0; t < plane.size(); ++t) tex.data[t * nc + c] = plane[t];
  }
  return tex;
}

}  // namespace skybake
