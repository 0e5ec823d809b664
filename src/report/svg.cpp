// The log-log chart of the report page (html.hpp).
#include <algorithm>
#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "report/html.hpp"

namespace skybake {

namespace {

constexpr double kWidth = 560, kHeight = 340;
constexpr double kLeft = 70, kRight = 20, kTop = 20, kBottom = 50;

// Whole decades around [lo, hi] (at least one decade wide).
std::pair<int, int> decades(double lo, double hi) {
  int a = int(std::floor(std::log10(lo))), b = int(std::ceil(std::log10(hi)));
  if (b <= a) b = a + 1;
  return {a, b};
}

std::string decade_label(int e) {
  if (e >= -2 && e <= 2) return fmt::format("{:g}", std::pow(10.0, e));
  return fmt::format("1e{}", e);
}

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string loglog_svg(const std::vector<PlotPoint>& points, const std::string& x_label,
                       const std::string& y_label) {
  std::vector<PlotPoint> pts;
  for (const PlotPoint& p : points)
    if (p.x > 0.0 && p.y > 0.0 && std::isfinite(p.x) && std::isfinite(p.y)) pts.push_back(p);
  double x_lo = INFINITY, x_hi = 0, y_lo = INFINITY, y_hi = 0;
  for (const PlotPoint& p : pts) {
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
  }
  if (pts.empty()) x_lo = y_lo = 0.1, x_hi = y_hi = 1.0;
  // Plain variables, not structured bindings: lambdas below capture them
  // (C++17 does not allow capturing a binding; clang refuses it).
  double xa, xb, ya, yb;
  std::tie(xa, xb) = decades(x_lo, x_hi);
  std::tie(ya, yb) = decades(y_lo, y_hi);
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  auto sx = [&](double x) { return kLeft + (std::log10(x) - xa) / (xb - xa) * pw; };
  auto sy = [&](double y) { return kTop + (yb - std::log10(y)) / (yb - ya) * ph; };

  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" class=\"plot\">\n"
      "<rect x=\"{2}\" y=\"{3}\" width=\"{4}\" height=\"{5}\" fill=\"#fff\" stroke=\"#888\"/>\n",
      kWidth, kHeight, kLeft, kTop, pw, ph);
  for (int e = xa; e <= xb; ++e) {
    const double x = sx(std::pow(10.0, e));
    s += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
        x, kTop, kTop + ph, kTop + ph + 16, decade_label(e));
  }
  for (int e = ya; e <= yb; ++e) {
    const double y = sy(std::pow(10.0, e));
    s += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
        kLeft, y, kLeft + pw, kLeft - 6, y + 4, decade_label(e));
  }
  s += fmt::format(
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n"
      "<text x=\"14\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 14 {})\">{}</text>\n",
      kLeft + pw / 2, kHeight - 10, html_escape(x_label), kTop + ph / 2, kTop + ph / 2,
      html_escape(y_label));

  std::vector<PlotPoint> front;
  for (const PlotPoint& p : pts)
    if (p.front) front.push_back(p);
  std::sort(front.begin(), front.end(),
            [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
  if (front.size() > 1) {
    s += "<polyline fill=\"none\" stroke=\"#2a7\" stroke-width=\"1.5\" points=\"";
    for (const PlotPoint& p : front) s += fmt::format("{:.1f},{:.1f} ", sx(p.x), sy(p.y));
    s += "\"/>\n";
  }
  for (const PlotPoint& p : pts) {
    const char* fill = p.secondary ? "none" : (p.highlight ? "#d22" : "#36c");
    const char* stroke = p.highlight ? "#d22" : "#36c";
    s += fmt::format(
        "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" stroke=\"{}\" "
        "stroke-width=\"{}\"><title>{}</title></circle>\n",
        sx(p.x), sy(p.y), p.highlight ? 6 : (p.secondary ? 3 : 4), fill, stroke,
        p.highlight ? 2 : 1, html_escape(p.title));
  }
  s += "</svg>\n";
  return s;
}

}  // namespace skybake
