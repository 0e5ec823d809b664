// Research tool, not part of the product: where the 4D table's error on the
// report's 72 sky views comes from (docs/report.md "Where the 4D table's
// error on Mars comes from"). One factor at a time: the table is baked and
// read with one setting changed, against the same path-traced references
// (the report's views, camera and seeds), and the worst channel's denoised
// relative RMSE and the bias per channel are printed for each.
//
//   build/bench/orders_4d_study PRESET CACHE_DIR [PATHS] [ROWS]
//        PATHS: path tracer paths per channel and view (default 65536, the
//        report's); references are cached in CACHE_DIR per (albedo, paths,
//        seed set). ROWS: comma-separated subset of the row groups (default
//        all): base, nu, bands, shape, single, ground, noise, order2, views,
//        hg, fix (finer mu_s and nu), axes (one axis of 32x128x32x8 halved), fine (one axis of
//        32x128x32x16 doubled).
//
// Readings of one baked table (single Mie from its own texture):
//   p_R       orders >= 2 stored / p_R(slice nu), read x p_R(nu): Bruneton's
//             convention (scattering_orders.hpp, "Storage of orders >= 2");
//   undivided orders >= 2 stored as radiance, lerped in nu;
//   p_M       stored / p_M(the texel's clamped nu), read x p_M(nu).
// A table of 29 nu slices read through every 4th slice has the 8-slice
// table's storage with the 29-slice iteration behind it: it separates the
// storage's nu interpolation from the iteration's own nu resolution.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "atmosphere/geometry.hpp"
#include "atmosphere/phase.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "reference/atmosphere_quadrature.hpp"
#include "reference/path_tracer.hpp"
#include "report/setup.hpp"
#include "report/sky_radiance.hpp"

using namespace skybake;

