#pragma once
//! Log-spaced finite-volume radial grid (spec §6.4, §10.2). Immutable after construction.
//! Faces r_f[0..n] are log-spaced between r_in and r_out; the centre of cell i is the
//! geometric mean of its faces, so on this grid every face is also the geometric mean of
//! its two neighbouring centres (this makes face interpolation of power laws exact).
#include <vector>

namespace panoptic {

class Grid {
 public:
  //! r_in, r_out [cm], n cells.
  Grid(double r_in, double r_out, int n);

  int n_cells() const { return n_; }
  double r_c(int i) const { return r_c_[i]; }  //!< cell centre [cm]
  double r_f(int i) const { return r_f_[i]; }  //!< face i (left face of cell i) [cm]
  double area(int i) const {
    return area_[i];
  }  //!< annulus area pi (r_f(i+1)^2 - r_f(i)^2) [cm^2]
  double dlnr() const { return dlnr_; }  //!< ln(r_f(i+1)/r_f(i))
  const std::vector<double>& centres() const { return r_c_; }
  const std::vector<double>& faces() const { return r_f_; }
  const std::vector<double>& areas() const { return area_; }
  //! Index of the cell that holds r (clamped to [0, n-1]).
  int cell_of(double r) const;

 private:
  int n_;
  double dlnr_;
  std::vector<double> r_c_, r_f_, area_;
};

}  // namespace panoptic
