#include "physics/modules/planetesimal_channels.hpp"

namespace panoptic {

PlanetesimalChannels::PlanetesimalChannels(StateLayout& layout,
                                           const PlanetesimalOptions& options,
                                           double sigma_scale)
    : opt_(options) {
  // Sigma_pl only books what the channels convert (no right-hand side reads it back): a
  // quadrature, left out of CVODE's error test (VarInfo::error_test): its error feeds
  // nothing back, and in the test it only costs steps, while the outcomes move no more
  // than a change of round-off moves them and the dust budget closes to round-off
  // (tests/bench/results/performance_log.md). Nor does it carry CVODE's non-negativity
  // constraint: with no error weight, CVODE would clip any negative excursion to zero
  // without limit (its constraint correction is accepted when small in the weighted
  // norm), and each clip loses mass from the budget. Sigma_pl dips below zero only
  // where Sigma_d itself sits within its tolerance of zero.
  if (opt_.coagulation)
    coag_slot_ =
        layout.add_cell_var({"sigma_pl_coag", "g cm^-2",
                             "planetesimals formed by direct coagulation (spec §7.1)",
                             sigma_scale, false, false});
  if (opt_.si != StreamingInstability::kNone)
    si_slot_ = layout.add_cell_var({"sigma_pl_si", "g cm^-2",
                                    "planetesimals formed by the streaming instability "
                                    "(spec §7.2)",
                                    sigma_scale, false, false});
}

std::vector<OutputField> PlanetesimalChannels::channel_fields(
    const StateLayout& layout) const {
  const int n = layout.n_cells();
  const std::size_t cells = static_cast<std::size_t>(n);
  // Sigma_pl of the channel in `slot` at every cell centre [g cm^-2]; empty when off
  const auto sigma = [&layout, n](std::span<const double> y, int slot) {
    std::vector<double> out(slot < 0 ? 0 : n);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = y[layout.index(int(i), slot)];
    return out;
  };
  std::vector<OutputField> fields{
      {"sigma_pl", cells, "g cm^-2", "planetesimal surface density, all channels",
       [this, n, sigma](std::span<const double> y) {
         const auto c = sigma(y, coag_slot_), s = sigma(y, si_slot_);
         std::vector<double> total(n, 0.0);
         for (int i = 0; i < n; ++i)
           total[i] = (c.empty() ? 0.0 : c[i]) + (s.empty() ? 0.0 : s[i]);
         return total;
       }}};
  if (coag_slot_ >= 0)
    fields.push_back(
        {"sigma_pl_coag", cells, "g cm^-2", "planetesimals by direct coagulation",
         [this, sigma](std::span<const double> y) { return sigma(y, coag_slot_); }});
  if (si_slot_ >= 0)
    fields.push_back(
        {"sigma_pl_si", cells, "g cm^-2", "planetesimals by streaming instability",
         [this, sigma](std::span<const double> y) { return sigma(y, si_slot_); }});
  return fields;
}

}  // namespace panoptic
