// requires: atmosphere_common.glsl, multiscattering.glsl
// skybake runtime: the converged model's multiple-scattering source by view
// (multiscattering with "angular": "nu_zenith"; docs/reference.md "Psi_ms by
// view", docs/runtime.md "Multiple scattering by view"; C++
// src/atmosphere/multiscattering_lut.hpp lookup_multiscattering with nu and
// mu_v). In 1/sr: multiply by the sun's illuminance and sigma_s, as Psi_ms.
//
// The texture: a volume W x H x (1 + nu_slices + zenith_slices), RGB linear
// float, trilinear, clamp to edge on every axis, no mips. Slice 0 is the
// isotropic Psi_ms (lookup_multiscattering reads it as a 2D table); a view
// reads a(nu) + b(mu_v), each term one trilinear fetch between two slices:
//   a: slices 1 + k, k + f = (0.5 - 0.5 nu)^(1/4) (nu_slices - 1),
//   b: slices 1 + nu_slices + k, k + f = (0.5 + 0.5 sign(mu_v) sqrt|mu_v|) (zenith_slices - 1),
// nu = dot(view ray, sun) (the same along a ray: work it out once per ray),
// mu_v = dot(point, view ray) / |point| (the view's zenith cosine at the
// march's point). Two fetches per step where Hillaire's runtime takes one.

// The axes before the slice offset, in [0, 1].
float nu_node_unit_from_cosine(float nu) {
  return sqrt(sqrt(clamp(0.5 - 0.5 * nu, 0.0, 1.0)));
}
float zenith_node_unit_from_cosine(float mu_v) {
  mu_v = clamp_cosine(mu_v);
  float s = sqrt(abs(mu_v));
  return 0.5 + 0.5 * (mu_v < 0.0 ? -s : s);
}

// The w coordinate of slice `first` + x (nodes - 1): between the two
// slices' centres, so the trilinear fetch blends them linearly.
float view_slice_w(int first, int nodes, float x, int depth) {
  return (float(first) + clamp(x, 0.0, 1.0) * float(nodes - 1) + 0.5) / float(depth);
}

// max(a(nu) + b(mu_v), 0) at radius r (clamped to the shell) and sun zenith
// cosine mu_s, with the table's mapping and slice counts (metadata
// nu_slices, zenith_slices; zenith_slices 0: no b term).
vec3 lookup_multiscattering_view(sampler3D lut, MultiscatteringMapping mapping,
                                 AtmosphereParameters atm, int nu_slices, int zenith_slices,
                                 float r, float mu_s, float nu, float mu_v) {
  ivec3 size = textureSize(lut, 0);
  vec2 uv = multiscattering_uv_from_r_mu_s(atm, r, mu_s, size.x, size.y, mapping);
  float w_a = view_slice_w(1, nu_slices, nu_node_unit_from_cosine(nu), size.z);
  vec3 psi = textureLod(lut, vec3(uv, w_a), 0.0).rgb;
  if (zenith_slices > 0) {
    float w_b =
        view_slice_w(1 + nu_slices, zenith_slices, zenith_node_unit_from_cosine(mu_v), size.z);
    psi += textureLod(lut, vec3(uv, w_b), 0.0).rgb;
  }
  return max(psi, vec3(0.0));
}
