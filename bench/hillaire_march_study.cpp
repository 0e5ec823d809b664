// Research tool, not a benchmark: why Hillaire's demo march (his
// IntegrateScatteredLuminance, atmosphere/hillaire_demo_march.hpp) renders
// skybake's converged tables in the "hillaire_demo" convention brighter than
// the path tracer, and what the tables' content can do about it
// (docs/report.md "Hillaire's runtime with skybake's tables",
// docs/decisions/hillaire-demo-march.md). Earth; the report section's 240
// views and path-traced references (same seeds). Per march and table set it
// prints R/G/B denoised relative RMSE, worst, bias, and the noisy RMSE:
//   his            his passes' tables (40 far-end samples, 8 x 8 directions)
//   converged      skybake's transmittance and converged Psi_ms, his layout
//   conv_bruneton  the same Psi_ms with skybake's own transmittance layout
//                  (texel i at i / (n - 1)) read his way: half a texel off
//   paper_bruneton Hillaire 2020's Psi_ms, the same transmittance
//   psi_fit        the converged Psi_ms as "fit_demo_march" bakes it
//                  (atmosphere/hillaire_demo_march_fit.hpp: one fit for both
//                  settings, 8 nodes)
// and fits of k(h), piecewise linear on --nodes altitudes (default 8), per
// setting: relative least squares of his march at the setting against his
// march at 2000 samples over training views disjoint from the report's
// (what a bake can do without a path tracer), or against the path tracer on
// the report's own views (a bound: the best such a factor can do there):
//   rows_bake, rows_bound     both tables' rows scaled (the transmittance
//                             then is no longer the transmittance)
//   rows_bake_x               the factor fitted at the other setting
//   global_bound              one factor per channel on both tables
//   psi_bake, psi_bound       the multiscattering table's rows alone
// The marches: RayMarchMinMaxSPP 30-31 and 4-14 at his SampleSegmentT 0.3,
// and 2000 samples; and his aerial-perspective pass (study_aerial).
//
//   build/bench/hillaire_march_study [--paths N] [--reference FILE] [--nodes N]
// --reference caches the path-traced references (read when it exists).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "atmosphere/converged_multiscattering.hpp"
#include "atmosphere/hillaire_demo_march_fit.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/transmittance_lut.hpp"
#include "core/math.hpp"
#include "pipeline/atmosphere_specs.hpp"
#include "pipeline/preset_loader.hpp"
#include "reference/path_tracer.hpp"
#include "report/hillaire_march.hpp"
#include "report/hillaire_runtime.hpp"
#include "report/setup.hpp"
#include "report/sky_radiance.hpp"

using namespace skybake;

namespace {

struct StudyView {
  glm::dvec3 position{0.0}, dir{0.0}, sun{0.0};
  RadianceEstimate ref;
};

std::vector<StudyView> study_views(const Atmosphere& atm, const HillaireRuntimeSetup& s) {
  std::vector<StudyView> views;
  for (double alt : s.hillaire_camera_altitudes_m)
    for (double sun_deg : s.hillaire_sun_elevations_deg)
      for (double e_deg : s.hillaire_view_elevations_deg)
        for (int k = 0; k < s.hillaire_view_azimuths; ++k) {
          const double phi = 2.0 * kPi * (k + 0.5) / s.hillaire_view_azimuths, e = e_deg * kDeg;
          StudyView v;
          v.position = {0.0, 0.0, atm.bottom_radius_m + alt};
          v.dir = {std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e)};
          v.sun = sky_radiance_sun(sun_deg);
          views.push_back(v);
        }
  return views;
}

// The report section's references (its seeds), or the cached ones.
void trace_references(const Atmosphere& atm, int samples, const std::string& cache,
                      std::vector<StudyView>& views) {
  std::ifstream in(cache);
  if (!cache.empty() && in) {
    for (StudyView& v : views)
      in >> v.ref.mean.x >> v.ref.mean.y >> v.ref.mean.z >> v.ref.ci95.x >> v.ref.ci95.y >>
          v.ref.ci95.z;
    if (in) return;
  }
  const SkyPathTracer tracer(atm);
  PathTracerSpec paths;
  paths.max_bounces = sky_radiance_max_bounces(atm);
  paths.samples = samples;
  for (size_t i = 0; i < views.size(); ++i) {
    paths.seed = 7919 + i;
    views[i].ref = tracer.trace(views[i].position, views[i].dir, views[i].sun, paths);
  }
  if (cache.empty()) return;
  std::ofstream out(cache);
  out.precision(17);
  for (const StudyView& v : views)
    out << v.ref.mean.x << ' ' << v.ref.mean.y << ' ' << v.ref.mean.z << ' ' << v.ref.ci95.x
        << ' ' << v.ref.ci95.y << ' ' << v.ref.ci95.z << '\n';
}

