#include "src/grid.hpp"

#include <algorithm>
#include <cmath>

#include "src/units.hpp"

namespace panoptic {

Grid::Grid(double r_in, double r_out, int n)
    : n_(n), dlnr_(std::log(r_out / r_in) / n), r_c_(n), r_f_(n + 1), area_(n) {
  for (int i = 0; i <= n; ++i) r_f_[i] = r_in * std::exp(dlnr_ * i);
  r_f_[n] = r_out;  // exact outer edge, whatever the rounding of exp
  for (int i = 0; i < n; ++i) {
    r_c_[i] = std::sqrt(r_f_[i] * r_f_[i + 1]);
    area_[i] = units::kPi * (r_f_[i + 1] * r_f_[i + 1] - r_f_[i] * r_f_[i]);
  }
}

int Grid::cell_of(double r) const {
  const auto it = std::upper_bound(r_f_.begin(), r_f_.end(), r);
  const int i = static_cast<int>(it - r_f_.begin()) - 1;
  return std::clamp(i, 0, n_ - 1);
}

}  // namespace panoptic
