#pragma once
//! Spectral indices of `panoptic observe` between every pair of wavelengths (shorter
//! first): alpha = ln(I1/I2) / ln(nu1/nu2), NaN where either intensity is not positive.
#include <cstddef>
#include <vector>

#include "src/observe/emission.hpp"
#include "src/observe/sky_images.hpp"

namespace panoptic {

//! Per pair p: pairs_mm[2p], pairs_mm[2p+1] (shorter, longer); profile [pair][bin],
//! model [pair][cell], total [pair].
struct SpectralIndex {
  std::size_t n_pairs = 0;
  std::vector<double> pairs_mm;
  std::vector<double> profile;  //!< of the convolved radial profiles
  std::vector<double> model;    //!< of the model intensity at the cell centres
  std::vector<double> total;    //!< of the total fluxes of the model images
};

SpectralIndex spectral_index(const std::vector<double>& lambda_mm, const CellEmission& e,
                             const SkyImages& im);

}  // namespace panoptic