namespace {

struct StudyView {
  glm::dvec3 dir, sun;
  double mu, mu_s, nu;
};

std::vector<StudyView> study_views(const SkyRadianceCamera& cam, const std::vector<double>& suns) {
  std::vector<StudyView> out;
  for (double s : suns)
    for (const glm::dvec3& d : cam.dirs) {
      const glm::dvec3 sun = sky_radiance_sun(s);
      out.push_back({d, sun, d.z, sun.z, clamp_cosine(glm::dot(d, sun))});
    }
  return out;
}

struct References {
  std::vector<glm::dvec3> mean, ci95;
};

// Set 0 has the report's seeds (sky_radiance.cpp: 3 x view index + 1).
References study_references(const Atmosphere& atm, const SkyRadianceCamera& cam,
                            const std::vector<StudyView>& views, int paths, int set,
                            const std::filesystem::path& cache, int bounces = 0) {
  const glm::dvec3 a = atm.ground_albedo;
  const std::filesystem::path file =
      cache / fmt::format("ref_{:.3f}_{:.3f}_{:.3f}_p{}_s{}.json", a.x, a.y, a.z, paths, set);
  References r;
  if (std::filesystem::exists(file)) {
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    for (const auto& v : j["mean"]) r.mean.push_back({v[0], v[1], v[2]});
    for (const auto& v : j["ci95"]) r.ci95.push_back({v[0], v[1], v[2]});
    return r;
  }
  const SkyPathTracer tracer(atm);
  r.mean.resize(views.size()), r.ci95.resize(views.size());
  tbb::parallel_for(size_t(0), views.size(), [&](size_t v) {
    PathTracerSpec spec;
    spec.samples = paths;
    spec.max_bounces = bounces > 0 ? bounces : sky_radiance_max_bounces(atm);
    spec.seed = 3 * v + 1 + uint64_t(set) * 1000003ull;
    const RadianceEstimate e = tracer.trace(cam.position, views[v].dir, views[v].sun, spec);
    r.mean[v] = e.mean, r.ci95[v] = e.ci95;
  });
  nlohmann::json j;
  for (size_t v = 0; v < views.size(); ++v) {
    j["mean"].push_back({r.mean[v].x, r.mean[v].y, r.mean[v].z});
    j["ci95"].push_back({r.ci95[v].x, r.ci95[v].y, r.ci95[v].z});
  }
  std::ofstream(file) << j.dump();
  return r;
}

struct StudyTable {
  BrunetonTextures t;
  Texture multiple;  // sum of the orders >= 2 at each texel, radiance
  double seconds = 0.0;
};

StudyTable study_bake(const Atmosphere& atm, const Texture& transmittance,
                      const BrunetonSpec& spec) {
  StudyTable s;
  const auto t0 = std::chrono::steady_clock::now();
  s.t = bake_bruneton(atm, transmittance, spec, BakeContext{});
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ScatteringShape& shape = s.t.shape;
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  s.multiple = Texture(s.t.single_mie.width, s.t.single_mie.height, s.t.single_mie.depth, 1,
                       {"R", "G", "B"});
  for (int z = 0; z < shape.r_size; ++z)
    for (int y = 0; y < shape.mu_size; ++y)
      for (int x = 0; x < shape.texture_width(); ++x) {
        const double p_r = phases.rayleigh(texels.nu[size_t(x / shape.mu_s_size)]);
        for (int c = 0; c < 3; ++c)
          s.multiple.texel(x, y, z)[c] =
              float((double(s.t.scattering.texel(x, y, z)[c]) - s.t.single_rayleigh.texel(x, y, z)[c]) * p_r);
      }
  return s;
}

// Every step-th nu slice of a packed table.
Texture every_nth_slice(const Texture& t, const ScatteringShape& from, int step,
                        ScatteringShape& to) {
  to = from;
  to.nu_size = (from.nu_size - 1) / step + 1;
  Texture out(to.texture_width(), t.height, t.depth, 1, {"R", "G", "B"});
  for (int z = 0; z < t.depth; ++z)
    for (int y = 0; y < t.height; ++y)
      for (int m = 0; m < to.nu_size; ++m)
        for (int l = 0; l < to.mu_s_size; ++l)
          for (int c = 0; c < 3; ++c)
            out.texel(m * to.mu_s_size + l, y, z)[c] =
                t.texel(m * step * from.mu_s_size + l, y, z)[c];
  return out;
}

// How orders >= 2 are stored and read back: stored / divisor(texel), read x factor(nu).
struct Storage {
  std::string name;
  std::function<double(const ScatteringParams& p, double slice_nu)> divisor;
  std::function<double(double nu)> factor;
};

std::vector<Storage> storages(const ScatteringPhases& phases) {
  return {{"p_R", [&](const ScatteringParams&, double nu) { return phases.rayleigh(nu); },
           [&](double nu) { return phases.rayleigh(nu); }},
          {"undivided", [](const ScatteringParams&, double) { return 1.0; },
           [](double) { return 1.0; }},
          {"p_M", [&](const ScatteringParams& p, double) { return phases.mie(p.nu); },
           [&](double nu) { return phases.mie(nu); }}};
}

// Orders >= 2 stored / HG(g, the texel's clamped nu), read x HG(g, nu).
Storage hg_storage(double g) {
  return {fmt::format("HG {:.2f}", g),
          [g](const ScatteringParams& p, double) { return henyey_greenstein_phase(p.nu, g); },
          [g](double nu) { return henyey_greenstein_phase(nu, g); }};
}

// The views read from single tables (phases after the lerp) plus the
// orders >= 2 stored the given way, at the camera's radius r.
std::vector<glm::dvec3> study_read(const Atmosphere& atm, const ScatteringShape& shape,
                                   const Texture& single_r, const Texture& single_m,
                                   const Texture& multiple, const Storage& storage, double r,
                                   const std::vector<StudyView>& views) {
  const ScatteringPhases phases = scattering_phases(atm);
  const ScatteringTexelGrid texels = scattering_texel_grid(atm, shape);
  Texture stored = multiple;
  for (int z = 0; z < shape.r_size; ++z)
    for (int y = 0; y < shape.mu_size; ++y)
      for (int x = 0; x < shape.texture_width(); ++x) {
        const double d = storage.divisor(texels.params(x, y, z), texels.nu[size_t(x / shape.mu_s_size)]);
        for (int c = 0; c < 3; ++c) stored.texel(x, y, z)[c] = float(multiple.texel(x, y, z)[c] / d);
      }
  std::vector<glm::dvec3> out;
  for (const StudyView& v : views) {
    const bool hits = ray_intersects_ground(atm.bottom_radius_m, r, v.mu);
    const ScatteringTaps taps = scattering_taps(
        shape, scattering_uvwz_from_r_mu_mu_s_nu(atm, shape, r, v.mu, v.mu_s, v.nu, hits));
    out.push_back(phases.rayleigh(v.nu) * read_scattering(single_r, shape, taps) +
                  phases.mie(v.nu) * read_scattering(single_m, shape, taps) +
                  storage.factor(v.nu) * read_scattering(stored, shape, taps));
  }
  return out;
}

// Orders >= 2 alone, read the given way (single set to zero).
std::vector<glm::dvec3> study_read_multiple(const Atmosphere& atm, const ScatteringShape& shape,
                                            const Texture& multiple, const Storage& storage,
                                            double r, const std::vector<StudyView>& views) {
  Texture zero = multiple;
  std::fill(zero.data.begin(), zero.data.end(), 0.0f);
  return study_read(atm, shape, zero, zero, multiple, storage, r, views);
}

void print_row(const std::string& name, const std::vector<glm::dvec3>& lut, const References& ref,
               double seconds, int orders, std::ofstream& csv) {
  std::vector<RadiancePair> rows;
  for (size_t v = 0; v < lut.size(); ++v) rows.push_back({lut[v], ref.mean[v], ref.ci95[v], ref.mean[v]});
  const nlohmann::json s = radiance_stats(rows);
  std::string per;
  for (const auto& ch : s["channels"])
    per += fmt::format(" {:6.2f}/{:+6.2f}", 100.0 * ch["rel_rmse_denoised"].get<double>(),
                       100.0 * ch["rel_bias"].get<double>());
  std::printf("%-34s worst %6.2f %%  R/G/B denoised/bias %%%s  noise %.2f %%  %.1f s  %d orders\n",
              name.c_str(), 100.0 * s["worst"]["rel_rmse_denoised"].get<double>(), per.c_str(),
              100.0 * s["worst"]["noise_rel_rms"].get<double>(), seconds, orders);
  std::fflush(stdout);
  csv << "\"" << name << "\"," << s["worst"]["rel_rmse_denoised"].get<double>();
  for (const auto& ch : s["channels"])
    csv << "," << ch["rel_rmse_denoised"].get<double>() << "," << ch["rel_bias"].get<double>();
  csv << "," << s["worst"]["noise_rel_rms"].get<double>() << "," << seconds << "," << orders << "\n";
}

// What every group of rows reads: the scene, its views and references.
struct Study {
  Scene scene;
  std::filesystem::path cache;
  int paths = 65536;
  SkyRadianceCamera cam;
  std::vector<StudyView> views;
  double r = 0.0;
  Texture transmittance;
  References ref;
  ScatteringPhases phases;
  std::vector<Storage> store;
  std::ofstream csv;
  BrunetonSpec base;  // the report's full table (report/bruneton.cpp), Mie separate

