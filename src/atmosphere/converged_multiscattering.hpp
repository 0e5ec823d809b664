// Psi_ms from converged multiple scattering (docs/reference.md "Converged
// Psi_ms"): the same table as multiscattering_lut.hpp (shape, axes, sun
// mappings, units 1/sr per unit of sun illuminance, read with
// lookup_multiscattering), holding the mean incident radiance of every order
// at each point instead of Hillaire's L_2nd / (1 - f_ms):
//   Psi_conv(x) = (1 / (4 pi E)) int_4pi L*(x, omega') d omega',
// L* the sky of every order >= 1 plus the light the ground reflects (lit by
// the sun and the sky), taken from Bruneton's order iteration
// (scattering_orders.hpp) iterated to convergence in memory.
// Reads: the transmittance LUT.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/incident_radiance.hpp"
#include "atmosphere/medium.hpp"
#include "atmosphere/multiscattering_lut.hpp"
#include "atmosphere/psi_view_nodes.hpp"
#include "atmosphere/scattering_orders.hpp"
#include "core/bake_context.hpp"
#include "core/texture.hpp"

namespace skybake {

// How the one value per point is taken from the light around it
// (docs/reference.md "Converged Psi_ms", "The relative estimator"): `mean`,
// the mean incident radiance (the isotropic source carries the scattered
// power exactly); `relative` (the default), the mean of the source over the
// views ground viewers have of the point, weighted so that its relative
// error against the whole source, single scattering included, averages to
// zero (what skies seen from the ground ask for; it differs from the mean
// where Mie's forward peak makes the source anisotropic).
enum class PsiEstimator { mean, relative };
const char* psi_estimator_name(PsiEstimator e);

struct ConvergedMultiscatteringSpec {
  // The 4D iteration: shape (mu_s_min is replaced, below), tolerance, tail.
  BrunetonSpec bruneton = default_converged_bruneton_spec();
  int bands = 16;  // zenith bands of the sphere grid the mean is taken over (x 2 bands azimuths)
  PsiEstimator estimator = PsiEstimator::relative;
  // With nu_slices >= 2, the table also holds the view-dependent source
  // a(nu) + b(mu_v) (psi_view_nodes.hpp; docs/reference.md "Psi_ms by
  // view"): a at nu_slices nodes of the view-sun cosine, b at zenith_slices
  // (0, or >= 2) nodes of the view's zenith cosine, in slices of a volume
  // after the isotropic slice 0.
  int nu_slices = 0;
  int zenith_slices = 0;
  PsiViewShape view_shape() const { return {nu_slices, zenith_slices}; }
  // The table's lowest sun cosine is at most this (and converged_mu_s_min):
  // a field read by viewers deeper in twilight than that default reaches
  // (sky_light_source.hpp). 0: the default alone.
  double mu_s_min_cap = 0.0;

