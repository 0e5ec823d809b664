// OpenVDB output and input for Textures: one grid per channel, with the voxel
// transform and metadata; dense grids, background 0. Only vdb.cpp includes
// OpenVDB (slow headers, docs/architecture.md "Build").
//
// File shape:
//   One openvdb::FloatGrid per channel, named after the channel (OpenVDB
//   lists grids by name, so the channel order is kept in metadata).
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
//   metadata keys may not be "shape" or "channels". OpenVDB adds its own
//   file_* statistics.
//   Compression: OpenVDB's default (Blosc + active mask when available).
// Determinism: OpenVDB writes a random UUID into the file header; we replace
// it with one derived from a hash of the rest of the file, so the same
// texture gives byte-identical files (and distinct contents distinct UUIDs).
// Both functions run in the VDB plugin, libskybake_vdb.so, opened on first
// use (vdb_plugin.hpp); when it cannot be loaded they throw IoError naming
// every path tried.
#pragma once

#include <string>

#include "core/texture.hpp"

namespace skybake {

// Writes `tex` to exactly `path` (no temporary file: the caller renames).
// voxel_size: world-space edge length of one voxel (> 0; 1/N maps an N-texel
// axis onto [0, 1]). Threaded (OpenVDB's dense copy uses TBB).
// Throws IoError (before creating the file) when a value is NaN/Inf, the
// texture is empty or a 2D array, or channel names repeat or hold commas; throws IoError when
// OpenVDB fails (the partial file is removed); throws Error on a reserved
// metadata key or a voxel size that is not positive and finite.
void write_vdb(const std::string& path, const Texture& tex, double voxel_size);

// Reads a .vdb of float grids into a Texture: channels are the grid names in
// skybake:channels order (for a foreign file, OpenVDB's name order); the shape comes from
// skybake:shape, or for a foreign file from the union of the grids' active bounding boxes (whose
// minimum becomes texel 0). Metadata: the first grid's skybake:* strings, prefix stripped. Throws
// IoError when the file cannot be read or holds a non-float grid.
Texture read_vdb(const std::string& path);

}  // namespace skybake
