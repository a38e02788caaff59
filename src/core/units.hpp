#pragma once
//! Physical constants and unit conversions, cgs. Values from spec §1.1.
namespace panoptic::units {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kG = 6.674e-8;     //!< gravitational constant [cm^3 g^-1 s^-2]
inline constexpr double kMsun = 1.989e33;  //!< solar mass [g]
inline constexpr double kLsun = 3.828e33;  //!< solar luminosity [erg s^-1]
inline constexpr double kAu = 1.496e13;    //!< astronomical unit [cm]
inline constexpr double kBoltzmann = 1.3807e-16;  //!< Boltzmann constant [erg K^-1]
inline constexpr double kMassH = 1.6735e-24;      //!< hydrogen-atom mass [g]
inline constexpr double kYr = 3.156e7;            //!< year [s]
inline constexpr double kMyr = 1e6 * kYr;         //!< megayear [s]
inline constexpr double kMearth = 5.972e27;       //!< Earth mass [g]

// radiation and the sky (panoptic observe)
inline constexpr double kPlanck = 6.62607015e-27;  //!< Planck constant [erg s] (SI 2019)
inline constexpr double kLightSpeed = 2.99792458e10;         //!< speed of light [cm s^-1]
inline constexpr double kJansky = 1e-23;                     //!< [erg s^-1 cm^-2 Hz^-1]
inline constexpr double kArcsecPerRad = 206264.80624709636;  //!< 180 * 3600 / pi

}  // namespace panoptic::units
