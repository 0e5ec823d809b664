#include "report/html.hpp"

#include <fmt/format.h>

#include "report/colour.hpp"

namespace skybake {

namespace {

const char* kStyle = R"(<style>
body { font: 14px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 70em; color: #222; }
h1 { font-size: 1.6em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border: 1px solid #ccc; padding: 2px 8px; text-align: right; }
th { background: #f3f3f3; } td.l, th.l { text-align: left; }
tr.op td { background: #fde8e8; font-weight: bold; } tr.front td:first-child { color: #2a7; }
.note { color: #555; } .plot text { font-size: 11px; fill: #444; }
.met { color: #2a7; font-weight: bold; } .notmet { color: #d22; font-weight: bold; }
img { max-width: 100%; border: 1px solid #ccc; }
</style>
)";

std::string num(const nlohmann::json& v) {
  if (!v.is_number()) return "-";
  return fmt::format("{:.3g}", v.get<double>());
}

std::string pct(const nlohmann::json& v) {
  if (!v.is_number()) return "-";
  return fmt::format("{:.3g} %", 100.0 * v.get<double>());
}

std::string text(const nlohmann::json& v) {
  return html_escape(v.is_string() ? v.get<std::string>() : v.dump());
}

// A value as prose: numbers to 3 significant digits (integers whole), lists
// as "a, b, c" ("a x b" for a size), objects as "key value; key value",
// never raw JSON.
std::string prose(const nlohmann::json& v, const std::string& key = "") {
  if (v.is_number_integer()) return v.dump();
  if (v.is_number()) return num(v);
  if (v.is_array()) {
    std::string s;
    for (size_t i = 0; i < v.size(); ++i)
      s += (i ? (key == "size" ? " x " : ", ") : "") + prose(v[i]);
    return s;
  }
  if (v.is_object()) {
    std::string s;
    for (const auto& [k, x] : v.items()) s += (s.empty() ? "" : "; ") + html_escape(k) + " " + prose(x, k);
    return s;
  }
  return text(v);
}

// Where a product's largest errors lie, when docs/report.md says: shown
// beside the headline number, which alone reads as a failure.
std::string max_error_note(const std::string& product) {
  if (product == "multiscattering")
    return "at the terminator (sun 0-12 deg below the horizon), where Psi_ms falls by orders of "
           "magnitude across a texel; the daytime sky's error is small next to the model's";
  if (product == "transmittance")
    return "on grazing rays high in the atmosphere, where T falls by orders of magnitude across a "
           "texel";
  return "";
}

std::string row(const std::vector<std::string>& cells, const std::string& cls = "") {
  std::string s = cls.empty() ? "<tr>" : "<tr class=\"" + cls + "\">";
  for (size_t i = 0; i < cells.size(); ++i)
    s += (i == 0 ? "<td class=\"l\">" : "<td>") + cells[i] + "</td>";
  return s + "</tr>\n";
}

std::string header(const std::vector<std::string>& cells) {
  std::string s = "<tr>";
  for (size_t i = 0; i < cells.size(); ++i)
    s += (i == 0 ? "<th class=\"l\">" : "<th>") + html_escape(cells[i]) + "</th>";
  return s + "</tr>\n";
}

std::string summary_table(const nlohmann::json& report) {
  std::string s = "<table>\n" + header({"product", "kind", "operating point", "seconds", "max rel",
                                        "rms rel", "half max rel", "on front"});
  for (const auto& p : report["products"]) {
    if (p["kind"] != "lut") {
      s += row({text(p["product"]), text(p["kind"]), "", "", "", "", "", ""});
      continue;
    }
    const auto& op = p["ladder"][p["operating_point"].get<size_t>()];
    const bool noted = !max_error_note(p["product"]).empty();
    s += row({text(p["product"]), "lut", text(op["label"]), num(op["seconds"]),
              num(op["max_rel"]) + (noted ? "<sup>*</sup>" : ""), num(op["rms_rel"]),
              num(p["half"]["half"]["max_rel"]), op["pareto"].get<bool>() ? "yes" : "no"});
  }
  s += "</table>\n";
  for (const auto& p : report["products"])
    if (p["kind"] == "lut" && !max_error_note(p["product"]).empty())
      s += "<p class=\"note\"><sup>*</sup> " + text(p["product"]) + ": the largest errors lie " +
           max_error_note(p["product"]) + " (docs/report.md).</p>\n";
  return s;
}

// Column label of a ladder point's extra statistics.
std::string extra_label(const std::string& key) {
  if (key == "single_scattering") return "single";
  if (key == "transmittance") return "A";
  return key;  // header() escapes
}

std::string product_section(const nlohmann::json& p) {
  std::string s = fmt::format("<h2 id=\"{0}\">{0}</h2>\n", text(p["product"]));
  s += "<p class=\"note\">Reference: " + text(p["reference"]) +
       ".<br>Queries: " + text(p["queries"]) + ".";
  if (!max_error_note(p["product"]).empty())
    s += "<br>The largest errors lie " + max_error_note(p["product"]) + ".";
  s += "</p>\n";
  std::vector<PlotPoint> points;
  for (const auto& q : p["ladder"]) {
    PlotPoint a;
    a.x = q["seconds"], a.y = q["max_rel"];
    a.highlight = q["operating_point"], a.front = q["pareto"];
    a.title = q["label"].get<std::string>() + " (max rel)";
    points.push_back(a);
    PlotPoint b = a;
    b.y = q["rms_rel"], b.front = false, b.secondary = true;
    b.title = q["label"].get<std::string>() + " (rms rel)";
    points.push_back(b);
  }
  s += loglog_svg(points, "bake time (s)", "relative error");
  s += "<p class=\"note\">Filled: max relative error; hollow: RMS relative error; red: the "
       "preset's operating point; green line: the Pareto front (time, max rel).</p>\n";
  // Statistics a ladder point carries beside its main numbers (sky-view's
  // single scattering, aerial perspective's A, ...): one pair of columns each.
  std::vector<std::string> extra;
  if (!p["ladder"].empty())
    for (const auto& [key, value] : p["ladder"][0].items())
      if (value.is_object() && value.contains("rms_rel")) extra.push_back(key);
  std::vector<std::string> cols = {"settings", "seconds", "max abs", "max rel", "rms rel"};
  for (const std::string& key : extra)
    cols.insert(cols.end(), {extra_label(key) + ": max rel", extra_label(key) + ": rms rel"});
  s += "<table>\n" + header(cols);
  for (const auto& q : p["ladder"]) {
    std::vector<std::string> cells = {text(q["label"]), num(q["seconds"]), num(q["max_abs"]),
                                      num(q["max_rel"]), num(q["rms_rel"])};
    for (const std::string& key : extra)
      cells.insert(cells.end(), {num(q[key]["max_rel"]), num(q[key]["rms_rel"])});
    const std::string cls = q["operating_point"].get<bool>() ? "op"
                            : q["pareto"].get<bool>()        ? "front"
                                                             : "";
    s += row(cells, cls);
  }
  return s + "</table>\n";
}

std::string radiance_table(const std::string& title, const nlohmann::json& stats) {
  std::string s = "<h3>" + html_escape(title) + "</h3>\n<table>\n" +
                  header({"channel", "views", "RMSE", "rel RMSE", "reference noise (rel)",
                          "rel RMSE without noise", "rel bias", "max rel", "max CI95 (rel)"});
  for (const auto& c : stats["channels"])
    s += row({text(c["channel"]), text(c["views"]), num(c["rmse"]), pct(c["rel_rmse"]),
              pct(c["noise_rel_rms"]), pct(c["rel_rmse_denoised"]), pct(c["rel_bias"]),
              pct(c["max_rel"]), pct(c["max_ci95_rel"])});
  return s + "</table>\n";
}

// One target verdict (target_json, sky_radiance.hpp) as a paragraph. A
// quick run's few paths and small tables cannot show that a target is
// missed: only "met" is a verdict there, anything else is left unmarked.
std::string target_paragraph(const std::string& model, const nlohmann::json& target, bool quick) {
  std::string status = target["status"];
  std::string cls = status == "met" ? "met" : (status == "not met" ? "notmet" : "");
  if (quick && status != "met") status = "not judged by a quick run", cls = "";
  return fmt::format(
      "<p>Target for {} ({}): <span class=\"{}\">{}</span> (worst-channel rel RMSE {}, "
      "{} without the reference noise).</p>\n",
      model, text(target["what"]), cls, status, pct(target["rel_rmse"]),
      pct(target["rel_rmse_denoised"]));
}

// Said once above the targets of a quick run.
const char* kQuickTargets =
    "<p class=\"note\">A quick run (--quick) cannot judge the targets below: its path-traced "
    "references carry percent-level noise and its Bruneton and converged tables are small, so "
    "a target it does not meet is left unmarked. A full run (without --quick) judges them.</p>\n";

// Hillaire's demo run-time with each set of tables (hillaire_runtime.hpp):
// worst-channel and per-channel denoised rel RMSE against the path tracer.
std::string hillaire_runtime_section(const nlohmann::json& h, bool quick) {
  std::string s =
      "<h2 id=\"hillaire\">Hillaire's runtime with skybake's tables</h2>\n";
  if (h.is_null()) return s + "<p>Not run (skyview was not selected).</p>\n";
  s += fmt::format(
      "<p>His ray march and sky-view read (transcribed), cameras at {} m, suns {} deg up, "
      "views at {} deg x {} azimuths ({} views); path tracer {} paths, up to {} bounces. Rel "
      "RMSE without the reference noise, R / G / B.</p>\n<table>\n",
      prose(h["camera_altitudes_m"]), prose(h["sun_elevations_deg"]),
      prose(h["view_elevations_deg"]), prose(h["view_azimuths"]), prose(h["views"]),
      prose(h["path_tracer"]["samples"]), prose(h["path_tracer"]["max_bounces"]));
  const auto rgb = [](const nlohmann::json& stats) {
    std::string cell;
    for (const auto& c : stats["channels"])
      cell += (cell.empty() ? "" : " / ") + pct(c["rel_rmse_denoised"]);
    return cell;
  };
  s += header({"his runtime path", "his own tables", "skybake, paper Psi_ms",
               "skybake, converged Psi_ms", "skybake, Psi_ms fitted to his march"});
  for (const char* m : {"march_30_31", "march_4_14", "march_2000", "march_30_31_midpoint",
                        "march_4_14_midpoint", "skyview_lookup"}) {
    std::vector<std::string> cells = {m};
    for (const char* set : {"his_tables", "skybake_paper", "skybake_converged", "skybake_fitted"})
      cells.push_back(rgb(h[m][set]));
    s += row(cells, "");
  }
  s += "</table>\n<p>skybake's converged sky-view in each azimuth layout, read by skybake's "
       "lookups, against the same path tracer:</p>\n<table>\n";
  s += header({"layout", "R / G / B"});
  for (const auto& [layout, stats] : h["skyview_layouts"].items()) s += row({layout, rgb(stats)}, "");
  s += "</table>\n";
  if (quick) s += kQuickTargets;
  for (const auto& t : h["targets"]) {
    std::string status = t["status"];
    std::string cls = status == "met" ? "met" : "notmet";
    if (quick && status != "met") status = "not judged by a quick run", cls = "";
    s += fmt::format("<p>Target ({}): <span class=\"{}\">{}</span>, {} against {}.</p>\n",
                     text(t["what"]), cls, status, pct(t["value"]), pct(t["limit"]));
  }
  return s;
}

std::string sky_section(const nlohmann::json& sky, bool quick) {
  std::string s = "<h2 id=\"sky\">Sky radiance: LUTs against the path tracer</h2>\n";
  if (sky.is_null()) return s + "<p>Not run (neither skyview nor scattering was selected).</p>\n";
  const auto& pt = sky["path_tracer"];
  s += fmt::format(
      "<p>Camera at {} m; sun elevations {} deg; views at elevations {} deg x {} azimuths; "
      "sky-view {}. Path tracer: {} paths per channel and view (every order), up to {} "
      "bounces, ground albedo {}; its single scattering is within {} standard errors of the "
      "quadrature.</p>\n",
      num(sky["camera_altitude_m"]), prose(sky["sun_elevations_deg"]),
      prose(sky["view_elevations_deg"]), prose(sky["view_azimuths"]), prose(sky["skyview"]),
      prose(pt["samples"]), prose(pt["max_bounces"]), prose(pt["ground_albedo"]),
      num(pt["single_scattering_max_z_vs_quadrature"]));
  if (quick) s += kQuickTargets;
  s += target_paragraph("Hillaire's model", sky["target"], quick);
  s += radiance_table("With multiple scattering (Hillaire's Psi_ms) vs path tracer, all orders",
                      sky["multiple"]);
  for (const auto& b : sky["multiple_by_sun"])
    s += radiance_table(fmt::format("... sun at {} deg", num(b["sun_elevation_deg"])),
                        b["multiple"]);
  if (sky.contains("converged_vs_path_tracer")) {
    const auto& m = sky["models"];
    s += fmt::format(
        "<p>Two Psi_ms models at the operating point: Hillaire 2020 baked in {} s; converged "
        "(mean incident radiance of a {} order iteration to {}, {} orders, last residual {}) "
        "in {} s.</p>\n",
        num(m["hillaire2020"]["bake_seconds"]), prose(m["converged"]["scattering_shape"], "size"),
        num(m["converged"]["tolerance"]), prose(m["converged"]["orders_used"]),
        num(m["converged"]["last_residual"]), num(m["converged"]["bake_seconds"]));
    s += target_paragraph("the converged Psi_ms", sky["converged_target"], quick);
    s += radiance_table("With multiple scattering (converged Psi_ms) vs path tracer, all orders",
                        sky["converged_vs_path_tracer"]);
    if (sky.contains("converged_relative_vs_path_tracer")) {
      s += target_paragraph("the converged Psi_ms, relative estimator",
                            sky["converged_relative_target"], quick);
      s += radiance_table(
          "With multiple scattering (converged Psi_ms, relative estimator) vs path tracer, all "
          "orders",
          sky["converged_relative_vs_path_tracer"]);
    }
    if (sky.contains("converged_angular_vs_path_tracer")) {
      s += target_paragraph("the converged Psi_ms by view (a(nu) + b(mu_v))",
                            sky["converged_angular_target"], quick);
      s += radiance_table(
          "With multiple scattering (converged Psi_ms by view, relative weights) vs path tracer, "
          "all orders",
          sky["converged_angular_vs_path_tracer"]);
    }
    s += target_paragraph("the sky-view with the 4D orders \u2265 2",
                          sky["skyview_multiple4d_target"], quick);
    s += radiance_table(
        "Sky-view: single scattering marched + the 4D iteration's orders \u2265 2 (the same "
        "iteration) vs path tracer, all orders",
        sky["skyview_multiple4d_vs_path_tracer"]);
  }
  s += "<p>Share of the path-traced radiance carried by orders \u2265 2 (R, G, B): " +
       prose(sky["multiple_scattering_share"]) + ".</p>\n";
  s += radiance_table(
      "Orders 1 and 2 only (Psi_ms replaced by its second order L_2) vs path tracer, 2 vertices",
      sky["second_order_vs_path_tracer"]);
  s += radiance_table("Single scattering only vs path tracer (1 bounce, black ground)",
                      sky["single_vs_path_tracer"]);
  s += radiance_table("Single scattering only vs adaptive quadrature (noise free)",
                      sky["single_vs_quadrature"]);
  s += "<details><summary>Every view (RGB, units of the sun's illuminance)</summary>\n<table>\n" +
       header({"sun", "elevation", "azimuth", "LUT", "path traced", "CI95", "LUT orders 1-2",
               "path traced 2", "LUT single", "quadrature single"});
  auto rgb = [](const nlohmann::json& v) {
    return fmt::format("{:.4g} {:.4g} {:.4g}", v[0].get<double>(), v[1].get<double>(),
                       v[2].get<double>());
  };
  for (const auto& v : sky["views"])
    s += row({num(v["sun_elevation_deg"]), num(v["view_elevation_deg"]), num(v["view_azimuth_deg"]),
              rgb(v["lut"]), rgb(v["path_traced"]), rgb(v["path_traced_ci95"]),
              rgb(v["lut_second_order"]), rgb(v["path_traced_2"]), rgb(v["lut_single"]),
              rgb(v["quadrature_single"])});
  return s + "</table>\n</details>\n";
}

// The sky_irradiance section's table of texels, each error apart.
std::string sky_irradiance_texels(const nlohmann::json& texels) {
  std::string s = "<table>\n" + header({"altitude (m)", "sun zenith (deg)", "decode RMS",
                                        "decode max", "L2 limit RMS", "L2 limit max",
                                        "between texels RMS", "between texels max"});
  for (const auto& x : texels)
    s += row({num(x["altitude_m"]), num(x["sun_zenith_deg"]), pct(x["decode"]["rms"]),
              pct(x["decode"]["max"]), pct(x["l2_limit"]["rms"]), pct(x["l2_limit"]["max"]),
              pct(x["interpolation"]["rms"]), pct(x["interpolation"]["max"])});
  return s + "</table>\n";
}

// The sky_irradiance section (sky_irradiance.hpp): per measured texel the
// three errors apart, the decode against the path tracer, L2's own limit
// (the best 9-coefficient fit of the reference) and the bilinear read
// between texels, relative to the mean E over the normals.
std::string sky_irradiance_section(const nlohmann::json& si, bool quick) {
  std::string s = "<h2 id=\"sky_irradiance\">Sky irradiance: L2 SH against the path tracer</h2>\n";
  if (si.is_null()) return s + "<p>Not run (sky_irradiance was not selected).</p>\n";
  const auto& pt = si["path_tracer"];
  s += fmt::format(
      "<p>Table {} (sun zenith x altitude), radiance from the {} source, baked in {} s. "
      "Reference: E(n) at {} normals per texel from the path tracer's radiance on {} + {} "
      "zenith rays x {} azimuths, {} paths per ray and channel. Errors are relative to the "
      "mean E over the normals.</p>\n",
      prose(si["size"], "size"), text(si["radiance_source"]), num(si["bake_seconds"]),
      prose(pt["normals"]), prose(pt["rays_below"]), prose(pt["rays_above"]),
      prose(pt["azimuths"]), prose(pt["samples"]));
  if (quick) s += kQuickTargets;
  const auto& t = si["target"];
  std::string status = t.value("status", "not measured");
  std::string cls = status == "met" ? "met" : (status == "missed" ? "notmet" : "");
  if (quick && status != "met") status = "not judged by a quick run", cls = "";
  s += fmt::format("<p>Target ({}): <span class=\"{}\">{}</span> (worst decode RMS {}).</p>\n",
                   text(t["what"]), cls, status, pct(t["worst_rms"]));
  s += sky_irradiance_texels(si["texels"]);
  if (si.contains("twilight_texels") && !si["twilight_texels"].empty()) {
    const auto& tw = si["twilight_target"];
    const std::string tw_status = tw.value("status", "not measured");
    s += fmt::format(
        "<p>Twilight, {} paths per ray and channel. Target ({}): <span class=\"{}\">{}</span> "
        "(worst excess over it {}).</p>\n",
        prose(si["twilight_path_tracer_samples"]), text(tw["what"]),
        tw_status == "met" ? "met" : "notmet", tw_status, pct(tw["worst_excess"]));
    s += sky_irradiance_texels(si["twilight_texels"]);
  }
  return s;
}

std::string precision_section(const nlohmann::json& precision) {
  std::string s = "<h2 id=\"precision\">Where float32 and half lose</h2>\n";
  const auto& h = precision["horizon_transmittance"];
  if (!h.is_null()) {
    s += "<h3>Transmittance between two points near the horizon</h3>\n<p class=\"note\">" +
         text(h["what"]) + "; reference " + text(h["reference"]) + "; camera altitudes " +
         prose(h["altitudes_m"]) + " m; path fractions " + prose(h["path_fractions"]) +
         ". Relative errors divide by max(T, 1e-6); lost = cases with T &gt; 1e-6 off by "
         "more than 50 %; underflow = cases whose denominator is 0 in that storage.</p>\n";
    s += "<table>\n" +
         header({"elevation (deg)", "cases", "T min", "T max", "LUT max rel", "LUT lost",
                 "LUT half max rel", "LUT half lost", "exact float32 max rel", "float32 underflow",
                 "exact half max rel", "half underflow"});
    for (const auto& r : h["rows"])
      s += row({num(r["elevation_deg"]), text(r["cases"]), num(r["reference_min"]),
                num(r["reference_max"]), num(r["lut"]["max_rel"]), text(r["lut"]["lost"]),
                num(r["lut_half"]["max_rel"]), text(r["lut_half"]["lost"]),
                num(r["exact_float"]["max_rel"]), text(r["exact_float"]["underflow"]),
                num(r["exact_half"]["max_rel"]), text(r["exact_half"]["underflow"])});
    s += "</table>\n";
  }
  s += "<h3>Each table stored as half</h3>\n<table>\n" +
       header({"product", "float32 max rel", "half max rel", "float32 rms rel", "half rms rel",
               "values", "flushed to 0", "subnormal", "overflow", "max round trip (normal)"});
  for (const auto& p : precision["half"])
    s += row({text(p["product"]), num(p["float"]["max_rel"]), num(p["half"]["max_rel"]),
              num(p["float"]["rms_rel"]), num(p["half"]["rms_rel"]), text(p["storage"]["values"]),
              text(p["storage"]["flushed_to_zero"]), text(p["storage"]["subnormal"]),
              text(p["storage"]["overflow"]), num(p["storage"]["max_rel_round_trip_normal"])});
  return s + "</table>\n";
}

std::string bruneton_section(const nlohmann::json& b, bool quick) {
  std::string s = "<h2 id=\"bruneton\">Hillaire vs Bruneton against the path tracer</h2>\n";
  if (b.is_null() || b["status"] != "measured")
    return s + "<p>" + (b.is_null() ? std::string("not run") : text(b.value("reason", ""))) +
           "</p>\n";
  const auto& t = b["bruneton"];
  s += fmt::format(
      "<p>Bruneton's 4D table ({}): shape {}, {} orders used (last residual {}), single Mie "
      "{}, baked in {} s. Same views and path-traced references as the sky radiance "
      "section.</p>\n",
      text(t["source"]), prose(t["shape"], "size"), prose(t["orders_used"]), num(t["last_residual"]),
      t["mie"] == "alpha" ? "extrapolated from alpha" : "from its own table",
      num(t["bake_seconds"]));
  s += radiance_table("Hillaire 2020 (sky-view + Psi_ms)", b["hillaire"]);
  if (quick) s += kQuickTargets;
  s += target_paragraph("Bruneton's table as read", b["target"], quick);
  s += target_paragraph("Bruneton's table with single Mie from its own texture",
                        b["exact_mie_target"], quick);
  s += target_paragraph("sky-view single + Bruneton orders \u2265 2", b["hybrid_target"], quick);
  s += radiance_table("Bruneton 2017 (4D table of orders)", b["bruneton_vs_path_tracer"]);
  s += radiance_table("Bruneton 2017, single Mie from its own texture (no alpha extrapolation)",
                      b["bruneton_exact_mie_vs_path_tracer"]);
  s += radiance_table("Sky-view single scattering + Bruneton orders \u2265 2",
                      b["skyview_single_plus_bruneton_multiple_vs_path_tracer"]);
  for (const auto& x : b["bruneton_by_sun"])
    s += radiance_table(fmt::format("Bruneton, sun at {} deg", num(x["sun_elevation_deg"])),
                        x["bruneton"]);
  return s;
}

}  // namespace

std::string report_html(const nlohmann::json& report) {
  std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  s += "<title>skybake report: " + text(report["scene"]) + "</title>\n" + kStyle +
       "</head>\n<body>\n";
  s += "<h1>skybake report: " + text(report["scene"]) + "</h1>\n";
  s += fmt::format("<p class=\"note\">Preset {}; {}; level {}; {} s.</p>\n", text(report["preset"]),
                   text(report["tool"]), text(report["level"]), num(report["seconds"]));
  s += "<p>Errors are measured the way an engine sees them: each table is read with its lookup "
       "(interpolation included) at pseudo-random query points and compared with an independent "
       "reference; relative errors divide by max(|reference|, 1e-3 x the largest reference). "
       "Times are wall seconds of one bake. See docs/report.md.</p>\n";
  s += summary_table(report);
  for (const auto& p : report["products"])
    if (p["kind"] == "lut") s += product_section(p);
  const bool quick = report.value("level", "") == "quick";
  s += sky_section(report["sky_radiance"], quick);
  s += hillaire_runtime_section(report["hillaire_runtime"], quick);
  if (report.contains("sky_irradiance"))
    s += sky_irradiance_section(report["sky_irradiance"], quick);
  s += precision_section(report["precision"]);
  s += bruneton_section(report["bruneton_comparison"], quick);
  if (report.contains("colour")) s += colour_html(report["colour"]);
  if (report["files"].contains("preview"))
    s += "<h2>Sky previews</h2>\n<p>High sun, 10 deg, sunset, below the horizon, from space "
         "(rendered from the operating-point tables).</p>\n<img src=\"" +
         text(report["files"]["preview"]) + "\" alt=\"sky previews\">\n";
  return s + "</body>\n</html>\n";
}

}  // namespace skybake