DemoMarch study_march(double lo, double hi) {
  DemoMarch m;
  m.min_samples = lo;
  m.max_samples = hi;
  return m;
}

// Both tables' rows scaled by k(h), k piecewise linear on `nodes` altitudes
// evenly over the shell: the transmittance's rows (his texel centres on
// rho) and the multiscattering's (his sub-uv positions on altitude).
struct ScaledTables {
  Texture transmittance, multiscattering;
};

double hat_weight(double h, double shell, int nodes, int b) {
  const double x = std::clamp(h / shell, 0.0, 1.0) * (nodes - 1);
  return std::max(0.0, 1.0 - std::abs(x - b));
}

// psi_only: the multiscattering table's rows alone.
ScaledTables scale_rows(const Atmosphere& atm, const Texture& t, const Texture& ms,
                        const std::vector<glm::dvec3>& k, bool psi_only = false) {
  ScaledTables out{t, ms};
  const double rb = atm.bottom_radius_m, rt = atm.top_radius_m, shell = rt - rb;
  const double big_h = std::sqrt(rt * rt - rb * rb);
  const int nodes = int(k.size());
  auto factor = [&](double h) {
    glm::dvec3 f(0.0);
    for (int b = 0; b < nodes; ++b) f += k[b] * hat_weight(h, shell, nodes, b);
    return f;
  };
  for (int j = 0; j < (psi_only ? 0 : t.height); ++j) {
    const double rho = big_h * (j + 0.5) / t.height;
    const glm::dvec3 f = factor(std::sqrt(rho * rho + rb * rb) - rb);
    for (int i = 0; i < t.width; ++i)
      for (int c = 0; c < 3; ++c) out.transmittance.at(i, j, 0, 0, c) *= float(f[c]);
  }
  const double n = ms.height;
  for (int j = 0; j < ms.height; ++j) {
    const double x = std::clamp((((j + 0.5) * (n + 1.0) / n) - 0.5) / n, 0.0, 1.0);
    const glm::dvec3 f = factor(x * shell);
    for (int i = 0; i < ms.width; ++i)
      for (int c = 0; c < 3; ++c) out.multiscattering.at(i, j, 0, 0, c) *= float(f[c]);
  }
  return out;
}

// Solves A x = b (n x n, symmetric positive definite) by Gaussian elimination.
std::vector<double> solve_dense(std::vector<double> a, std::vector<double> b) {
  const int n = int(b.size());
  for (int p = 0; p < n; ++p)
    for (int r = p + 1; r < n; ++r) {
      const double f = a[r * n + p] / a[p * n + p];
      for (int c = p; c < n; ++c) a[r * n + c] -= f * a[p * n + c];
      b[r] -= f * b[p];
    }
  std::vector<double> x(n);
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int c = r + 1; c < n; ++c) s -= a[r * n + c] * x[c];
    x[r] = s / a[r * n + r];
  }
  return x;
}

// k per node and channel minimising sum_v ((sum_b k_b C_bv + F_v - Y_v) / Y_v)^2
// + lambda sum_b (k_b - 1)^2 (nodes no sample reaches stay at 1); F the
// basis' last entry when fixed_last (an unscaled part), else 0.
std::vector<glm::dvec3> fit_rows(std::vector<std::vector<glm::dvec3>> basis,
                                 const std::vector<glm::dvec3>& target, bool fixed_last = false) {
  std::vector<glm::dvec3> fixed(target.size(), glm::dvec3(0.0));
  if (fixed_last) {
    fixed = basis.back();
    basis.pop_back();
  }
  const int nodes = int(basis.size());
  const double lambda = 1e-4 * double(target.size());
  std::vector<glm::dvec3> k(nodes, glm::dvec3(1.0));
  for (int c = 0; c < 3; ++c) {
    std::vector<double> a(nodes * nodes, 0.0), b(nodes, 0.0);
    for (size_t v = 0; v < target.size(); ++v) {
      const double y = target[v][c], rhs = target[v][c] - fixed[v][c];
      for (int i = 0; i < nodes; ++i) {
        b[i] += basis[i][v][c] * rhs / (y * y);
        for (int j = 0; j < nodes; ++j) a[i * nodes + j] += basis[i][v][c] * basis[j][v][c] / (y * y);
      }
    }
    for (int i = 0; i < nodes; ++i) {
      a[i * nodes + i] += lambda;
      b[i] += lambda;
    }
    const std::vector<double> x = solve_dense(a, b);
    for (int i = 0; i < nodes; ++i) k[i][c] = x[i];
  }
  return k;
}

