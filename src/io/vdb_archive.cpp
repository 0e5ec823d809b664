#include "io/vdb_archive.hpp"

#include <ostream>

#include <openvdb/io/File.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>

#include "io/buffered_out_file.hpp"

namespace skybake {

namespace {

// io::File for its compression settings and the archive's protected writers.
class ArchiveWriter : public openvdb::io::File {
 public:
  ArchiveWriter(const std::string& path, uint32_t compression) : File(path) {
    setCompression(compression);
  }

  void write_all(std::ostream& os, const openvdb::GridCPtrVec& grids) const {
    Archive::write(os, grids, /*seekable=*/true);
  }

  // io::Archive::write (openvdb/io/Archive.cc, OpenVDB 10) step by step,
  // for grids with distinct non-empty names and distinct trees: stream
  // metadata, header, the file's (empty) metadata, the grid count, then per
  // grid its descriptor and writeGrid, the compression flags restored after
  // each. Tested against write_all to the byte (tests/io/vdb_leaves_test.cpp).
  void write_one_at_a_time(std::ostream& os, const std::vector<openvdb::FloatGrid::Ptr>& grids,
                           const std::function<openvdb::FloatTree::Ptr(size_t)>& tree_of) const {
    namespace io = openvdb::io;
    io::StreamMetadata::Ptr meta = io::getStreamMetadataPtr(os);
    if (!meta) {  // the stream does not own it: kept alive here until the end
      meta = std::make_shared<io::StreamMetadata>();
      io::setStreamMetadataPtr(os, meta, /*transfer=*/false);
    }
    io::setDataCompression(os, compression());
    io::setWriteGridStatsMetadata(os, isGridStatsMetadataEnabled());
    writeHeader(os, /*seekable=*/true);
    openvdb::MetaMap().writeMeta(os);
    const int32_t count = int32_t(grids.size());
    os.write(reinterpret_cast<const char*>(&count), sizeof(count));
    for (size_t i = 0; i < grids.size(); ++i) {
      grids[i]->setTree(tree_of(i));
      io::GridDescriptor gd(grids[i]->getName(), grids[i]->type(), grids[i]->saveFloatAsHalf());
      writeGrid(gd, grids[i], os, /*seekable=*/true);
      // Freed here, so the next tree's leaves reuse the memory.
      grids[i]->setTree(std::make_shared<openvdb::FloatTree>(0.0f));
      io::setDataCompression(os, compression());
    }
  }
};

}  // namespace

void write_vdb_archive(const std::string& path, uint32_t compression,
                       const openvdb::GridCPtrVec& grids) {
  BufferedOutFile out(path);
  std::ostream os(&out);
  ArchiveWriter(path, compression).write_all(os, grids);
  out.close();
}

void write_vdb_archive_one_tree_at_a_time(
    const std::string& path, uint32_t compression, const std::vector<openvdb::FloatGrid::Ptr>& grids,
    const std::function<openvdb::FloatTree::Ptr(size_t)>& tree_of) {
  BufferedOutFile out(path);
  std::ostream os(&out);
  ArchiveWriter(path, compression).write_one_at_a_time(os, grids, tree_of);
  out.close();
}

}  // namespace skybake
