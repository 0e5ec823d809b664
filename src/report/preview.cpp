#include "report/preview.hpp"

#include <fmt/format.h>

#include "atmosphere/sky_preview.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/png_preview.hpp"
#include "pipeline/product_options.hpp"

namespace fs = std::filesystem;

namespace skybake {

PreviewSetup PreviewSetup::full() {
  return {{320, 180}};
}

PreviewSetup PreviewSetup::quick() {
  return {{160, 90}};
}

nlohmann::json sky_preview_report(const ReportInputs& in, const PreviewSetup& setup) {
  in.stage("sky preview");
  SkyPreviewSpec spec;
  spec.width = setup.preview_size.at(0);
  spec.height = setup.preview_size.at(1);
  if (const OutputSpec* o = in.scene.find_output("sky_preview"))
    spec.camera_altitude_m =
        option_double(*o, "camera_altitude_km", spec.camera_altitude_m * 1e-3) * 1e3;
  const Texture picture = bake_sky_preview(in.scene.atmosphere, in.transmittance,
                                           in.multiscattering, spec, BakeContext{});
  create_folder(in.folder);
  const std::string name = "sky_preview.png";
  AtomicFile file(in.folder / name);
  PreviewOptions options;
  options.exposure = 1.0;  // the preview is display-referred already
  // Errors name sky_preview.png, not its temporary.
  file.write([&](const fs::path& temp) { write_png_preview(temp.string(), picture, options); });
  file.commit();
  return name;
}

}  // namespace skybake