  const Atmosphere& atm() const { return scene.atmosphere; }
  std::vector<glm::dvec3> read(const StudyTable& s, const Storage& st, const Atmosphere& a) {
    return study_read(a, s.t.shape, s.t.single_rayleigh, s.t.single_mie, s.multiple, st, r, views);
  }
  // One bake read every way of `store`, against `against`.
  StudyTable run(const std::string& name, const BrunetonSpec& spec, const References& against,
                 const Atmosphere& a) {
    StudyTable s = study_bake(a, transmittance, spec);
    for (const Storage& st : store)
      print_row(name + " " + st.name, read(s, st, a), against, s.seconds, s.t.orders_used, csv);
    return s;
  }
  StudyTable run(const std::string& name, const BrunetonSpec& spec) {
    return run(name, spec, ref, atm());
  }
  void print(const std::string& name, const StudyTable& s, const Storage& st) {
    print_row(name + " " + st.name, read(s, st, atm()), ref, s.seconds, s.t.orders_used, csv);
  }
  Atmosphere black_ground() const {
    Atmosphere a = atm();
    a.ground_albedo = glm::dvec3(0.0);
    return a;
  }
};

void base_rows(Study& st, bool single, bool noise) {
  const StudyTable s = st.run("32x128x32x8", st.base);
  if (single) {
    // Single scattering from adaptive quadrature: the single tables' share.
    std::vector<glm::dvec3> lut =
        study_read_multiple(st.atm(), s.t.shape, s.multiple, st.store[0], st.r, st.views);
    for (size_t v = 0; v < st.views.size(); ++v)
      lut[v] += reference_single_scattering(st.atm(), st.cam.position, st.views[v].dir,
                                            st.views[v].sun, 1e-6)
                    .value;
    print_row("32x128x32x8 p_R, single by quadrature", lut, st.ref, s.seconds, s.t.orders_used,
              st.csv);
  }
  if (noise) {
    const References other = study_references(st.atm(), st.cam, st.views, st.paths, 1, st.cache);
    print_row("32x128x32x8 p_R vs seed set 1", st.read(s, st.store[0], st.atm()), other, s.seconds,
              s.t.orders_used, st.csv);
    print_row("seed set 1 vs seed set 0 (noise x sqrt 2)", other.mean, st.ref, 0.0, 0, st.csv);
  }
}

// Orders 1 and 2 alone over a black ground, against the path tracer limited
// to two vertices: the second order's own error.
void order2_rows(Study& st) {
  const Atmosphere black = st.black_ground();
  const References ref2 = study_references(black, st.cam, st.views, st.paths, 2, st.cache, 2);
  BrunetonSpec spec = st.base;
  spec.tolerance = 0.0, spec.orders = 2;
  st.run("32x128x32x8 orders 1-2, black ground", spec, ref2, black);
  spec.nu_size = 29;
  st.run("32x128x32x29 orders 1-2, black ground", spec, ref2, black);
  spec.nu_size = 8, spec.density_directions = 32;
  st.run("32x128x32x8 bands 32 orders 1-2, black", spec, ref2, black);
}

// Each view's relative error, the share of orders >= 2 and the reference's noise.
void view_rows(Study& st) {
  const StudyTable s = study_bake(st.atm(), st.transmittance, st.base);
  const std::vector<glm::dvec3> lut = st.read(s, st.store[0], st.atm());
  const std::vector<glm::dvec3> m =
      study_read_multiple(st.atm(), s.t.shape, s.multiple, st.store[0], st.r, st.views);
  std::printf("sun elev az  nu   (L-X)/X R G B %%   multiple share B   se B %%\n");
  for (size_t v = 0; v < st.views.size(); ++v) {
    const StudyView& w = st.views[v];
    const glm::dvec3 e = (lut[v] - st.ref.mean[v]) / st.ref.mean[v];
    std::printf("%4.0f %4.0f %4.0f %5.2f  %+6.1f %+6.1f %+6.1f   %5.2f   %4.1f\n",
                std::asin(w.sun.z) / kDeg, std::asin(w.dir.z) / kDeg,
                std::atan2(w.dir.y, w.dir.x) / kDeg, w.nu, 100 * e.x, 100 * e.y, 100 * e.z,
                m[v].z / lut[v].z, 100 * st.ref.ci95[v].z / 1.96 / st.ref.mean[v].z);
  }
}

void nu_rows(Study& st) {
  BrunetonSpec spec = st.base;
  spec.nu_size = 16;
  st.run("32x128x32x16", spec);
  spec.nu_size = 29;
  const StudyTable s = st.run("32x128x32x29", spec);
  ScatteringShape as8;
  const Texture sr = every_nth_slice(s.t.single_rayleigh, s.t.shape, 4, as8);
  const Texture sm = every_nth_slice(s.t.single_mie, s.t.shape, 4, as8);
  const Texture m = every_nth_slice(s.multiple, s.t.shape, 4, as8);
  for (const Storage& storage : st.store)
    print_row("32x128x32x29 read as 8 slices " + storage.name,
              study_read(st.atm(), as8, sr, sm, m, storage, st.r, st.views), st.ref, s.seconds,
              s.t.orders_used, st.csv);
}

void shape_rows(Study& st) {
  BrunetonSpec spec = st.base;
  spec.r_size = 16, spec.mu_size = 64, spec.mu_s_size = 16;
  st.run("16x64x16x8", spec);
  const double ratio = st.atm().bottom_radius_m / st.atm().top_radius_m;
  spec.mu_s_min = std::max(-0.99, -safe_sqrt(1.0 - ratio * ratio) - 0.1);
  st.run("16x64x16x8 converged mu_s_min", spec);
}

// Divided by a lobe between Rayleigh's and Mie's; and the finer sun and nu axes.
void divisor_rows(Study& st, bool hg, bool fix) {
  for (int nu : {8, 16}) {
    if (hg) {
      BrunetonSpec spec = st.base;
      spec.nu_size = nu;
      const StudyTable s = study_bake(st.atm(), st.transmittance, spec);
      for (double g : {0.2, 0.4, 0.6, 0.7})
        st.print(fmt::format("32x128x32x{}", nu), s, hg_storage(g));
    }
    if (fix) {
      BrunetonSpec spec = st.base;
      spec.mu_s_size = 64, spec.nu_size = nu;
      const StudyTable s = st.run(fmt::format("32x128x64x{}", nu), spec);
      st.print(fmt::format("32x128x64x{}", nu), s, hg_storage(0.2));
    }
  }
}

// One axis halved from the report's table, or doubled from its 16-slice twin.
void axis_rows(Study& st, bool halved, bool doubled) {
  for (int axis = 0; axis < 4; ++axis) {
    BrunetonSpec spec = st.base;
    int* sizes[4] = {&spec.r_size, &spec.mu_size, &spec.mu_s_size, &spec.density_directions};
    if (halved && axis < 3) {
      *sizes[axis] /= 2;
      st.run(fmt::format("{}x{}x{}x8", spec.r_size, spec.mu_size, spec.mu_s_size), spec);
    }
    if (doubled) {
      spec = st.base;
      spec.nu_size = 16;
      int* fine[4] = {&spec.r_size, &spec.mu_size, &spec.mu_s_size, &spec.density_directions};
      *fine[axis] *= 2;
      st.run(fmt::format("{}x{}x{}x16 bands {}", spec.r_size, spec.mu_size, spec.mu_s_size,
                         spec.density_directions),
             spec);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: orders_4d_study PRESET CACHE_DIR [PATHS] [ROWS]\n");
    return 2;
  }
  Study st;
  st.scene = load_scene(argv[1]);
  st.cache = argv[2];
  std::filesystem::create_directories(st.cache);
  st.paths = argc > 3 ? std::stoi(argv[3]) : 65536;
  std::set<std::string> groups;
  if (argc > 4) {
    std::stringstream ss(argv[4]);
    for (std::string g; std::getline(ss, g, ',');) groups.insert(g);
  }
  auto wanted = [&](const char* g) { return groups.empty() || groups.count(g) > 0; };
  const SkyRadianceSetup setup = SkyRadianceSetup::full();
  st.cam = sky_radiance_camera(st.scene, setup);
  st.views = study_views(st.cam, setup.sun_elevations_deg);
  st.r = glm::length(st.cam.position);
  st.transmittance = bake_transmittance_lut(
      st.atm(), transmittance_spec(operating_spec(st.scene, "transmittance")), BakeContext{});
  st.ref = study_references(st.atm(), st.cam, st.views, st.paths, 0, st.cache);
  st.phases = scattering_phases(st.atm());
  st.store = storages(st.phases);
  st.csv.open(st.cache / "study.csv", std::ios::app);
  st.base.tolerance = 1e-3;
  st.base.combined_mie_alpha = false;
  if (wanted("base") || wanted("single") || wanted("noise"))
    base_rows(st, wanted("single"), wanted("noise"));
  if (wanted("order2")) order2_rows(st);
  if (wanted("views")) view_rows(st);
  if (wanted("nu")) nu_rows(st);
  if (wanted("bands")) {
    BrunetonSpec spec = st.base;
    spec.density_directions = 32;
    st.run("32x128x32x8 density bands 32", spec);
  }
  if (wanted("shape")) shape_rows(st);
  if (wanted("hg") || wanted("fix")) divisor_rows(st, wanted("hg"), wanted("fix"));
  if (wanted("axes") || wanted("fine")) axis_rows(st, wanted("axes"), wanted("fine"));
  if (wanted("ground")) {
    const Atmosphere black = st.black_ground();
    st.run("32x128x32x8 black ground", st.base,
           study_references(black, st.cam, st.views, st.paths, 0, st.cache), black);
  }
  return 0;
}