  static BrunetonSpec default_converged_bruneton_spec();
};

// The lowest sun cosine the 4D table needs: 0.1 below the horizon's cosine
// at the top of the atmosphere (a point anywhere in the shell is then deep
// in the planet's shadow), at most -0.99 (the table's axis excludes -1).
double converged_mu_s_min(const Atmosphere& atm);

// All the light of the iteration, as the mean reads it.
struct ConvergedField {
  ScatteringShape shape;
  SingleScatteringTables single;  // order 1, S_R and S_M
  Texture multiple;               // sum of the orders >= 2 (tail included), radiance
  Texture ground_irradiance;      // every order, direct sunlight included; row 0 the ground
  ScatteringPhases phases;
  int orders_used = 0;
  double last_residual = 1.0;
  // The iteration's energy balance (energy_balance.hpp); the products read
  // from the field record it as "energy_out_over_in".
  glm::dvec3 energy_out_over_in{0.0};
};
ConvergedField compute_converged_field(const Atmosphere& atm, const Texture& transmittance_lut,
                                       const ConvergedMultiscatteringSpec& spec,
                                       const BakeContext& ctx);

// What the estimator reads besides the field, the same at every point: the
// sphere grid (its half: cells mirrored about the sun's plane see the same
// light), and for the relative estimator each view cell's phase over the
// incident cells (normalised to one on the grid, mirror pairs folded),
// row-major [view][incident].
struct PsiQuadrature {
  SphereGrid grid;
  PsiEstimator estimator = PsiEstimator::mean;
  ScatteringPhases phases;
  std::vector<glm::dvec3> directions;  // half cells, band-major
  std::vector<double> solid_angle;     // of one cell of the pair
  std::vector<double> kernel_rayleigh, kernel_mie;
  double mie_phase(double nu) const;  // 0 without Mie
};
PsiQuadrature psi_quadrature(const ConvergedMultiscatteringSpec& spec,
                             const ScatteringPhases& phases);

// Psi at (r, mu_s) from L* on the sphere grid, per unit of sun illuminance
// (1/sr), with the spec's estimator. 0 below the field's mu_s_min. Thread-safe.
glm::dvec3 compute_converged_multiscattering(const Atmosphere& atm,
                                             const Texture& transmittance_lut,
                                             const ConvergedField& field, double r, double mu_s,
                                             const PsiQuadrature& quadrature);

// Psi at (r, mu_s) as the table's slices hold it: the isotropic value
// (compute_converged_multiscattering), then with a view shape (nu_nodes >=
// 2) its nodes, fitted to the source of orders >= 2 over the grid's
// directions (fit_view_nodes) with the estimator's weights: relative, the
// ground viewers' (plus kViewNodeOtherViews of their mean for the directions
// no ground viewer looks along, which viewers above the ground see) over the
// whole source; mean, the solid angle. q needs the phase kernels
// (psi_quadrature of a spec with nu_slices or the relative estimator).
// Thread-safe.
constexpr double kViewNodeOtherViews = 0.05;
std::vector<glm::dvec3> compute_converged_multiscattering_slices(
    const Atmosphere& atm, const Texture& transmittance_lut, const ConvergedField& field, double r,
    double mu_s, const PsiQuadrature& q, PsiViewShape shape);

// The range over view directions of the source of orders >= 2 at (r, mu_s),
// j(v) per unit of sigma_s E (docs/reference.md "The relative estimator"),
// per channel: min and max over the grid's half cells. Every Psi that is a
// mean of j over directions with weights >= 0 lies in it (both estimators;
// the mean too, each phase integrating to one): a bound on what any such
// estimator can give (docs/decisions/converged-psi-ms.md). q needs the relative estimator's kernels.
// Both 0 below the field's mu_s_min. Thread-safe.
struct SourceRange {
  glm::dvec3 min{0.0}, max{0.0};
};
SourceRange converged_source_range(const Atmosphere& atm, const Texture& transmittance_lut,
                                   const ConvergedField& field, double r, double mu_s,
                                   const PsiQuadrature& q);

// The table; rows in parallel, each texel independent (same data for any
// thread count). Metadata as bake_multiscattering_lut's, model "converged",
// with the iteration's orders and last residual; with nu_slices, a volume
// of 1 + nu_slices + zenith_slices slices and the keys "nu_slices",
// "zenith_slices" and "view_slices" (the slices' formula).
Texture bake_converged_multiscattering_lut(const Atmosphere& atm, const Texture& transmittance_lut,
                                           const MultiscatteringLutSpec& table,
                                           const ConvergedMultiscatteringSpec& spec,
                                           const BakeContext& ctx);
// The same from a field already computed with `spec` (the report shares one
// field between this table and skyview_multiple4d.hpp).
Texture converged_multiscattering_table(const Atmosphere& atm, const Texture& transmittance_lut,
                                        const MultiscatteringLutSpec& table,
                                        const ConvergedMultiscatteringSpec& spec,
                                        const ConvergedField& field, const BakeContext& ctx);

}  // namespace skybake
