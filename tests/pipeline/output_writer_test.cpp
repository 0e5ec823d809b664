// The output writer (pipeline/output_writer.hpp): every requested format is
// written under its final name and reads back as the texture that was given;
// the manifest records match the files; nothing temporary is left behind;
// and a format that fails leaves no file of that output under a final name,
// not even the formats written before it, nor a half-replaced old version.
#include "pipeline/output_writer.hpp"

#include <OpenImageIO/imageio.h>
#include <openvdb/openvdb.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/file_record.hpp"
#include "io/texture_file.hpp"
#include "support/run.hpp"

namespace fs = std::filesystem;

namespace skybake {
namespace {

// A small RGBA volume with distinct, exactly representable values: every
// format that stores float32 must give them back bit for bit.
Texture rgba_volume() {
  Texture tex(8, 4, 3, 1, {"R", "G", "B", "A"});
  for (size_t i = 0; i < tex.data.size(); ++i) tex.data[i] = float(i % 251) / 256.0f + 0.125f;
  return tex;
}

// The aerial-perspective product: a 3D RGBA table that may be written as EXR,
// DDS, VDB and a PNG preview.
const ProductInfo& volume_product() {
  const ProductInfo* info = find_product("aerial_perspective");
  EXPECT_NE(info, nullptr);
  return *info;
}

OutputSpec spec_of(const std::string& name, std::vector<std::string> formats) {
  OutputSpec spec;
  spec.product = "aerial_perspective";
  spec.name = name;
  spec.size = {8, 4, 3};
  spec.formats = std::move(formats);
  spec.options = nlohmann::json::object({{"product", "aerial_perspective"}});
  return spec;
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (is_temporary_name(e.path().filename().string())) found.push_back(e.path().string());
  return found;
}

void expect_same_texels(const Texture& read, const Texture& written, const std::string& what) {
  ASSERT_EQ(read.width, written.width) << what;
  ASSERT_EQ(read.height, written.height) << what;
  ASSERT_EQ(read.depth, written.depth) << what;
  ASSERT_EQ(read.channel_count(), written.channel_count()) << what;
  ASSERT_EQ(read.data.size(), written.data.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < read.data.size(); ++i) differing += read.data[i] != written.data[i];
  EXPECT_EQ(differing, 0u) << what << ": texels that did not survive the round trip";
}

TEST(OutputWriter, FileNamesFollowTheFormatsInOrder) {
  const OutputSpec spec = spec_of("sky", {"dds", "png", "exr", "vdb"});
  EXPECT_EQ(output_files(spec),
            (std::vector<std::string>{"sky.dds", "sky.preview.png", "sky.exr", "sky.vdb"}));
  EXPECT_TRUE(output_files(spec_of("sky", {})).empty());
}

TEST(OutputWriter, EveryFormatIsWrittenUnderItsFinalNameAndReadsBackEqual) {
  const fs::path dir = test::fresh_dir("output_writer_all_formats");
  const Texture tex = rgba_volume();
  const OutputSpec spec = spec_of("volume", {"exr", "dds", "vdb", "png"});
  const std::vector<ManifestFile> files = write_outputs(tex, volume_product(), spec, dir);

  ASSERT_EQ(files.size(), spec.formats.size());
  const std::vector<std::string> names = output_files(spec);
  for (size_t i = 0; i < files.size(); ++i) {
    SCOPED_TRACE(names[i]);
    EXPECT_EQ(files[i].path, names[i]);
    EXPECT_EQ(files[i].format, spec.formats[i]);
    EXPECT_FALSE(files[i].encoding.empty());
    // The record describes the file under its final name.
    const FileStat st = stat_file(dir / names[i]);
    ASSERT_TRUE(st.exists && st.regular);
    EXPECT_EQ(files[i].size, st.size);
    EXPECT_EQ(files[i].hash, hash_file(dir / names[i]));
  }
  for (const char* name : {"volume.exr", "volume.dds", "volume.vdb"}) {
    const LoadedTexture back = read_texture_file((dir / name).string());
    expect_same_texels(back.texture, tex, name);
  }
  EXPECT_TRUE(temporaries(dir).empty());
  EXPECT_EQ(test::list_files(dir), (std::vector<std::string>{"volume.dds", "volume.exr",
                                                             "volume.preview.png", "volume.vdb"}));
}

TEST(OutputWriter, ExrCompressionIsTheOutputsOwn) {
  const fs::path dir = test::fresh_dir("output_writer_exr_compression");
  const Texture tex = rgba_volume();
  for (const char* compression : {"none", "zip", "zips", "piz"}) {
    OutputSpec spec = spec_of(compression, {"exr"});
    spec.options["exr_compression"] = compression;
    write_outputs(tex, volume_product(), spec, dir);
    const std::string path = (dir / (std::string(compression) + ".exr")).string();
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().get_string_attribute("compression"), compression);
    expect_same_texels(read_texture_file(path).texture, tex, path);
  }
}

TEST(OutputWriter, ExrCompressionDefaultsToTheProducts) {
  // docs/formats.md "EXR": zip for the maps, none for the float32
  // atmosphere tables and the tileable noises, whose texels zip barely shrinks.
  const fs::path dir = test::fresh_dir("output_writer_exr_default");
  const Texture tex = rgba_volume();
  for (const auto& [product, compression] :
       {std::pair<const char*, const char*>{"weather", "zip"},
        {"aerial_perspective", "none"},
        {"scattering", "none"},
        {"noise_shape", "none"},
        {"noise_detail", "none"}}) {
    const ProductInfo* info = find_product(product);
    ASSERT_NE(info, nullptr) << product;
    OutputSpec spec = spec_of(product, {"exr"});
    spec.product = product;
    write_outputs(tex, *info, spec, dir);
    const std::string path = (dir / (std::string(product) + ".exr")).string();
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().get_string_attribute("compression"), compression) << product;
    expect_same_texels(read_texture_file(path).texture, tex, path);
  }
}