struct Geometry {
  glm::dvec3 position, dir, sun;
};

std::vector<glm::dvec3> render(const Atmosphere& atm, const Texture& t, const Texture& ms,
                               const std::vector<Geometry>& views, const DemoMarch& march) {
  std::vector<glm::dvec3> out;
  for (const Geometry& g : views)
    out.push_back(demo_integrate(atm, {&t, &ms}, g.position, g.dir, g.sun, march).luminance);
  return out;
}

// The march's output with both tables' rows scaled by each node's hat alone
// (the march is linear in the tables' texels).
std::vector<std::vector<glm::dvec3>> row_basis(const Atmosphere& atm, const Texture& t,
                                               const Texture& ms, int nodes,
                                               const std::vector<Geometry>& views,
                                               const DemoMarch& march, bool psi_only = false) {
  std::vector<std::vector<glm::dvec3>> basis;
  for (int b = 0; b < nodes; ++b) {
    std::vector<glm::dvec3> k(nodes, glm::dvec3(0.0));
    k[b] = glm::dvec3(1.0);
    const ScaledTables s = scale_rows(atm, t, ms, k, psi_only);
    basis.push_back(render(atm, s.transmittance, s.multiscattering, views, march));
  }
  if (psi_only) {
    // The single-scattering part, unscaled: a fixed term (fit_rows' last
    // entry), taken out of each node's render.
    std::vector<glm::dvec3> zero(nodes, glm::dvec3(0.0));
    const ScaledTables s = scale_rows(atm, t, ms, zero, true);
    const std::vector<glm::dvec3> fixed = render(atm, s.transmittance, s.multiscattering, views, march);
    for (std::vector<glm::dvec3>& b : basis)
      for (size_t v = 0; v < b.size(); ++v) b[v] -= fixed[v];
    basis.push_back(fixed);
  }
  return basis;
}

// Training views for the bake-time fit, disjoint from the report's.
std::vector<Geometry> training_views(const Atmosphere& atm) {
  std::vector<Geometry> out;
  for (double alt : {1.0, 300.0, 1e3, 3e3, 10e3})
    for (double sun_deg : {80.0, 45.0, 20.0, 6.0, 3.0, 1.0})
      for (double e_deg : {1.0, 4.0, 7.0, 15.0, 30.0, 40.0, 60.0, 70.0, 89.0})
        for (double az : {0.2, 1.1, 1.9, 2.9}) {
          const double e = e_deg * kDeg;
          out.push_back({{0.0, 0.0, atm.bottom_radius_m + alt},
                         {std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)},
                         sky_radiance_sun(sun_deg)});
        }
  return out;
}

void print_row(const char* name, const std::vector<glm::dvec3>& lut,
               const std::vector<StudyView>& views) {
  std::vector<RadiancePair> pairs;
  for (size_t i = 0; i < views.size(); ++i)
    pairs.push_back({lut[i], views[i].ref.mean, views[i].ref.ci95, views[i].ref.mean});
  const nlohmann::json s = radiance_stats(pairs);
  std::printf("  %-16s", name);
  for (const auto& c : s["channels"]) std::printf(" %5.2f", 100.0 * c["rel_rmse_denoised"].get<double>());
  std::printf("  worst %5.2f  bias", 100.0 * s["worst"]["rel_rmse_denoised"].get<double>());
  for (const auto& c : s["channels"]) std::printf(" %+5.2f", 100.0 * c["rel_bias"].get<double>());
  std::printf("  noisy");
  for (const auto& c : s["channels"]) std::printf(" %5.2f", 100.0 * c["rel_rmse"].get<double>());
  std::printf("\n");
}

// Every table the study reads, made as the report section makes them
// (report/hillaire_runtime.cpp).
struct StudyTables {
  Texture t_skybake, t_his, ms_his, t_demo, ms_paper, ms_conv, ms_fit;
};

