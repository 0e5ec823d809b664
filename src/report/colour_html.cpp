// The "Colour" section of report.html (report/colour.hpp).
#include <fmt/format.h>

#include "report/colour.hpp"
#include "report/html.hpp"

namespace skybake {

std::string colour_html(const nlohmann::json& c) {
  std::string s = "<h2 id=\"colour\">Colour: three wavelengths and N against the spectrum</h2>\n";
  if (c.contains("skipped")) return s + "<p>" + html_escape(c["skipped"].get<std::string>()) + "</p>\n";
  s += fmt::format(
      "<p>Sky-view texels against the spectral path tracer ({} wavelengths, {} paths per channel, "
      "group and direction), per view the largest CIE 1976 Delta u'v' (one just-noticeable "
      "difference is about 0.004) and relative luminance error; in brackets each "
      "against the {}-wavelength table (spectral sampling alone). Target: N = 15 within 0.002 "
      "and 1%.</p>\n<table>\n<tr><th>altitude</th><th>sun</th>",
      c["reference_wavelengths"].get<int>(), c["samples"].get<int>(),
      c["reference_wavelengths"].get<int>());
  std::vector<std::string> tables;
  for (const auto& [name, value] : c["worst"].items()) tables.push_back(name);
  for (const std::string& t : tables) s += "<th>" + html_escape(t) + "</th>";
  s += "<th>reference noise</th></tr>\n";
  for (const auto& v : c["views"]) {
    s += fmt::format("<tr><td>{} m</td><td>{} deg</td>", v["altitude_m"].get<double>(),
                     v["sun_elevation_deg"].get<double>());
    for (const std::string& t : tables)
      s += fmt::format("<td>{:.4f} ({:.4f}), {:.1f}% ({:.2f}%)</td>", v[t]["delta_uv"].get<double>(),
                       v[t]["table_delta_uv"].get<double>(),
                       100.0 * v[t]["luminance_error"].get<double>(),
                       100.0 * v[t]["table_luminance_error"].get<double>());
    s += fmt::format("<td>{:.4f}, {:.1f}%</td></tr>\n", v["ref_delta_uv_ci95"].get<double>(),
                     100.0 * v["ref_luminance_ci95"].get<double>());
  }
  s += "</table>\n<p>Each view's tables side by side (columns as in the table):</p>\n";
  return s + "<img src=\"" + html_escape(c["preview"].get<std::string>()) +
         "\" alt=\"colour previews\">\n";
}

}  // namespace skybake
