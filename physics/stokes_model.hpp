#pragma once
//! Where the transport gets the Stokes number of the dust in a cell. The engine's scenes
//! prescribe it (constant or a radial power law, PrescribedStokes); the porous growth
//! model computes it from the particle mass and filling factor in the cell state (spec
//! §2). Both a double and an AD overload, so transport Jacobians stay exact.
#include <vector>

#include "src/core/autodiff.hpp"

namespace panoptic {

class StokesModel {
 public:
  virtual ~StokesModel() = default;
  //! Stokes number of the dust in `cell`, whose state is `ycell`.
  virtual double St(int cell, const double* ycell) const = 0;
  virtual AD St(int cell, const AD* ycell) const = 0;
};

//! St = St_1au (r_c / au)^slope, independent of the state.
class PrescribedStokes : public StokesModel {
 public:
  explicit PrescribedStokes(std::vector<double> st_per_cell)
      : st_(std::move(st_per_cell)) {}
  double St(int cell, const double*) const override { return st_[cell]; }
  AD St(int cell, const AD*) const override { return AD(st_[cell]); }

 private:
  std::vector<double> st_;
};

}  // namespace panoptic
