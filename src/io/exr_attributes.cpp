#include "io/exr_attributes.hpp"

#include <variant>

#include <ImfDoubleAttribute.h>
#include <ImfIntAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>

#include "core/colour.hpp"

namespace skybake {

void insert_typed_attribute(Imf::Header& header, const std::string& name, const MetaValue& value) {
  struct Insert {
    Imf::Header& header;
    const std::string& name;
    void operator()(int v) const { header.insert(name, Imf::IntAttribute(v)); }
    void operator()(double v) const { header.insert(name, Imf::DoubleAttribute(v)); }
    void operator()(const std::string& v) const { header.insert(name, Imf::StringAttribute(v)); }
    void operator()(const glm::ivec2& v) const {
      header.insert(name, Imf::V2iAttribute(Imath::V2i(v.x, v.y)));
    }
    void operator()(const glm::ivec3& v) const {
      header.insert(name, Imf::V3iAttribute(Imath::V3i(v.x, v.y, v.z)));
    }
    void operator()(const glm::dvec2& v) const {
      header.insert(name, Imf::V2dAttribute(Imath::V2d(v.x, v.y)));
    }
    void operator()(const glm::dvec3& v) const {
      header.insert(name, Imf::V3dAttribute(Imath::V3d(v.x, v.y, v.z)));
    }
  };
  std::visit(Insert{header, name}, value);
}

void add_exr_chromaticities(Imf::Header& header, const Metadata& metadata) {
  auto it = metadata.find("colour_space");
  if (it == metadata.end() || !std::holds_alternative<std::string>(it->second)) return;
  const std::string& name = std::get<std::string>(it->second);
  if (name != "rec709" && name != "acescg") return;
  const Chromaticities c =
      chromaticities_of(name == "acescg" ? ColourSpace::acescg : ColourSpace::rec709);
  auto v2f = [](const glm::dvec2& v) { return Imath::V2f(float(v.x), float(v.y)); };
  Imf::addChromaticities(header,
                         Imf::Chromaticities(v2f(c.red), v2f(c.green), v2f(c.blue), v2f(c.white)));
}

std::optional<MetaValue> typed_attribute(const Imf::Attribute& a) {
  if (const auto* v = dynamic_cast<const Imf::IntAttribute*>(&a)) return v->value();
  if (const auto* v = dynamic_cast<const Imf::DoubleAttribute*>(&a)) return v->value();
  if (const auto* v = dynamic_cast<const Imf::StringAttribute*>(&a)) return v->value();
  if (const auto* v = dynamic_cast<const Imf::V2iAttribute*>(&a))
    return glm::ivec2(v->value().x, v->value().y);
  if (const auto* v = dynamic_cast<const Imf::V3iAttribute*>(&a))
    return glm::ivec3(v->value().x, v->value().y, v->value().z);
  if (const auto* v = dynamic_cast<const Imf::V2dAttribute*>(&a))
    return glm::dvec2(v->value().x, v->value().y);
  if (const auto* v = dynamic_cast<const Imf::V3dAttribute*>(&a))
    return glm::dvec3(v->value().x, v->value().y, v->value().z);
  return std::nullopt;
}

}  // namespace skybake
