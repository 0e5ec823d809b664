// Metadata values as typed EXR header attributes and back (docs/formats.md
// "Metadata"): int, double, string, v2i, v3i, v2d, v3d.
#pragma once

#include <optional>
#include <string>

#include <ImfAttribute.h>
#include <ImfHeader.h>

#include "core/metadata.hpp"

namespace skybake {

// Inserts `value` under `name` as the attribute of its type.
void insert_typed_attribute(Imf::Header& header, const std::string& name, const MetaValue& value);

// The metadata value of an attribute of one of those types, or nullopt.
std::optional<MetaValue> typed_attribute(const Imf::Attribute& a);

// The standard `chromaticities` attribute (OpenEXR's Imf::Chromaticities)
// of a table whose metadata names its colour_space (a spectral bake's; an
// RGB table's primaries are the preset's wavelengths, not a colour space).
void add_exr_chromaticities(Imf::Header& header, const Metadata& metadata);

}  // namespace skybake
