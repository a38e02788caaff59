#include "src/observe/spectral_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace panoptic {

SpectralIndex spectral_index(const std::vector<double>& lambda_mm, const CellEmission& e,
                             const SkyImages& im) {
  const std::size_t nl = lambda_mm.size(), n = e.n_cells, nb = im.r_mid_arcsec.size();
  std::vector<std::size_t> order(nl);
  for (std::size_t l = 0; l < nl; ++l) order[l] = l;
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return lambda_mm[x] < lambda_mm[y]; });
  const auto alpha = [](double i1, double i2, double nu1, double nu2) {
    return i1 > 0.0 && i2 > 0.0 ? std::log(i1 / i2) / std::log(nu1 / nu2)
                                : std::numeric_limits<double>::quiet_NaN();
  };
  SpectralIndex s;
  for (std::size_t p = 0; p < nl; ++p)
    for (std::size_t q = p + 1; q < nl; ++q) {
      const std::size_t l1 = order[p], l2 = order[q];
      const double nu1 = e.nu[l1], nu2 = e.nu[l2];
      s.pairs_mm.push_back(lambda_mm[l1]);
      s.pairs_mm.push_back(lambda_mm[l2]);
      for (std::size_t b = 0; b < nb; ++b)
        s.profile.push_back(alpha(im.profile_convolved[l1 * nb + b],
                                  im.profile_convolved[l2 * nb + b], nu1, nu2));
      for (std::size_t i = 0; i < n; ++i)
        s.model.push_back(
            alpha(e.intensity[l1 * n + i], e.intensity[l2 * n + i], nu1, nu2));
      s.total.push_back(alpha(im.flux_model[l1], im.flux_model[l2], nu1, nu2));
      ++s.n_pairs;
    }
  return s;
}

}  // namespace panoptic
