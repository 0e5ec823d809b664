// The report page of `skybake report` (report.hpp): one HTML file with no
// external resources but the preview PNG beside it. Per product an inline
// SVG log-log plot of error against bake time (every ladder point; the
// Pareto front as a line; the operating point highlighted) and the ladder
// table; the sky radiance tables with the path tracer's confidence; the
// float32 / half findings; the sky previews. Built from report.json alone, so
// the page and the file never disagree.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace skybake {

std::string report_html(const nlohmann::json& report);

// One plotted point of a log-log chart (x and y > 0; others are skipped).
struct PlotPoint {
  double x = 0.0, y = 0.0;
  bool highlight = false;  // drawn larger, in the accent colour
  bool front = false;      // joined by the front line
  bool secondary = false;  // hollow marker (a second series)
  std::string title;       // tooltip
};

// An inline <svg> log-log chart with decade grid lines and axis labels.
std::string loglog_svg(const std::vector<PlotPoint>& points, const std::string& x_label,
                       const std::string& y_label);

// Text safe inside HTML elements and attributes.
std::string html_escape(const std::string& text);

}  // namespace skybake
