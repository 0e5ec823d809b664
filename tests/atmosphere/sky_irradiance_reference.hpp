// The sky_irradiance tests' names for the path-tracer reference of
// reference/sky_irradiance_reference.hpp. Header only.
#pragma once

#include "reference/sky_irradiance_reference.hpp"

namespace skybake::fixtures {

using ReferenceRule = IrradianceReferenceRule;
using RelativeErrors = IrradianceErrors;
using skybake::fibonacci_normals;
using skybake::IrradianceReference;

inline IrradianceReference reference_irradiance(const Atmosphere& atm, double altitude_m,
                                                double sun_zenith_rad, const ReferenceRule& rule,
                                                int normals) {
  return reference_sky_irradiance(atm, altitude_m, sun_zenith_rad, rule, normals);
}

template <typename Decode>
RelativeErrors relative_errors(const IrradianceReference& ref, Decode decode) {
  return irradiance_errors(ref, decode);
}

}  // namespace skybake::fixtures
