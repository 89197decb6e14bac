// CSV input and JSON output of top_sim_fit.
#include "fit_data.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <nlohmann/json.hpp>

namespace top_sim {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r\"");
    const auto e = cell.find_last_not_of(" \t\r\"");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool skip(const std::string& line) {
  const auto b = line.find_first_not_of(" \t\r");
  return b == std::string::npos || line[b] == '#';
}

// strtod on the whole cell; "nan" and "inf" parse (the fits reject them as non-finite, by name).
bool parse_number(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

}  // namespace

bool CsvColumns::has(const std::string& name) const {
  for (const auto& n : names)
    if (n == name) return true;
  return false;
}

const std::vector<double>& CsvColumns::column(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return values[i];
  throw FitError("no column '" + name + "'");
}

CsvColumns read_csv_columns(std::istream& in, const std::string& source, const std::vector<std::string>& required,
                            const std::vector<std::string>& optional) {
  std::string line;
  while (std::getline(in, line) && skip(line)) {}
  if (skip(line)) throw FitError(source + ": empty file; needs a header row naming the columns");
  const std::vector<std::string> header = split(line);
  CsvColumns c;
  std::vector<std::size_t> index;
  auto find = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<long>(i);
    return -1L;
  };
  for (const auto& name : required) {
    const long i = find(name);
    if (i < 0) throw FitError(source + ": missing column '" + name + "' in the header row '" + line + "'");
    c.names.push_back(name), index.push_back(static_cast<std::size_t>(i));
  }
  for (const auto& name : optional)
    if (const long i = find(name); i >= 0) c.names.push_back(name), index.push_back(static_cast<std::size_t>(i));
  c.values.resize(c.names.size());
  for (std::size_t row = 1; std::getline(in, line); ++row) {
    if (skip(line)) continue;
    const std::vector<std::string> cells = split(line);
    for (std::size_t k = 0; k < index.size(); ++k) {
      double v = 0.0;
      const std::string cell = index[k] < cells.size() ? cells[index[k]] : "";
      if (!parse_number(cell, v))
        throw FitError(source + ": row " + std::to_string(row) + ", column '" + c.names[k] + "': '" + cell +
                       "' is not a number");
      c.values[k].push_back(v);
    }
  }
  return c;
}

std::vector<StationaryMeasurement> read_stationary_data(std::istream& in, const std::string& source) {
  const CsvColumns c = read_csv_columns(in, source, {"alpha", "phi"}, {"sigma_alpha", "sigma_phi"});
  if (c.has("sigma_alpha") != c.has("sigma_phi"))
    throw FitError(source + ": give both columns sigma_alpha and sigma_phi, or neither");
  std::vector<StationaryMeasurement> out(c.column("alpha").size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].alpha = c.column("alpha")[i];
    out[i].phi = c.column("phi")[i];
    if (c.has("sigma_alpha")) {
      out[i].sigma_alpha = c.column("sigma_alpha")[i];
      out[i].sigma_phi = c.column("sigma_phi")[i];
      if (!(out[i].sigma_alpha > 0.0) || !(out[i].sigma_phi > 0.0))
        throw FitError(source + ": row " + std::to_string(i + 1) + ": sigma_alpha and sigma_phi must be > 0");
    }
  }
  return out;
}

std::vector<ContactSample> read_trajectory_data(std::istream& in, const std::string& source) {
  const CsvColumns c = read_csv_columns(in, source, {"t", "contact_x", "contact_y"});
  std::vector<ContactSample> out(c.column("t").size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = {c.column("t")[i], c.column("contact_x")[i], c.column("contact_y")[i]};
  return out;
}

std::string fit_json(const FitResult& r, const std::string& kind, double cpu_seconds) {
  using Json = nlohmann::ordered_json;  // members in the documented order (docs/analysis.md)
  auto object = [&r](auto value_of) {  // {name: value_of(i)} over the fitted parameters
    Json o = Json::object();
    for (std::size_t i = 0; i < r.names.size(); ++i) o[r.names[i]] = value_of(static_cast<Eigen::Index>(i));
    return o;
  };
  const Json o = {  // a number that is not finite is written as null
      {"fit", kind},
      {"parameters", object([&](Eigen::Index i) { return r.values[i]; })},
      {"uncertainties", object([&](Eigen::Index i) { return r.errors[i]; })},
      {"covariance",
       object([&](Eigen::Index i) { return object([&](Eigen::Index j) { return r.covariance(i, j); }); })},
      {"chi2", r.chi2}, {"dof", r.dof}, {"sigma_known", r.sigma_known}, {"at_bound", r.at_bound},
      {"converged", r.converged}, {"solver_message", r.message}, {"evaluations", r.evaluations},
      {"cpu_seconds", cpu_seconds}};
  return o.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace top_sim
