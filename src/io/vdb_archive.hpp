// Writing a VDB file's grids (VDB plugin only: includes OpenVDB), through a
// BufferedOutFile (io/buffered_out_file.hpp): io::File::write streams through
// a default std::ofstream, whose filebuf makes a system call per leaf
// buffer. OpenVDB's archive writer, given that stream, writes the same bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

namespace skybake {

// OpenVDB's io::Archive::write of `grids`, seekable as io::File writes it,
// with `compression` (openvdb::io::COMPRESS_* flags).
void write_vdb_archive(const std::string& path, uint32_t compression,
                       const openvdb::GridCPtrVec& grids);

// The same file as write_vdb_archive of `grids` with grid i's tree given by
// `tree_of(i)`, but each tree made just before its grid is written and freed
// right after: one channel's leaves at a time, the next built from the
// memory of the one before (a 128^3 volume's four grids hold 34 MB of leaves
// and nodes, fresh pages each). The grids' names are distinct and not empty
// (no name suffixes, as write_vdb checks) and their trees distinct (no
// instances); their trees are left empty.
void write_vdb_archive_one_tree_at_a_time(
    const std::string& path, uint32_t compression, const std::vector<openvdb::FloatGrid::Ptr>& grids,
    const std::function<openvdb::FloatTree::Ptr(size_t)>& tree_of);

}  // namespace skybake