// OpenVDB's record of how a file's first grid was compressed ("blosc +
// active values", "active values", ...), read by OpenVDB itself.
std::string vdb_file_compression(const std::string& path) {
  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
  file.close();
  if (!grids || grids->empty()) return "no grid";
  const auto meta = (*grids)[0]->getMetadata<openvdb::StringMetadata>("file_compression");
  return meta ? meta->value() : "none recorded";
}

TEST(OutputWriter, VdbCompressionIsTheOutputsOrTheProducts) {
  // docs/formats.md "VDB": Blosc for the tables, none for the tileable
  // noises; an output's vdb_compression wins. The active mask always.
  const fs::path dir = test::fresh_dir("output_writer_vdb_compression");
  const Texture tex = rgba_volume();
  struct Case {
    const char* product;
    const char* option;  // "" for the default
    const char* expected;
  };
  for (const Case& c : {Case{"aerial_perspective", "", "blosc + active values"},
                        Case{"noise_shape", "", "active values"},
                        Case{"noise_shape", "blosc", "blosc + active values"},
                        Case{"aerial_perspective", "zip", "zip + active values"},
                        Case{"aerial_perspective", "none", "active values"}}) {
    const std::string name = std::string(c.product) + "_" + (*c.option ? c.option : "default");
    OutputSpec spec = spec_of(name, {"vdb"});
    spec.product = c.product;
    if (*c.option) spec.options["vdb_compression"] = c.option;
    write_outputs(tex, *find_product(c.product), spec, dir);
    const std::string path = (dir / (name + ".vdb")).string();
    EXPECT_EQ(vdb_file_compression(path), c.expected) << name;
    expect_same_texels(read_texture_file(path).texture, tex, path);
  }
}

