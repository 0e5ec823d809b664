// The planet and atmosphere sections of a scene preset (inline or read from
// their files, already validated against their schemas) into an Atmosphere
// in metres, with the semantic checks the schemas cannot say: a top radius
// above the planet's, profiles whose bounds are ordered, |g| < 1, a phase
// function for every component that scatters, distinct component names.
#pragma once

#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "pipeline/preset_source.hpp"

namespace skybake::preset {

// obj[key] as a finite number; throws a PresetError at `at`/key otherwise.
double number(const nlohmann::json& obj, const std::string& key, const Source& src,
              const std::string& at);
// obj[key] as three finite numbers >= 0, or 0 when absent.
glm::dvec3 rgb(const nlohmann::json& obj, const std::string& key, const Source& src,
               const std::string& at);

// The components of an atmosphere section (rayleigh, mie, ozone, extra)
// into `a`, each checked on its own; a component with all-zero coefficients
// is left out.
void add_components(Atmosphere& a, const nlohmann::json& atm, const Source& asrc,
                    Problems& problems);

// Each problem goes to `problems`; what could not be read stays at its default.
Atmosphere atmosphere_from(const nlohmann::json& planet, const Source& psrc,
                           const nlohmann::json& atm, const Source& asrc, Problems& problems);

}  // namespace skybake::preset
