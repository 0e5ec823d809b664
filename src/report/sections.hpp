// The sections of `skybake report` in one table (sections.cpp), in the order
// they run: each row names the section, the products it covers, where its
// JSON goes in report.json, its quick and full setup and the function that
// runs it. A new section is one row and its own file.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report/setup.hpp"

namespace skybake {

struct ReportSection {
  std::string name;
  // The section runs when the report covers one of these products; empty:
  // whenever a section with products runs (it reads their tables or JSON).
  std::vector<std::string> products;
  // A JSON pointer into report.json; "/products/-" appends a product's entry
  // (and marks its products measured). A result with a "half" object is also
  // listed in "precision"."half".
  std::string place;
  // The setup of each level: its keys are the section's "level_settings".
  nlohmann::json quick, full;
  // Reads its setup from the run's level settings (level_settings below).
  std::function<nlohmann::json(const ReportInputs&, const nlohmann::json& settings)> run;
};

// A section whose setup is a struct with to_json / from_json (the field names
// are the level_settings keys).
template <typename Setup>
ReportSection make_section(std::string name, std::vector<std::string> products, std::string place,
                           const Setup& quick, const Setup& full,
                           nlohmann::json (*run)(const ReportInputs&, const Setup&)) {
  return {std::move(name),
          std::move(products),
          std::move(place),
          quick,
          full,
          [run](const ReportInputs& in, const nlohmann::json& settings) {
            return run(in, settings.get<Setup>());
          }};
}

// A section with no settings of its own.
inline ReportSection make_section(std::string name, std::vector<std::string> products,
                                  std::string place, nlohmann::json (*run)(const ReportInputs&)) {
  return {std::move(name),
          std::move(products),
          std::move(place),
          nlohmann::json::object(),
          nlohmann::json::object(),
          [run](const ReportInputs& in, const nlohmann::json&) { return run(in); }};
}

const std::vector<ReportSection>& report_sections();

// report.json's "level_settings" of a run: the shared ReportLevel and every
// section's setup, at the quick or full level.
nlohmann::json level_settings(bool quick);

// True when a section appends `product`'s entry to "products" (a ladder).
bool is_measured(const std::string& product);

// True when the report runs `section` for the products it covers.
bool section_runs(const ReportSection& section, const std::vector<std::string>& products);

}  // namespace skybake