TEST(OutputWriter, HalfPrecisionIsWithinHalfRounding) {
  const fs::path dir = test::fresh_dir("output_writer_half");
  const Texture tex = rgba_volume();
  OutputSpec spec = spec_of("half", {"exr", "dds"});
  spec.precision = "half";
  write_outputs(tex, volume_product(), spec, dir);
  for (const char* name : {"half.exr", "half.dds"}) {
    const Texture back = read_texture_file((dir / name).string()).texture;
    ASSERT_EQ(back.data.size(), tex.data.size()) << name;
    for (size_t i = 0; i < tex.data.size(); ++i)
      ASSERT_LE(std::abs(back.data[i] - tex.data[i]), std::ldexp(std::abs(tex.data[i]), -11))
          << name << " value " << i;
  }
}

TEST(OutputWriter, AFailingFormatLeavesNoFileOfThatOutput) {
  // R8_UNORM holds one channel: the DDS of an RGBA texture is refused, after
  // the EXR before it in the list was already written to its temporary.
  const fs::path dir = test::fresh_dir("output_writer_failure");
  OutputSpec spec = spec_of("broken", {"exr", "vdb", "dds"});
  spec.options["dds_format"] = "R8_UNORM";
  EXPECT_THROW(write_outputs(rgba_volume(), volume_product(), spec, dir), IoError);
  EXPECT_TRUE(test::list_files(dir).empty()) << "first file: " << test::list_files(dir).front();
}

TEST(OutputWriter, ANonFiniteTextureIsRefusedOnceForEveryFormatNamingTheFirst) {
  // The writers leave check_finite to write_outputs (once per texture): a
  // NaN is still refused before any file, named by the first format's file
  // and its texel, whichever format comes first.
  Texture tex = rgba_volume();
  tex.at(5, 2, 1, 0, 2) = std::nanf("");
  for (const std::vector<std::string>& formats :
       {std::vector<std::string>{"dds", "exr", "vdb", "png"},
        std::vector<std::string>{"png", "vdb", "exr", "dds"},
        std::vector<std::string>{"vdb", "dds"}}) {
    const fs::path dir = test::fresh_dir("output_writer_non_finite");
    const std::string first = output_files(spec_of("table", formats)).front();
    try {
      write_outputs(tex, volume_product(), spec_of("table", formats), dir);
      ADD_FAILURE() << "a NaN was written as " << first;
    } catch (const IoError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find((dir / first).string()), std::string::npos) << what;
      EXPECT_NE(what.find("non-finite value (nan) at texel x=5 y=2 z=1 layer=0 channel B"),
                std::string::npos)
          << what;
    }
    EXPECT_TRUE(test::list_files(dir).empty()) << "first file: " << test::list_files(dir).front();
  }
}

TEST(OutputWriter, AFailingFormatLeavesTheOldVersionWhole) {
  // An output written before, then re-written with a format that fails: the
  // old files stay as they were, none replaced by the new version.
  const fs::path dir = test::fresh_dir("output_writer_old_version");
  const Texture old_tex = rgba_volume();
  const std::vector<ManifestFile> old_files =
      write_outputs(old_tex, volume_product(), spec_of("table", {"exr", "dds"}), dir);

  Texture new_tex = old_tex;
  for (float& v : new_tex.data) v *= 2.0f;
  OutputSpec spec = spec_of("table", {"exr", "dds"});
  spec.options["dds_format"] = "R8_UNORM";
  EXPECT_THROW(write_outputs(new_tex, volume_product(), spec, dir), IoError);

  for (const ManifestFile& f : old_files) {
    EXPECT_EQ(stat_file(dir / f.path).size, f.size) << f.path;
    EXPECT_EQ(hash_file(dir / f.path), f.hash) << f.path;
  }
  EXPECT_TRUE(temporaries(dir).empty());
  EXPECT_EQ(test::list_files(dir), (std::vector<std::string>{"table.dds", "table.exr"}));
}

}  // namespace
}  // namespace skybake
