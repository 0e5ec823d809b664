// A walk over a VDB file's bytes in the order OpenVDB 10 reads them (file
// format 222 to 224 with grid offsets, float grids Tree_float_5_4_3), run
// before OpenVDB sees the file. OpenVDB trusts every length in the file: a
// metadata string, a node count or a compressed chunk's size is allocated as
// read (a 500-byte file reached 11 GB). The walk checks each of them against
// the bytes that remain, each blosc chunk's header against its chunk, and the
// grid offsets against where each section really ends, so that what OpenVDB
// then allocates is bounded by the file's size (about 35 bytes of tree per
// byte of file: an internal node's table per 8 KiB of masks, a leaf's 2 KiB
// buffer per 73 bytes). docs/decisions/hostile-texture-files.md, "Hostile inputs", has the details.
#pragma once

#include <string>

namespace skybake {

// Throws IoError "<path>: not a VDB skybake can read safely: <rule> (at byte
// N)" at the first length that does not fit, or for anything the walk does
// not know (other grid types, grid instances, transforms other than the
// linear maps, files without grid offsets). Needs openvdb::initialize().
void check_vdb_layout(const std::string& path);

}  // namespace skybake
