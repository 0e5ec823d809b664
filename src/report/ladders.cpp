#include "report/ladders.hpp"

#include <cmath>

#include <fmt/format.h>

#include "atmosphere/geometry.hpp"
#include "core/math.hpp"
#include "report/stats.hpp"

namespace skybake {

std::string settings_label(const nlohmann::json& settings) {
  std::string label;
  for (const auto& [key, value] : settings.items()) {
    if (!label.empty()) label += ' ';
    label += key + '=';
    if (value.is_array()) {
      for (size_t i = 0; i < value.size(); ++i) label += (i ? "x" : "") + value[i].dump();
    } else {
      label += value.dump();
    }
  }
  return label;
}

nlohmann::json run_ladder(const std::string& product, const nlohmann::json& axes,
                          const std::vector<nlohmann::json>& grid, const nlohmann::json& operating,
                          const LadderMeasure& measure, const ReportInputs& in) {
  std::vector<nlohmann::json> settings = grid;
  size_t op = settings.size();
  for (size_t i = 0; i < settings.size(); ++i)
    if (settings[i] == operating) op = i;
  if (op == settings.size()) settings.push_back(operating);

  nlohmann::json ladder = nlohmann::json::array();
  for (size_t i = 0; i < settings.size(); ++i) {
    in.stage(fmt::format("{} ladder {}/{}: {}", product, i + 1, settings.size(),
                         settings_label(settings[i])));
    nlohmann::json point = measure(settings[i]);
    point["label"] = settings_label(settings[i]);
    point["settings"] = settings[i];
    point["operating_point"] = i == op;
    ladder.push_back(std::move(point));
  }
  const std::vector<size_t> front = mark_pareto(ladder);
  return {{"axes", axes}, {"ladder", ladder}, {"operating_point", op}, {"pareto", front}};
}

ViewQuery view_query(const Atmosphere& atm, size_t index, uint32_t first_dim, double mu_s_min) {
  ViewQuery q;
  const double u = query_unit(index, first_dim);
  q.altitude_m = (atm.top_radius_m - atm.bottom_radius_m) * u * u;
  q.r = atm.bottom_radius_m + q.altitude_m;
  q.mu = 2.0 * query_unit(index, first_dim + 1) - 1.0;
  q.mu_s = mu_s_min + (1.0 - mu_s_min) * query_unit(index, first_dim + 2);
  q.nu = nu_from_azimuth(q.mu, q.mu_s, 2.0 * kPi * query_unit(index, first_dim + 3));
  q.hits_ground = ray_intersects_ground(atm.bottom_radius_m, q.r, q.mu);
  return q;
}

double nu_from_azimuth(double mu, double mu_s, double phi) {
  return clamp_cosine(mu * mu_s + safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s)) * std::cos(phi));
}

}  // namespace skybake
