#pragma once
//! A positive quantity tabulated in radius (a CSV file: Sigma_g(r), T(r), alpha(r)),
//! interpolated linearly in ln r - ln value, i.e. as a power law between two rows, so
//! that a table of a power law reproduces it to round-off. No extrapolation: a radius
//! outside the table is an error (the scene checks that the table covers the grid).
#include <filesystem>
#include <string>
#include <vector>

namespace panoptic {

class RadialTable {
 public:
  //! r [cm], strictly increasing and > 0; value > 0 and finite; at least two rows.
  //! Throws std::invalid_argument naming the first bad row (1-based among the rows) and
  //! `what` (the column).
  RadialTable(std::vector<double> r, std::vector<double> value, const std::string& what);

  //! The value at r, log-log interpolated [unit of the column]; throws std::out_of_range
  //! outside [r_min, r_max] (beyond a relative 1e-12, the round-off of the grid's edges).
  double operator()(double r) const;
  //! Integral of value 2 pi r dr over [r1, r2] (inside the table), in closed form row by
  //! row (value ∝ r^k between two rows): the mass of an annulus for Sigma_g.
  double annulus_integral(double r1, double r2) const;
  //! The innermost radius where the value falls to `level` [cm]: 0 when it is <= level
  //! at r_min, +inf when it stays above it (the snow line of a T(r) table, spec §1.7).
  double first_fall_to(double level) const;

  double r_min() const { return r_.front(); }
  double r_max() const { return r_.back(); }
  const std::vector<double>& r() const { return r_; }
  const std::vector<double>& values() const { return v_; }

 private:
  //! The row interval [i, i+1] holding r (r inside the table).
  std::size_t interval(double r) const;
  //! Power-law exponent of interval i.
  double slope(std::size_t i) const;
  std::vector<double> r_, v_, ln_r_, ln_v_;
};

//! The columns of a CSV file, in the order of `names`: a header line naming the columns
//! with their units (e.g. "r_au,sigma_g_gcm2,T_K"; any order, each of `names` exactly
//! once, no other column), then one row of numbers per line. Blank lines and lines
//! starting with '#' are skipped. Throws std::invalid_argument saying what is wrong
//! (missing file, missing or unknown column, a field that is not a number, a short row),
//! with the line number, and the header it expects.
std::vector<std::vector<double>> read_csv_columns(const std::filesystem::path& file,
                                                  const std::vector<std::string>& names);

}  // namespace panoptic
