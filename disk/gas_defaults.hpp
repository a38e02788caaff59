#pragma once
//! The default gas of a scene: the one statement of these values. The scene schema
//! (src/scene: disk.T_1au, disk.mu, ...), the ThermalParams initialisers
//! (disk/gas_disk.hpp) and make_local_gas() (disk/local_gas.hpp) read them from here.
//! Plain constants: this header includes nothing, so every layer may use it.

namespace panoptic::gas_defaults {

//! Temperature at 1 au for L_* = L_sun [K] (spec §1.3, §10.1: T = 280 (r/au)^-1/2 K).
inline constexpr double kT1au = 280.0;
//! Temperature power-law exponent, T ∝ r^-q (spec §1.3: q = 1/2).
inline constexpr double kQ = 0.5;
//! Temperature floor [K] (spec §1.3: T >= 10 K).
inline constexpr double kTFloor = 10.0;
//! Mean molecular weight [-] (spec §1.1, §10.1).
inline constexpr double kMu = 2.34;
//! Shakura-Sunyaev alpha [-] (spec §1.5, §10.1: fiducial 1e-3).
inline constexpr double kAlpha = 1e-3;
//! Molecular collision cross-section of H2 [cm^2] (spec §1.6).
inline constexpr double kSigmaMol = 2e-15;
//! Water-ice sublimation temperature [K] (spec §1.7).
inline constexpr double kTSub = 170.0;

}  // namespace panoptic::gas_defaults
