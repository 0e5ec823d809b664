#include "report/ladders.hpp"

#include <fmt/format.h>

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

}  // namespace skybake
