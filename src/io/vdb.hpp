// OpenVDB output and input for Textures: one grid per channel, with the voxel
// transform and metadata; dense grids, background 0. Only the plugin's
// vdb.cpp and vdb_leaves.cpp include OpenVDB (slow headers,
// docs/architecture.md "Build").
//
// File shape:
//   One openvdb::FloatGrid per channel, named after the channel or by the
//   caller's grid names (OpenVDB lists grids by name, so the channel order is
//   kept in metadata). Grid class: unknown, or fog volume for density-like
//   data (VdbWriteOptions; docs/formats.md "VDB").
//   Texel (x, y, z) is voxel index coordinate (x, y, z); a 2D texture is the
//   single slice z = 0. Every voxel of [0, W) x [0, H) x [0, D) is active
//   (constant regions may be stored as active tiles), background 0.
//   Transform: linear, voxel size s, translated by s/2, so voxel i covers
//   world [i s, (i + 1) s] and its centre is (i + 0.5) s, the texel-centre
//   convention of docs/architecture.md "Texel centres"; with s = 1/N an N^3
//   volume spans exactly [0, 1]^3.
//   Grid metadata (on every grid): "skybake:<key>" string per
//   Texture::metadata entry, "skybake:shape" string "WxHxDxL" and
//   "skybake:channels", the channel names in texture order, comma separated;
//   and on each grid "skybake:texture_channel", the channel it holds; metadata
//   keys may not be "shape", "channels" or "texture_channel". OpenVDB adds its
//   own file_* statistics and "class".
//   Compression (VdbCompression): the active-value mask always; the value
//   buffers Blosc (LZ4, OpenVDB's default), zlib, or none.
// Determinism: OpenVDB writes a random UUID into the file header; we replace
// it with one derived from a hash of the rest of the file, so the same
// texture gives byte-identical files (and distinct contents distinct UUIDs).
// Both functions run in the VDB plugin, libskybake_vdb.so, opened on first
// use (vdb_plugin.hpp); when it cannot be loaded they throw IoError naming
// every path tried.
#pragma once

#include <string>
#include <vector>

#include "core/finite_check.hpp"
#include "core/texture.hpp"
#include "io/read_budget.hpp"

namespace skybake {

enum class VdbGridClass { unknown, fog_volume };

// How the grids' value buffers are compressed (docs/formats.md "VDB").
enum class VdbCompression { blosc, zip, none };

// How the grids' trees are built; the same file either way (tested).
// `direct` fills the leaves from the texture wherever that is provably
// copyFromDense's tree (io/vdb_leaves.hpp), else falls back to
// `dense_copy`: each channel copied into a dense array and given to
// OpenVDB's copyFromDense, the reference `direct` is tested against.
enum class VdbTreeBuild { direct, dense_copy };

// "blosc", "zip", "none"; throws Error naming the value otherwise.
VdbCompression vdb_compression_from_name(const std::string& name);

struct VdbWriteOptions {
  // World-space edge length of one voxel (> 0; 1/N maps an N-texel axis onto [0, 1]).
  double voxel_size = 1.0;
  // One grid name per channel, in channel order; empty: the channel names.
  // Each matches ^[A-Za-z_][A-Za-z0-9_]{0,63}$ (an identifier every DCC
  // tool accepts as a volume name), and they are distinct.
  std::vector<std::string> grid_names;
  // openvdb::GRID_FOG_VOLUME for density-like data (values 0 = empty and up),
  // so viewers shade it as a volume; GRID_UNKNOWN otherwise.
  VdbGridClass grid_class = VdbGridClass::unknown;
  VdbCompression compression = VdbCompression::blosc;
  FiniteCheck finite = FiniteCheck::run;  // core/finite_check.hpp
  VdbTreeBuild tree_build = VdbTreeBuild::direct;
};

// True when `name` is a grid name VdbWriteOptions accepts. Inline: both
// skybake_io and the plugin check it.
inline bool is_valid_vdb_grid_name(const std::string& name) {
  const auto letter = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
  };
  if (name.empty() || name.size() > 64 || !letter(name[0])) return false;
  for (char c : name)
    if (!letter(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

// Writes `tex` to exactly `path` (no temporary file: the caller renames).
// voxel_size: world-space edge length of one voxel (> 0; 1/N maps an N-texel
// axis onto [0, 1]). Threaded (OpenVDB's dense copy uses TBB).
// Throws IoError (before creating the file) when a value is NaN/Inf, the
// texture is empty or a 2D array, channel names repeat or hold commas, or the grid names are not
// one valid distinct name per channel; throws IoError when
// OpenVDB fails (the partial file is removed); throws Error on a reserved
// metadata key or a voxel size that is not positive and finite.
void write_vdb(const std::string& path, const Texture& tex, const VdbWriteOptions& options);
// As above with the channel names as grid names and class unknown.
void write_vdb(const std::string& path, const Texture& tex, double voxel_size);

// Reads a .vdb of float grids into a Texture: channels are the grids'
// skybake:texture_channel (else their names) in skybake:channels order (for a
// foreign file, the grid names in OpenVDB's name order); the shape comes from
// skybake:shape, or for a foreign file from the union of the grids' active bounding boxes (whose
// minimum becomes texel 0). Metadata: the first grid's skybake:* strings, prefix stripped. Throws
// IoError when the file cannot be read or holds a non-float grid.
// `budget`: the most the dense copy may take (io/read_budget.hpp).
Texture read_vdb(const std::string& path, uint64_t budget = kNoReadBudget);

}  // namespace skybake
