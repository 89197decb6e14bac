// top_sim_fit's input: CSV files with a header row, read by column name (docs/interfaces.md).
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "top_sim/fit.hpp"

namespace top_sim {

// Numeric columns of a CSV table: `required` must be present, `optional` may be; other columns are ignored.
// Empty lines and lines starting with '#' are skipped. Throws FitError naming the file, the missing column, or the
// row (1 = the first line after the header) and column of a value that is not a number.
struct CsvColumns {
  std::vector<std::string> names;            // required then the optional ones found
  std::vector<std::vector<double>> values;   // values[column][row]
  bool has(const std::string& name) const;
  const std::vector<double>& column(const std::string& name) const;
};
CsvColumns read_csv_columns(std::istream& in, const std::string& source, const std::vector<std::string>& required,
                            const std::vector<std::string>& optional = {});

// Columns alpha, phi [, sigma_alpha, sigma_phi] (both or neither).
std::vector<StationaryMeasurement> read_stationary_data(std::istream& in, const std::string& source);
// Columns t, contact_x, contact_y (e.g. top_sim_run --csv; other columns ignored).
std::vector<ContactSample> read_trajectory_data(std::istream& in, const std::string& source);

// The JSON result: parameters, uncertainties, covariance (name -> name -> value), chi2, dof, cpu_seconds, ...
std::string fit_json(const FitResult& r, const std::string& kind, double cpu_seconds);

}  // namespace top_sim
