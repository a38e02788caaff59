#include "disk/radial_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "src/core/units.hpp"

namespace panoptic {

RadialTable::RadialTable(std::vector<double> r, std::vector<double> value,
                         const std::string& what)
    : r_(std::move(r)), v_(std::move(value)) {
  if (r_.size() != v_.size())
    throw std::invalid_argument(what + ": " + std::to_string(r_.size()) + " radii for " +
                                std::to_string(v_.size()) + " values");
  if (r_.size() < 2)
    throw std::invalid_argument(what + ": needs at least two rows to interpolate, has " +
                                std::to_string(r_.size()));
  for (std::size_t i = 0; i < r_.size(); ++i) {
    const std::string row = "row " + std::to_string(i + 1) + ": ";
    if (!(r_[i] > 0.0) || !std::isfinite(r_[i]))
      throw std::invalid_argument(row + "the radius must be a finite number > 0");
    if (i > 0 && !(r_[i] > r_[i - 1]))
      throw std::invalid_argument(
          row +
          "the radii must be strictly increasing (this one is not larger than the "
          "row before); sort the rows by radius and remove repeated radii");
    if (!(v_[i] > 0.0) || !std::isfinite(v_[i]))
      throw std::invalid_argument(row + what +
                                  " must be a finite number > 0 (it is interpolated "
                                  "in its logarithm)");
  }
  ln_r_.resize(r_.size());
  ln_v_.resize(r_.size());
  for (std::size_t i = 0; i < r_.size(); ++i) {
    ln_r_[i] = std::log(r_[i]);
    ln_v_[i] = std::log(v_[i]);
  }
}

std::size_t RadialTable::interval(double r) const {
  constexpr double kEdge = 1e-12;  // the grid's edges r_in, r_out carry round-off
  if (!(r >= r_.front() * (1.0 - kEdge) && r <= r_.back() * (1.0 + kEdge)))
    throw std::out_of_range("radius " + std::to_string(r / units::kAu) +
                            " au outside the table (" +
                            std::to_string(r_.front() / units::kAu) + " to " +
                            std::to_string(r_.back() / units::kAu) + " au)");
  const auto it = std::upper_bound(r_.begin(), r_.end(), r);
  const std::size_t hi = std::clamp<std::size_t>(it - r_.begin(), 1, r_.size() - 1);
  return hi - 1;
}

double RadialTable::slope(std::size_t i) const {
  return (ln_v_[i + 1] - ln_v_[i]) / (ln_r_[i + 1] - ln_r_[i]);
}

double RadialTable::operator()(double r) const {
  const std::size_t i = interval(r);
  return std::exp(ln_v_[i] + slope(i) * (std::log(r) - ln_r_[i]));
}

double RadialTable::annulus_integral(double r1, double r2) const {
  // value = v(a) (r/a)^k on [a, b] inside one interval:
  // int v 2 pi r dr = 2 pi v(a) a^2 expm1((k + 2) ln(b/a)) / (k + 2)
  double total = 0.0;
  double a = r1;
  while (a < r2) {
    const std::size_t i = interval(a);
    const double b = std::min(r2, i + 2 < r_.size() ? r_[i + 1] : r2);
    const double k2 = slope(i) + 2.0, ln_ratio = std::log(b / a);
    const double scale = 2.0 * units::kPi * (*this)(a)*a * a;
    total += k2 == 0.0 ? scale * ln_ratio : scale * std::expm1(k2 * ln_ratio) / k2;
    if (b <= a) break;
    a = b;
  }
  return total;
}

double RadialTable::first_fall_to(double level) const {
  if (v_.front() <= level) return 0.0;
  const double ln_level = std::log(level);
  for (std::size_t i = 0; i + 1 < r_.size(); ++i)
    if (v_[i + 1] <= level) return std::exp(ln_r_[i] + (ln_level - ln_v_[i]) / slope(i));
  return std::numeric_limits<double>::infinity();
}

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

}  // namespace

std::vector<std::vector<double>> read_csv_columns(const std::filesystem::path& file,
                                                  const std::vector<std::string>& names) {
  const std::string expect = "; the header must name the columns " + joined(names) +
                             " (with these units, in any order)";
  std::ifstream in(file);
  if (!in)
    throw std::invalid_argument("cannot open " + file.string() +
                                " (no such file, or not readable); give the path of a "
                                "CSV file, relative to the scene file that sets the key");
  std::vector<int> column_of;  // for each of `names`, its column in the file
  std::vector<std::vector<double>> out(names.size());
  std::string line;
  std::size_t n_fields = 0;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::string where = file.string() + ":" + std::to_string(line_no) + ": ";
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto fields = split_fields(line);
    if (column_of.empty()) {  // the header
      n_fields = fields.size();
      for (const auto& f : fields)
        if (std::find(names.begin(), names.end(), f) == names.end())
          throw std::invalid_argument(where + "unknown column \"" + f + "\"" + expect);
      for (const auto& n : names) {
        const auto at = std::find(fields.begin(), fields.end(), n);
        if (at == fields.end())
          throw std::invalid_argument(where + "no column \"" + n + "\"" + expect);
        if (std::find(at + 1, fields.end(), n) != fields.end())
          throw std::invalid_argument(where + "column \"" + n + "\" twice" + expect);
        column_of.push_back(int(at - fields.begin()));
      }
      continue;
    }
    if (fields.size() != n_fields)
      throw std::invalid_argument(where + std::to_string(fields.size()) +
                                  " fields where the header has " +
                                  std::to_string(n_fields) + "; fix the row");
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& f = fields[column_of[k]];
      char* end = nullptr;
      const double x = std::strtod(f.c_str(), &end);
      if (f.empty() || end != f.c_str() + f.size() || !std::isfinite(x))
        throw std::invalid_argument(where + names[k] + " = \"" + f +
                                    "\" is not a finite number; fix the row");
      out[k].push_back(x);
    }
  }
  if (column_of.empty())
    throw std::invalid_argument(file.string() + ": no header line" + expect);
  return out;
}

}  // namespace panoptic
