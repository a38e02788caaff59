#pragma once
//! Where the gas surface density of a cell comes from: a state variable when the scene
//! evolves the gas (gas.evolve, spec §1.2), else the static profile. Templated reads so
//! that face fluxes can be differentiated exactly (src/core/autodiff.hpp).
#include <vector>

namespace panoptic {

struct GasColumn {
  int slot = -1;                     //!< Sigma_g slot in the cell state; -1 = static gas
  std::vector<double> static_sigma;  //!< static Sigma_g per cell [g cm^-2]

  bool evolves() const { return slot >= 0; }
  //! Sigma_g of `cell` whose state is `ycell` [g cm^-2].
  template <class T>
  T sigma(int cell, const T* ycell) const {
    return slot >= 0 ? ycell[slot] : T(static_sigma[cell]);
  }
};

}  // namespace panoptic
