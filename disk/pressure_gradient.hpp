#pragma once
//! The pressure-gradient parameter eta (spec §1.4; Weidenschilling 1977): the gas,
//! partly supported by its pressure, orbits at (1 - eta) v_K, so the solids feel a
//! headwind eta v_K. The one place the formula is written; the gradient itself comes
//! from the caller (centred differences at the cell centres, dlnp_dlnr_centres; the two
//! neighbouring centres at a face, DustTransport).

namespace panoptic {

//! eta = -1/2 (H/r)^2 dlnP/dlnr [-] (spec §1.4) for h_over_r_sq = (H/r)^2. The law is
//! linear in (H/r)^2: given s (H/r)^2 it returns s eta (DustTransport passes (H/r)^2 v_K
//! per face and gets the headwind eta v_K). T: double, or AD where dlnP/dlnr follows an
//! evolving Sigma_g.
template <class T>
T pressure_gradient_eta(double h_over_r_sq, const T& dlnp_dlnr) {
  return -0.5 * h_over_r_sq * dlnp_dlnr;
}

}  // namespace panoptic
