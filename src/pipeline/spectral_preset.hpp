// A scene's "spectral" key and its atmosphere's "spectrum" section into a
// SpectralScene (docs/presets.md "Spectral skies"), with the rules the
// schemas cannot say: tables of increasing wavelengths and matching
// lengths, and a law only for a component the atmosphere has.
#pragma once

#include <memory>

#include <nlohmann/json.hpp>

#include "atmosphere/medium.hpp"
#include "pipeline/preset_source.hpp"
#include "pipeline/scene.hpp"
#include "pipeline/spectral_scene.hpp"

namespace skybake::preset {

// `spectral` is the scene's "spectral" object (schema defaults applied),
// `atm` the atmosphere section and `a` the Atmosphere loaded from it.
// Problems go to `problems`; nullptr when there are any.
std::shared_ptr<const SpectralScene> spectral_from(const nlohmann::json& spectral,
                                                   const nlohmann::json& atm, const Source& asrc,
                                                   const Atmosphere& a, Problems& problems);

// Outputs a spectral scene cannot write: photometric tables in half
// floats (the sun's 1.28e5 lux and the sky near it pass half's 65504).
// `spectral` is the scene's "spectral" object.
void check_spectral_outputs(const nlohmann::json& spectral, const std::vector<OutputSpec>& outputs,
                            const Source& scene_src, Problems& problems);

// The scene's spectral bake, if `doc` (the scene, references inlined) asks
// for one and its atmosphere could be read: scene.spectral set, the sun's
// colour in the atmosphere's sun_illuminance, the outputs checked.
void load_spectral(Scene& scene, const nlohmann::json& doc, const Source& asrc,
                   const Source& scene_src, bool atmosphere_read, Problems& problems);

}  // namespace skybake::preset
