// The points at which a baked table is read to measure its error, shared by
// the bake's measurement (pipeline/error_measures.hpp) and the ladders of
// `skybake report` (report/*.cpp, docs/report.md "What is measured"): point
// i of a table hashes (i, the table's own coordinates, core/error_stats.hpp
// query_unit), so it is the same in any run and for any thread count, and
// the bake's n points are the first n of the report's. Each function says
// how its points are spread over the table's domain.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/aerial_perspective_lut.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/skyview_lut.hpp"

namespace skybake {

struct RadiusCosine {
  double r = 0.0;   // radius, m
  double mu = 0.0;  // a zenith cosine (view or sun, as the table's axis)
};

// Transmittance: uniform in the table's own unit square (x_mu, x_r) of
// transmittance_lut.hpp, dense near the ground and the horizon where T
// changes fastest, the way the table samples it.
RadiusCosine transmittance_query(const Atmosphere& atm, size_t index);

// Multiple scattering: altitude uniform over the shell, sun zenith cosine
// uniform in [-1, 1] (the table's axes, linear in both).
RadiusCosine multiscattering_query(const Atmosphere& atm, size_t index);

// Sky view: layer uniform over `views`, view direction uniform on the sphere
// (below the horizon the table holds the in-scattering up to the ground).
struct SkyviewQueryPoint {
  int layer = 0;
  double r = 0.0;  // the layer's viewer radius
  SkyviewDirection view;
};
SkyviewQueryPoint skyview_query(const Atmosphere& atm, const std::vector<SkyviewView>& views,
                                size_t index);

// Aerial perspective: screen position uniform, distance uniform between the
// camera and the nearer of the depth range and the ground along that ray (an
// engine reads the volume at the depth of a visible surface).
struct AerialQueryPoint {
  glm::dvec2 screen_uv{0.0};
  double distance_m = 0.0;
  glm::dvec3 position{0.0};  // the camera, planet-centred (local frame, z up)
  glm::dvec3 view_dir{0.0};
};
AerialQueryPoint aerial_query(const Atmosphere& atm, const AerialPerspectiveSpec& spec,
                              size_t index);

// A view of the precomputed-scattering tables (scattering, single_mie,
// scattering3d): altitude top * u^2 (terrain sits low), mu uniform in
// [-1, 1], mu_s uniform in [mu_s_min, 1], the sun's azimuth around the view
// uniform in [0, 2 pi) and the nu it gives; hashed from query_unit(index,
// first_dim .. first_dim + 3), so each table keeps its own points.
struct ViewQuery {
  double altitude_m = 0.0, r = 0.0, mu = 0.0, mu_s = 0.0, nu = 0.0;
  bool hits_ground = false;
};
ViewQuery view_query(const Atmosphere& atm, size_t index, uint32_t first_dim, double mu_s_min);
// The first coordinate of each table's view queries.
constexpr uint32_t kScatteringQueryDim = 40;
constexpr uint32_t kSingleMieQueryDim = 50;
constexpr uint32_t kScattering3dQueryDim = 70;

// cos of the angle between a view of zenith cosine mu and a sun of zenith
// cosine mu_s, phi apart in azimuth.
double nu_from_azimuth(double mu, double mu_s, double phi);

// Ground irradiance: altitude top * u^2, mu_s uniform in [mu_s_min, 1] (of
// the 4D table whose sky it integrates; below it that sky is clamped).
RadiusCosine irradiance_query(const Atmosphere& atm, size_t index, double mu_s_min);

// Gathering LUT: uniform in the table's own unit square (x_h, x_mu_s) of
// scattering3d_lut.hpp, whatever its size (the bake's measurement; the
// report's gathering ladder reads the texel centres of a finer table).
struct AltitudeSunCosine {
  double h = 0.0;     // altitude, m
  double mu_s = 0.0;  // sun zenith cosine
};
AltitudeSunCosine gathering_query(const Atmosphere& atm, size_t index);

}  // namespace skybake
