#include "report/setup.hpp"

#include "core/error.hpp"
#include "pipeline/product_graph.hpp"

namespace skybake {

ReportLevel ReportLevel::full() {
  ReportLevel l;
  l.name = "full";
  l.min_timing_seconds = 0.05;
  l.transmittance_steps = {5, 10, 20, 40, 80};
  l.transmittance_sizes = {{64, 16}, {128, 32}, {256, 64}, {512, 128}};
  l.transmittance_queries = 4096;
  l.quadrature_tolerance = 1e-9;
  l.multiscattering_directions = {16, 64, 256};
  l.multiscattering_steps = {10, 20, 40};
  l.multiscattering_sizes = {{32, 32}, {64, 64}};
  l.multiscattering_queries = 128;
  l.multiscattering_reference_directions = 2048;
  l.multiscattering_reference_steps = 200;
  l.skyview_steps = {8, 15, 30, 60};
  l.skyview_sizes = {{96, 54}, {192, 108}, {384, 216}};
  l.skyview_queries = 1024;
  l.skyview_reference_steps = 2000;
  l.single_scattering_tolerance = 1e-6;
  l.aerial_steps = {1, 2, 4, 8};
  l.aerial_depths = {16, 32, 64};
  l.aerial_queries = 2048;
  l.aerial_reference_steps = 2000;
  l.scattering_shapes = {{8, 32, 8, 4}, {16, 64, 16, 8}, {32, 128, 32, 8}, {32, 256, 32, 16}};
  l.scattering_ray_nodes = {15, 30, 51, 99};
  l.scattering_queries = 1024;
  l.single_mie_shapes = l.scattering_shapes;
  l.single_mie_ray_nodes = l.scattering_ray_nodes;
  l.single_mie_queries = 1024;
  l.irradiance_sizes = {{16, 4}, {32, 8}, {64, 16}, {128, 32}};
  l.irradiance_directions = {8, 16, 32, 64};
  l.irradiance_queries = 256;
  l.irradiance_reference_tolerance = 1e-4;
  l.scattering3d_shapes = {{8, 32, 8}, {16, 64, 16}, {32, 128, 32}, {64, 256, 64}};
  l.scattering3d_ray_nodes = {15, 30, 51, 99};
  l.scattering3d_queries = 1024;
  l.scattering3d_reference_azimuths = 32;
  l.gathering_shapes = {{8, 32, 8}, {16, 64, 16}, {32, 128, 32}};
  l.gathering_directions = {4, 8, 16, 32};
  l.gathering_queries = 512;
  l.gathering_reference_shape = {64, 256, 64};
  l.gathering_reference_directions = 64;
  l.gathering_reference_ray_nodes = 99;
  l.reference_transmittance_size = {1024, 256};
  l.reference_transmittance_steps = 200;
  l.sun_elevations_deg = {60.0, 20.0, 5.0};
  l.view_elevations_deg = {5.0, 20.0, 60.0};
  l.view_azimuths = 8;
  l.path_samples = 65536;
  l.path_samples_single = 16384;
  l.bruneton_shape = {32, 128, 32, 8};
  l.bruneton_tolerance = 1e-3;
  l.bruneton_max_orders = 100;
  l.preview_width = 320;
  l.preview_height = 180;
  return l;
}

ReportLevel ReportLevel::quick() {
  ReportLevel l = full();
  l.name = "quick";
  l.min_timing_seconds = 0.005;
  l.transmittance_steps = {5, 10, 20, 40};
  l.transmittance_sizes = {{64, 16}, {256, 64}};
  l.transmittance_queries = 512;
  l.quadrature_tolerance = 1e-8;
  l.multiscattering_directions = {16, 64};
  l.multiscattering_steps = {10, 20};
  l.multiscattering_sizes = {};
  l.multiscattering_queries = 24;
  l.multiscattering_reference_directions = 512;
  l.multiscattering_reference_steps = 80;
  l.skyview_steps = {8, 30};
  l.skyview_sizes = {{96, 54}, {192, 108}};
  l.skyview_queries = 128;
  l.skyview_reference_steps = 600;
  l.single_scattering_tolerance = 1e-5;
  l.aerial_steps = {1, 2, 4};
  l.aerial_depths = {16, 32};
  l.aerial_queries = 256;
  l.aerial_reference_steps = 500;
  l.scattering_shapes = {{8, 32, 8, 4}, {16, 64, 16, 8}};
  l.scattering_ray_nodes = {15, 51};
  l.scattering_queries = 64;
  l.single_mie_shapes = l.scattering_shapes;
  l.single_mie_ray_nodes = l.scattering_ray_nodes;
  l.single_mie_queries = 64;
  l.irradiance_sizes = {{16, 4}, {64, 16}};
  l.irradiance_directions = {8, 32};
  l.irradiance_queries = 16;
  l.irradiance_reference_tolerance = 1e-3;
  l.scattering3d_shapes = {{8, 32, 8}, {16, 64, 16}};
  l.scattering3d_ray_nodes = {15, 51};
  l.scattering3d_queries = 64;
  l.scattering3d_reference_azimuths = 16;
  l.gathering_shapes = {{8, 32, 8}, {16, 64, 16}};
  l.gathering_directions = {4, 16};
  l.gathering_queries = 128;
  l.gathering_reference_shape = {48, 192, 48};
  l.gathering_reference_directions = 32;
  l.gathering_reference_ray_nodes = 99;
  l.reference_transmittance_size = {512, 128};
  l.reference_transmittance_steps = 100;
  l.path_samples = 256;
  l.path_samples_single = 256;
  l.bruneton_shape = {16, 64, 16, 4};
  l.bruneton_orders = 4;
  l.bruneton_tolerance = 0.0;
  l.preview_width = 160;
  l.preview_height = 90;
  return l;
}

nlohmann::json level_json(const ReportLevel& l) {
  return {{"name", l.name},
          {"min_timing_seconds", l.min_timing_seconds},
          {"transmittance_steps", l.transmittance_steps},
          {"transmittance_sizes", l.transmittance_sizes},
          {"transmittance_queries", l.transmittance_queries},
          {"quadrature_tolerance", l.quadrature_tolerance},
          {"multiscattering_directions", l.multiscattering_directions},
          {"multiscattering_steps", l.multiscattering_steps},
          {"multiscattering_sizes", l.multiscattering_sizes},
          {"multiscattering_queries", l.multiscattering_queries},
          {"multiscattering_reference_directions", l.multiscattering_reference_directions},
          {"multiscattering_reference_steps", l.multiscattering_reference_steps},
          {"skyview_steps", l.skyview_steps},
          {"skyview_sizes", l.skyview_sizes},
          {"skyview_queries", l.skyview_queries},
          {"skyview_reference_steps", l.skyview_reference_steps},
          {"single_scattering_tolerance", l.single_scattering_tolerance},
          {"aerial_steps", l.aerial_steps},
          {"aerial_depths", l.aerial_depths},
          {"aerial_queries", l.aerial_queries},
          {"aerial_reference_steps", l.aerial_reference_steps},
          {"scattering_shapes", l.scattering_shapes},
          {"scattering_ray_nodes", l.scattering_ray_nodes},
          {"scattering_queries", l.scattering_queries},
          {"single_mie_shapes", l.single_mie_shapes},
          {"single_mie_ray_nodes", l.single_mie_ray_nodes},
          {"single_mie_queries", l.single_mie_queries},
          {"irradiance_sizes", l.irradiance_sizes},
          {"irradiance_directions", l.irradiance_directions},
          {"irradiance_queries", l.irradiance_queries},
          {"irradiance_reference_tolerance", l.irradiance_reference_tolerance},
          {"scattering3d_shapes", l.scattering3d_shapes},
          {"scattering3d_ray_nodes", l.scattering3d_ray_nodes},
          {"scattering3d_queries", l.scattering3d_queries},
          {"scattering3d_reference_azimuths", l.scattering3d_reference_azimuths},
          {"gathering_shapes", l.gathering_shapes},
          {"gathering_directions", l.gathering_directions},
          {"gathering_queries", l.gathering_queries},
          {"gathering_reference_shape", l.gathering_reference_shape},
          {"gathering_reference_directions", l.gathering_reference_directions},
          {"gathering_reference_ray_nodes", l.gathering_reference_ray_nodes},
          {"reference_transmittance_size", l.reference_transmittance_size},
          {"reference_transmittance_steps", l.reference_transmittance_steps},
          {"sun_elevations_deg", l.sun_elevations_deg},
          {"view_elevations_deg", l.view_elevations_deg},
          {"view_azimuths", l.view_azimuths},
          {"path_samples", l.path_samples},
          {"path_samples_single", l.path_samples_single},
          {"bruneton_shape", l.bruneton_shape},
          {"bruneton_orders", l.bruneton_orders},
          {"bruneton_tolerance", l.bruneton_tolerance},
          {"bruneton_max_orders", l.bruneton_max_orders},
          {"preview_size", {l.preview_width, l.preview_height}}};
}

OutputSpec operating_spec(const Scene& scene, const std::string& product) {
  if (const OutputSpec* spec = scene.find_output(product)) return *spec;
  const ProductInfo* info = find_product(product);
  if (!info) throw Error("report: unknown product " + product);
  return default_spec(*info);
}

}  // namespace skybake
