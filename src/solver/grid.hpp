#pragma once
//! Finite-volume radial grid (spec §6.4, §10.2). Immutable after construction.
//! Faces r_f[0..n] run from r_in to r_out, log-spaced (stretch 0) or with the spacing
//! d ln r ∝ r^stretch (faces uniform in r^-stretch): stretch > 0 refines the inner disk,
//! where growth fronts are narrowest. The centre of cell i is the geometric mean of its
//! faces; on the log-spaced grid every face is also the geometric mean of its two
//! neighbouring centres (face interpolation of power laws is then exact).
#include <vector>

namespace panoptic {

class Grid {
 public:
  //! r_in, r_out [cm], n cells, stretch: d ln r ∝ r^stretch (0: log-spaced).
  Grid(double r_in, double r_out, int n, double stretch = 0.0);

  int n_cells() const { return n_; }
  double r_c(int i) const { return r_c_[i]; }  //!< cell centre [cm]
  double r_f(int i) const { return r_f_[i]; }  //!< face i (left face of cell i) [cm]
  double area(int i) const {
    return area_[i];
  }  //!< annulus area pi (r_f(i+1)^2 - r_f(i)^2) [cm^2]
  double dlnr(int i) const {
    return dlnr_[i];
  }  //!< ln(r_f(i+1)/r_f(i)), the log width of cell i
  //! ln(r_c(i)/r_c(i-1)), the log distance between the centres either side of face i
  //! (i >= 1)
  double dlnr_centres(int i) const { return dlnr_c_[i]; }
  double stretch() const { return stretch_; }
  const std::vector<double>& centres() const { return r_c_; }
  const std::vector<double>& faces() const { return r_f_; }
  const std::vector<double>& areas() const { return area_; }
  //! Index of the cell that holds r (clamped to [0, n-1]).
  int cell_of(double r) const;

 private:
  int n_;
  double stretch_;
  std::vector<double> r_c_, r_f_, area_, dlnr_;
  std::vector<double> dlnr_c_;  // [i] = ln(r_c(i)/r_c(i-1)), i >= 1; [0] unused
};

}  // namespace panoptic
