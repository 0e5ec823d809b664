// VDB writer and reader: one dense FloatGrid per channel (layout in vdb.hpp),
// built into the VDB plugin (vdb_plugin.hpp), never into skybake_io.
// With vdb_leaves.cpp and vdb_archive.cpp, the only translation units of src/ that include
// OpenVDB (its headers cost 4-12 s per file; docs/architecture.md "Build").
#include "io/vdb.hpp"
#include "io/vdb_plugin.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <tbb/parallel_for.h>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "io/shape_text.hpp"
#include "io/vdb_archive.hpp"
#include "io/vdb_layout.hpp"
#include "io/vdb_leaves.hpp"

namespace skybake {

namespace {

const std::string kPrefix = "skybake:";
using DenseXYZ = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;
using DenseZYX = openvdb::tools::Dense<float, openvdb::tools::LayoutZYX>;

// The header written by io::Archive::writeHeader: magic (8 bytes), file
// format version (4), library major and minor versions (4 + 4), the
// "has grid offsets" flag (1), then the UUID as 36 ASCII characters.
constexpr size_t kUuidOffset = 21;
constexpr size_t kUuidLength = 36;
// Seeds of the two hashes that make the UUID (any two distinct values).
constexpr uint64_t kUuidSeeds[2] = {0x736b7962616b6531ull, 0x766462757569643aull};

// Bounds on the dense texture read_vdb makes: a side of at most 2^20 voxels
// (skybake writes at most 1024) and 4 GiB for the texture with its one-grid
// scratch plane (every output skybake writes is at most 2 GiB).
constexpr int64_t kMaxVdbSide = int64_t(1) << 20;
constexpr uint64_t kMaxVdbDenseBytes = uint64_t(4) << 30;

void init_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The grid name of each channel: the options' names, else the channel names.
std::vector<std::string> grid_names_of(const std::string& path, const Texture& tex,
                                       const VdbWriteOptions& options) {
  if (options.grid_names.empty()) return tex.channels;
  const std::vector<std::string>& names = options.grid_names;
  if (names.size() != tex.channels.size())
    throw IoError(fmt::format("{}: expected one grid name per channel ({}), got {} ({})", path,
                              tex.channels.size(), names.size(), fmt::join(names, ", ")));
  for (const std::string& name : names)
    if (!is_valid_vdb_grid_name(name))
      throw IoError(fmt::format("{}: expected grid names of letters, digits and '_' (not starting "
                                "with a digit, at most 64), got '{}'",
                                path, name));
  if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
    throw IoError(fmt::format("{}: expected distinct grid names, got {}", path,
                              fmt::join(names, ", ")));
  return names;
}

void check_writable(const std::string& path, const Texture& tex, double voxel_size,
                    FiniteCheck finite) {
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
  for (const char* key : {"shape", "channels", "texture_channel"})
    if (tex.metadata.count(key))
      throw Error(fmt::format("{}: expected a metadata key other than the reserved '{}{}'", path,
                              kPrefix, key));
  if (finite == FiniteCheck::run) check_finite(tex, path);
}

// A metadata value as the VDB metadata type of its type: int32, double,
// string, vec2i, vec3i, vec2d, vec3d (docs/formats.md "Metadata").
void insert_typed_meta(openvdb::GridBase& grid, const std::string& name, const MetaValue& value) {
  struct Insert {
    openvdb::GridBase& grid;
    const std::string& name;
    void operator()(int v) const { grid.insertMeta(name, openvdb::Int32Metadata(v)); }
    void operator()(double v) const { grid.insertMeta(name, openvdb::DoubleMetadata(v)); }
    void operator()(const std::string& v) const {
      grid.insertMeta(name, openvdb::StringMetadata(v));
    }
    void operator()(const glm::ivec2& v) const {
      grid.insertMeta(name, openvdb::Vec2IMetadata(openvdb::Vec2i(v.x, v.y)));
    }
    void operator()(const glm::ivec3& v) const {
      grid.insertMeta(name, openvdb::Vec3IMetadata(openvdb::Vec3i(v.x, v.y, v.z)));
    }
    void operator()(const glm::dvec2& v) const {
      grid.insertMeta(name, openvdb::Vec2DMetadata(openvdb::Vec2d(v.x, v.y)));
    }
    void operator()(const glm::dvec3& v) const {
      grid.insertMeta(name, openvdb::Vec3DMetadata(openvdb::Vec3d(v.x, v.y, v.z)));
    }
  };
  std::visit(Insert{grid, name}, value);
}

// The metadata value of a VDB metadata entry of one of the types above, or
// nullopt for any other type.
std::optional<MetaValue> typed_meta(const openvdb::Metadata& m) {
  if (const auto* v = dynamic_cast<const openvdb::Int32Metadata*>(&m)) return v->value();
  if (const auto* v = dynamic_cast<const openvdb::DoubleMetadata*>(&m)) return v->value();
  if (const auto* v = dynamic_cast<const openvdb::StringMetadata*>(&m)) return v->value();
  if (const auto* v = dynamic_cast<const openvdb::Vec2IMetadata*>(&m))
    return glm::ivec2(v->value().x(), v->value().y());
  if (const auto* v = dynamic_cast<const openvdb::Vec3IMetadata*>(&m))
    return glm::ivec3(v->value().x(), v->value().y(), v->value().z());
  if (const auto* v = dynamic_cast<const openvdb::Vec2DMetadata*>(&m))
    return glm::dvec2(v->value().x(), v->value().y());
  if (const auto* v = dynamic_cast<const openvdb::Vec3DMetadata*>(&m))
    return glm::dvec3(v->value().x(), v->value().y(), v->value().z());
  return std::nullopt;
}

// OpenVDB's flags for `c`; the active mask is cheap and lossless, so always.
uint32_t compression_flags(VdbCompression c) {
  const uint32_t values = c == VdbCompression::blosc ? openvdb::io::COMPRESS_BLOSC
                          : c == VdbCompression::zip ? openvdb::io::COMPRESS_ZIP
                                                     : openvdb::io::COMPRESS_NONE;
  return values | openvdb::io::COMPRESS_ACTIVE_MASK;
}

// The reference build of one channel's tree (VdbTreeBuild::dense_copy):
// every voxel in the texture's box active, values as OpenVDB's copyFromDense
// stores them.
openvdb::FloatTree::Ptr dense_copy_tree(const Texture& tex, int c) {
  const size_t nc = tex.channels.size(), texels = tex.texel_count();
  // OpenVDB's leaves hold z fastest (offset x << 6 | y << 3 | z), and
  // copyFromDense reads the dense array in that order: from an x-fastest
  // copy every voxel read jumps a whole plane (64 KB at 128^2), from a
  // z-fastest one (ZYX) the reads run along memory. The channel is copied
  // z fastest in tiles of 8 x 8 texels (x, z) per row y. Same values, same
  // grid.
  const size_t w = size_t(tex.width), h = size_t(tex.height), d = size_t(tex.depth);
  constexpr size_t kTile = 8;
  // Not zero-filled: the loops below write every element.
  const std::unique_ptr<float[]> plane(new float[texels]);
  for (size_t y = 0; y < h; ++y)
    for (size_t z0 = 0; z0 < d; z0 += kTile)
      for (size_t x0 = 0; x0 < w; x0 += kTile)
        for (size_t z = z0, z_end = std::min(z0 + kTile, d); z < z_end; ++z)
          for (size_t x = x0, x_end = std::min(x0 + kTile, w); x < x_end; ++x)
            plane[(x * h + y) * d + z] = tex.data[((z * h + y) * w + x) * nc + size_t(c)];
  const openvdb::CoordBBox box(openvdb::Coord(0),
                               openvdb::Coord(tex.width - 1, tex.height - 1, tex.depth - 1));
  auto tree = std::make_shared<openvdb::FloatTree>(0.0f);
  openvdb::tools::copyFromDense(DenseZYX(box, plane.get()), *tree, 0.0f);
  // copyFromDense leaves voxels equal to the background inactive; the union
  // with an all-active box activates them without changing any value, so the
  // grid is dense (vdb.hpp: every voxel of the domain is active) and viewers
  // see the whole domain.
  openvdb::MaskTree box_mask;
  box_mask.fill(box, true, true);
  tree->topologyUnion(box_mask);
  return tree;
}

// One channel's tree as a named grid with the texture's metadata.
openvdb::FloatGrid::Ptr make_grid(const Texture& tex, int c, openvdb::FloatTree::Ptr tree,
                                  const std::string& name, VdbGridClass grid_class,
                                  const openvdb::math::Transform& xform) {
  auto grid = openvdb::FloatGrid::create(tree);
  grid->setName(name);
  grid->setGridClass(grid_class == VdbGridClass::fog_volume ? openvdb::GRID_FOG_VOLUME
                                                            : openvdb::GRID_UNKNOWN);
  grid->setTransform(xform.copy());
  grid->insertMeta(kPrefix + "texture_channel", openvdb::StringMetadata(tex.channels[c]));
  for (const auto& [key, value] : tex.metadata) insert_typed_meta(*grid, kPrefix + key, value);
  grid->insertMeta(kPrefix + "shape",
                   openvdb::StringMetadata(
                       fmt::format("{}x{}x{}x{}", tex.width, tex.height, tex.depth, tex.layers)));
  grid->insertMeta(kPrefix + "channels",
                   openvdb::StringMetadata(fmt::format("{}", fmt::join(tex.channels, ","))));
  return grid;
}

bool is_uuid_text(const char* u) {
  for (size_t i = 0; i < kUuidLength; ++i)
    if ((i == 8 || i == 13 || i == 18 || i == 23) ? u[i] != '-' : !std::isxdigit(u[i]))
      return false;
  return true;
}

// Replaces the random UUID OpenVDB wrote with one derived from the file's
// other bytes: same content, same bytes. Two word-at-a-time hashes (seeds
// apart) of the file with the UUID's bytes zeroed make its 128 bits; the file
// is read in blocks (a multiple of 8 bytes, so the hash is the whole file's).
void make_uuid_deterministic(const std::string& path) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  std::vector<char> block(size_t(1) << 20);
  uint64_t h[2] = {kUuidSeeds[0], kUuidSeeds[1]}, length = 0;
  while (file) {
    file.read(block.data(), std::streamsize(block.size()));
    const size_t n = size_t(file.gcount());
    if (length == 0) {
      if (n < kUuidOffset + kUuidLength || !is_uuid_text(block.data() + kUuidOffset))
        throw Error(fmt::format("{}: expected an OpenVDB header with a UUID at byte {}", path,
                                kUuidOffset));
      std::fill_n(block.begin() + kUuidOffset, kUuidLength, '\0');
    }
    hash_words_mix2(h, block.data(), n);
    length += n;
  }
  if (!file.eof()) throw IoError(fmt::format("{}: cannot read back the VDB file", path));
  const std::string hex = fmt::format("{:016x}{:016x}", hash_words_finish(h[0], length),
                                      hash_words_finish(h[1], length));
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

void write_vdb_file(const std::string& path, const Texture& tex, const VdbWriteOptions& options) {
  const double voxel_size = options.voxel_size;
  check_writable(path, tex, voxel_size, options.finite);
  const std::vector<std::string> names = grid_names_of(path, tex, options);
  init_openvdb();
  auto xform = openvdb::math::Transform::createLinearTransform(voxel_size);
  xform->postTranslate(openvdb::Vec3d(0.5 * voxel_size));  // voxel i covers [i s, (i + 1) s]
  std::vector<openvdb::FloatGrid::Ptr> built(tex.channels.size());
  for (size_t c = 0; c < built.size(); ++c)
    built[c] = make_grid(tex, int(c), std::make_shared<openvdb::FloatTree>(0.0f), names[c],
                         options.grid_class, *xform);
  const uint32_t compression = compression_flags(options.compression);
  const auto tree_of = [&](size_t c) {
    openvdb::FloatTree::Ptr tree;
    if (options.tree_build == VdbTreeBuild::direct) tree = direct_leaf_tree(tex, int(c));
    return tree ? tree : dense_copy_tree(tex, int(c));
  };
  // One tree at a time where OpenVDB's writer keeps every grid name as it is
  // (io/vdb_archive.hpp: distinct, which grid_names_of checks, and not empty).
  const bool one_at_a_time =
      options.tree_build == VdbTreeBuild::direct &&
      std::none_of(names.begin(), names.end(), [](const std::string& n) { return n.empty(); });
  try {
    if (one_at_a_time) {
      write_vdb_archive_one_tree_at_a_time(path, compression, built, tree_of);
    } else {
      // The channels side by side; each tree is the same whatever the order.
      tbb::parallel_for(size_t(0), built.size(), [&](size_t c) { built[c]->setTree(tree_of(c)); });
      write_vdb_archive(path, compression, openvdb::GridCPtrVec(built.begin(), built.end()));
    }
    make_uuid_deterministic(path);
  } catch (const openvdb::Exception& e) {
    std::remove(path.c_str());
    throw IoError(fmt::format("{}: cannot write VDB: {}", path, e.what()));
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
}

namespace {

// Every grid of the file, as float grids, and the box of their active voxels.
std::vector<openvdb::FloatGrid::Ptr> read_float_grids(const std::string& path,
                                                      openvdb::CoordBBox& active) {
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
  for (const auto& base : *grids) {
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!grid)
      throw IoError(fmt::format("{}: expected float grids, got a {} grid '{}'", path, base->type(),
                                base->getName()));
    active.expand(grid->evalActiveVoxelBoundingBox());
    floats.push_back(grid);
  }
  return floats;
}

// The texture's box: skybake:shape when the file records it, else the active voxels.
openvdb::CoordBBox texture_box(const std::string& path, const openvdb::FloatGrid& first,
                               const openvdb::CoordBBox& active) {
  const std::string shape_text = string_meta(first, kPrefix + "shape");
  if (shape_text.empty()) {
    if (active.empty()) throw IoError(fmt::format("{}: expected active voxels, got none", path));
    return active;
  }
  const std::optional<ShapeText> s = parse_shape_text(shape_text, kMaxVdbSide);
  if (!s || s->layers != 1)
    throw IoError(fmt::format(
        "{}: expected skybake:shape of the form WxHxDx1 with sizes from 1 to {}, got '{}'", path,
        kMaxVdbSide, shape_text));
  return openvdb::CoordBBox(openvdb::Coord(0),
                            openvdb::Coord(s->width - 1, s->height - 1, s->depth - 1));
}

// The texture channel a grid holds: skybake:texture_channel, else its name.
std::string channel_of(const openvdb::GridBase& grid) {
  const std::string channel = string_meta(grid, kPrefix + "texture_channel");
  return channel.empty() ? grid.getName() : channel;
}

// The grids in channel order when the file records it (skybake:channels).
std::vector<openvdb::FloatGrid::Ptr> in_channel_order(
    const std::string& path, const std::vector<openvdb::FloatGrid::Ptr>& floats) {
  const std::string order = string_meta(*floats[0], kPrefix + "channels");
  if (order.empty()) return floats;
  std::vector<openvdb::FloatGrid::Ptr> ordered;
  for (size_t start = 0, end = 0; end != std::string::npos; start = end + 1) {
    end = order.find(',', start);
    const std::string name = order.substr(start, end - start);
    const auto it = std::find_if(floats.begin(), floats.end(),
                                 [&](const auto& g) { return channel_of(*g) == name; });
    if (it == floats.end())
      throw IoError(fmt::format(
          "{}: expected a grid holding channel '{}' (skybake:channels), got none", path, name));
    if (std::find(ordered.begin(), ordered.end(), *it) != ordered.end())
      throw IoError(fmt::format(
          "{}: expected distinct grids in skybake:channels, got '{}' twice", path, name));
    ordered.push_back(*it);
  }
  return ordered;
}

// The dense copy's size comes from the file: refuse it before allocating.
void check_dense_size(const std::string& path, const openvdb::CoordBBox& box, size_t grids,
                      uint64_t budget) {
  uint64_t voxels = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t side = int64_t(box.max()[axis]) - box.min()[axis] + 1;
    if (side < 1 || side > kMaxVdbSide)
      throw IoError(fmt::format("{}: expected a box of 1 to {} voxels per axis, got {}", path,
                                kMaxVdbSide, side));
    voxels *= uint64_t(side);
  }
  const uint64_t voxel_bytes = (grids + 1) * sizeof(float);  // texture and plane
  if (voxels > kMaxVdbDenseBytes / voxel_bytes)
    throw IoError(fmt::format("{}: a dense copy of {} voxels x {} grids is over the {} GiB limit",
                              path, voxels, grids, kMaxVdbDenseBytes >> 30));
  const openvdb::Coord dim = box.dim();
  check_read_budget(path, voxels * voxel_bytes, budget,
                    fmt::format("a dense {}x{}x{} copy of {} float grid{} and one plane",
                                dim.x(), dim.y(), dim.z(), grids, grids == 1 ? "" : "s"));
}

Texture dense_texture(const openvdb::CoordBBox& box,
                      const std::vector<openvdb::FloatGrid::Ptr>& floats) {
  std::vector<std::string> channels;
  for (const auto& grid : floats) channels.push_back(channel_of(*grid));
  const openvdb::Coord dim = box.dim();
  Texture tex(dim.x(), dim.y(), dim.z(), 1, channels);
  for (auto it = floats[0]->beginMeta(); it != floats[0]->endMeta(); ++it)
    if (it->first.rfind(kPrefix, 0) == 0 && it->first != kPrefix + "shape" &&
        it->first != kPrefix + "channels" && it->first != kPrefix + "texture_channel")
      if (std::optional<MetaValue> value = typed_meta(*it->second))
        tex.metadata[it->first.substr(kPrefix.size())] = *value;
  std::vector<float> plane(tex.texel_count());
  const size_t nc = channels.size();
  for (size_t c = 0; c < nc; ++c) {
    DenseXYZ dense(box, plane.data());
    openvdb::tools::copyToDense(*floats[c], dense);
    for (size_t t = 0; t < plane.size(); ++t) tex.data[t * nc + c] = plane[t];
  }
  return tex;
}

}  // namespace

Texture read_vdb_file(const std::string& path, uint64_t budget) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw IoError(fmt::format("{}: expected a regular file", path));
  init_openvdb();
  // Every length OpenVDB will trust is checked against the file first.
  check_vdb_layout(path);
  openvdb::CoordBBox active;
  const std::vector<openvdb::FloatGrid::Ptr> floats = read_float_grids(path, active);
  const openvdb::CoordBBox box = texture_box(path, *floats[0], active);
  const std::vector<openvdb::FloatGrid::Ptr> ordered = in_channel_order(path, floats);
  check_dense_size(path, box, ordered.size(), budget);
  return dense_texture(box, ordered);
}

}  // namespace skybake