StudyTables study_tables(const Scene& scene) {
  const Atmosphere& atm = scene.atmosphere;
  StudyTables t;
  TransmittanceLutSpec ts = transmittance_spec(operating_spec(scene, "transmittance"));
  t.t_skybake = bake_transmittance_lut(atm, ts, BakeContext{});
  t.t_his = demo_transmittance_pass(atm, ts.width, ts.height);
  t.ms_his = demo_multiscattering_pass(atm, t.t_his, 32);
  ts.convention = TableConvention::hillaire_demo;
  t.t_demo = bake_transmittance_lut(atm, ts, BakeContext{});
  const OutputSpec op = operating_spec(scene, "multiscattering");
  MultiscatteringLutSpec ms = multiscattering_spec(op);
  ms.height = ms.width;
  ms.sun_mapping = SunMapping::linear;
  ms.altitude_mapping = AltitudeMapping::linear;
  ms.convention = TableConvention::hillaire_demo;
  t.ms_paper = bake_multiscattering_lut(atm, t.t_skybake, ms, BakeContext{});
  const ConvergedMultiscatteringSpec cs = converged_multiscattering_spec(op);
  const ConvergedField field = compute_converged_field(atm, t.t_skybake, cs, BakeContext{});
  t.ms_conv = converged_multiscattering_table(atm, t.t_skybake, ms, cs, field, BakeContext{});
  // The shipped fit (atmosphere/hillaire_demo_march_fit.hpp).
  t.ms_fit = t.ms_conv;
  apply_demo_march_fit(atm, fit_demo_march(atm, t.t_demo, t.ms_conv), t.ms_fit);
  return t;
}

void print_factors(const Atmosphere& atm, const char* what, const std::vector<glm::dvec3>& k) {
  std::printf("  k(h) %s, R G B at 0, 2, 5, 10, 20 km:", what);
  for (double h : {0.0, 2e3, 5e3, 10e3, 20e3}) {
    glm::dvec3 f(0.0);
    for (int b = 0; b < int(k.size()); ++b)
      f += k[b] * hat_weight(h, atm.top_radius_m - atm.bottom_radius_m, int(k.size()), b);
    std::printf(" (%.3f %.3f %.3f)", f.x, f.y, f.z);
  }
  std::printf("\n");
}

struct StudySetting {
  const char* name;
  DemoMarch march, other;  // other: the setting a cross fit comes from
};

// The fits of one setting: against his 2000-sample march on the training
// views (bake), against the path tracer on the report's views (bound).
void study_setting(const Atmosphere& atm, const StudyTables& t, const StudySetting& st,
                   const std::vector<StudyView>& views, int nodes) {
  std::vector<Geometry> test;
  std::vector<glm::dvec3> ref;
  for (const StudyView& v : views) {
    test.push_back({v.position, v.dir, v.sun});
    ref.push_back(v.ref.mean);
  }
  const std::vector<Geometry> train = training_views(atm);
  const std::vector<glm::dvec3> target = render(atm, t.t_demo, t.ms_conv, train, study_march(2000, 2000));
  const DemoMarch& m = st.march;
  auto show = [&](const char* name, const std::vector<glm::dvec3>& k, bool psi_only) {
    const ScaledTables s = scale_rows(atm, t.t_demo, t.ms_conv, k, psi_only);
    print_row(name, render(atm, s.transmittance, s.multiscattering, test, m), views);
  };
  std::printf("%s (R G B denoised rel RMSE %%, worst, bias, noisy)\n", st.name);
  print_row("his", render(atm, t.t_his, t.ms_his, test, m), views);
  print_row("converged", render(atm, t.t_demo, t.ms_conv, test, m), views);
  print_row("conv_bruneton", render(atm, t.t_skybake, t.ms_conv, test, m), views);
  print_row("paper_bruneton", render(atm, t.t_skybake, t.ms_paper, test, m), views);
  print_row("psi_fit", render(atm, t.t_demo, t.ms_fit, test, m), views);
  const std::vector<glm::dvec3> k_rows = fit_rows(row_basis(atm, t.t_demo, t.ms_conv, nodes, train, m), target);
  show("rows_bake", k_rows, false);
  show("rows_bake_x",
       fit_rows(row_basis(atm, t.t_demo, t.ms_conv, nodes, train, st.other), target), false);
  show("rows_bound", fit_rows(row_basis(atm, t.t_demo, t.ms_conv, nodes, test, m), ref), false);
  show("global_bound", fit_rows(row_basis(atm, t.t_demo, t.ms_conv, 1, test, m), ref), false);
  const std::vector<glm::dvec3> k_psi =
      fit_rows(row_basis(atm, t.t_demo, t.ms_conv, nodes, train, m, true), target, true);
  show("psi_bake", k_psi, true);
  show("psi_bound", fit_rows(row_basis(atm, t.t_demo, t.ms_conv, nodes, test, m, true), ref, true),
       true);
  print_factors(atm, "rows_bake", k_rows);
  print_factors(atm, "psi_bake", k_psi);
}

// His aerial-perspective pass (RenderCameraVolumePS): slice k of 32 at
// ((k + 0.5) / 32)^2 x 128 km, marched with 2 (k + 1) fixed samples up to
// it; each table set against his march at 2000 fixed samples of the
// unfitted converged tables (the integral his pass converges to), over the
// report's cameras and suns and views 0.5 to 25 degrees up. Relative RMS and
// bias of the in-scattered luminance per channel over views x slices.
void study_aerial(const Atmosphere& atm, const StudyTables& t) {
  std::printf("his aerial-perspective pass against its 2000-sample march of the converged tables "
              "(R G B rel RMS %%, bias %%)\n");
  const Texture* sets[2][2] = {{&t.t_demo, &t.ms_conv}, {&t.t_demo, &t.ms_fit}};
  const char* names[2] = {"converged", "psi_fit"};
  for (int set = 0; set < 2; ++set) {
    glm::dvec3 sum2(0.0), sum(0.0);
    int n = 0;
    for (double alt : {1.0, 10e3})
      for (double sun_deg : {60.0, 10.0, 2.0})
        for (double e_deg : {0.5, 2.0, 10.0, 25.0})
          for (int k = 0; k < 8; ++k) {
            const double e = e_deg * kDeg, phi = 2.0 * kPi * (k + 0.5) / 8;
            const glm::dvec3 pos(0.0, 0.0, atm.bottom_radius_m + alt);
            const glm::dvec3 dir(std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e));
            const glm::dvec3 sun = sky_radiance_sun(sun_deg);
            for (int slice = 0; slice < 32; ++slice) {
              const double x = (slice + 0.5) / 32.0;
              DemoMarch his, ref;
              his.variable = ref.variable = false;
              his.min_samples = std::max(1.0, 2.0 * (slice + 1));
              ref.min_samples = 2000.0;
              his.max_distance = ref.max_distance = x * x * 128e3;
              const glm::dvec3 r =
                  demo_integrate(atm, {&t.t_demo, &t.ms_conv}, pos, dir, sun, ref).luminance;
              const glm::dvec3 l =
                  demo_integrate(atm, {sets[set][0], sets[set][1]}, pos, dir, sun, his).luminance;
              const glm::dvec3 d = l / r - 1.0;
              sum += d;
              sum2 += d * d;
              ++n;
            }
          }
    std::printf("  %-16s %5.2f %5.2f %5.2f  bias %+5.2f %+5.2f %+5.2f\n", names[set],
                100.0 * std::sqrt(sum2.x / n), 100.0 * std::sqrt(sum2.y / n),
                100.0 * std::sqrt(sum2.z / n), 100.0 * sum.x / n, 100.0 * sum.y / n,
                100.0 * sum.z / n);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int samples = 8192, nodes = 8;
  std::string cache;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--paths")) samples = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--reference")) cache = argv[i + 1];
    if (!std::strcmp(argv[i], "--nodes")) nodes = std::atoi(argv[i + 1]);
  }
  const Scene scene = load_scene("presets/earth.json");
  const Atmosphere& atm = scene.atmosphere;
  const StudyTables t = study_tables(scene);
  std::vector<StudyView> views = study_views(atm, HillaireRuntimeSetup::full());
  trace_references(atm, samples, cache, views);
  const DemoMarch m30 = study_march(30, 31), m4 = study_march(4, 14);
  study_setting(atm, t, {"march 30-31", m30, m4}, views, nodes);
  study_setting(atm, t, {"march 4-14", m4, m30}, views, nodes);
  std::printf("march 2000\n");
  std::vector<Geometry> test;
  for (const StudyView& v : views) test.push_back({v.position, v.dir, v.sun});
  const DemoMarch m2000 = study_march(2000, 2000);
  print_row("his", render(atm, t.t_his, t.ms_his, test, m2000), views);
  print_row("converged", render(atm, t.t_demo, t.ms_conv, test, m2000), views);
  print_row("conv_bruneton", render(atm, t.t_skybake, t.ms_conv, test, m2000), views);
  study_aerial(atm, t);
  return 0;
}
