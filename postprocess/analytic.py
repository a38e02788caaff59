"""Closed-form solutions used by the regression tests (pure numpy).

All functions broadcast over numpy arrays and work in any consistent unit system
(e.g. cgs): lengths share one unit L, times one unit T, diffusivities and
viscosities are in L^2 / T, and a mass M gives surface densities in M / L^2.
"""
import numpy as np

# Below this argument i0e uses the power series, above it the asymptotic series.
# At x = 20 the smallest asymptotic term is ~1e-18, so both branches are at
# rounding level there.
_I0E_SERIES_MAX_X = 20.0
_I0E_SERIES_TERMS = 60      # (x/2)^(2k)/(k!)^2 for k = 60, x = 20 is ~1e-30 of I0(20)
_I0E_ASYMPTOTIC_TERMS = 40  # terms k <= 40 decrease monotonically for x >= 20


def i0e(x):
    """Exponentially scaled modified Bessel function, exp(-|x|) I0(x) [dimensionless].

    |x| < 20: the power series I0(x) = sum_k (x/2)^(2k) / (k!)^2, summed with the
    factor exp(-|x|) folded into the first term (all terms positive, no overflow).
    |x| >= 20: the asymptotic expansion (Abramowitz & Stegun 9.7.1)
        exp(-x) I0(x) ~ (2 pi x)^(-1/2) sum_k [(2k-1)!!]^2 / (k! (8x)^k),
    truncated at 40 terms, where the omitted remainder is below double precision.
    Relative accuracy is ~1e-15 for all finite x.
    """
    x = np.abs(np.asarray(x, dtype=float))
    out = np.empty_like(x)
    small = x < _I0E_SERIES_MAX_X
    out[small] = _i0e_series(x[small])
    out[~small] = _i0e_asymptotic(x[~small])
    return out if out.ndim else out[()]


def _i0e_series(x):
    """exp(-x) I0(x) from the power series, for 0 <= x < ~20."""
    quarter_x2 = 0.25 * x * x
    term = np.exp(-x)
    total = term.copy()
    for k in range(1, _I0E_SERIES_TERMS + 1):
        term = term * quarter_x2 / (k * k)
        total += term
    return total


def _i0e_asymptotic(x):
    """exp(-x) I0(x) from the large-argument asymptotic series, for x >= ~20."""
    term = np.ones_like(x)
    total = term.copy()
    for k in range(1, _I0E_ASYMPTOTIC_TERMS + 1):
        term = term * (2 * k - 1) ** 2 / (8.0 * k * x)
        total += term
    return total / np.sqrt(2.0 * np.pi * x)


def ring_diffusion(r, t, r0, D, mass):
    """Surface density of a diffusing ring [M / L^2].

    A ring of total `mass` [M] placed at radius `r0` [L] at t = 0 spreads under the
    axisymmetric 2-D diffusion equation with constant diffusivity `D` [L^2 / T]:
        d(sigma)/dt = (1/r) d/dr (r D d(sigma)/dr).
    The solution is the instantaneous ring source of heat conduction (Carslaw &
    Jaeger 1959, "Conduction of Heat in Solids", 2nd ed., ch. 10), i.e. the azimuthal
    average of the 2-D point-source kernel mass / (4 pi D t) exp(-|x - x0|^2 / (4 D t)):
        sigma = mass / (4 pi D t) exp(-(r^2 + r0^2) / (4 D t)) I0(r r0 / (2 D t)),
    evaluated here as
        sigma = mass / (4 pi D t) exp(-(r - r0)^2 / (4 D t)) i0e(r r0 / (2 D t)),
    which neither overflows nor underflows for r0^2 >> D t.

    r [L], t [T] > 0. Integral of 2 pi r sigma dr over r in [0, inf) equals `mass`.
    """
    t = np.asarray(t, dtype=float)
    if np.any(t <= 0) or D <= 0:
        raise ValueError("ring_diffusion needs t > 0 and D > 0")
    four_dt = 4.0 * D * t
    r = np.asarray(r, dtype=float)
    return (mass / (np.pi * four_dt) * np.exp(-(r - r0) ** 2 / four_dt)
            * i0e(2.0 * r * r0 / four_dt))


def lbp_sigma(r, t, m_disk, r_c, nu_c, gamma=1.0):
    """Self-similar viscous accretion disk surface density [M / L^2].

    Lynden-Bell & Pringle (1974, MNRAS 168, 603) similarity solution in the form of
    Hartmann, Calvet, Gullbring & D'Alessio (1998, ApJ 495, 385, §3), for a
    viscosity nu = nu_c (r / r_c)^gamma:
        t_s   = r_c^2 / (3 (2 - gamma)^2 nu_c)          (viscous time at r_c)
        T     = 1 + t / t_s
        sigma = (2 - gamma) m_disk / (2 pi r_c^2) (r / r_c)^(-gamma)
                * T^(-(5/2 - gamma) / (2 - gamma)) exp(-(r / r_c)^(2 - gamma) / T).
    r [L], t [T] >= 0, m_disk [M] is the disk mass at t = 0, r_c [L] the initial
    scaling radius, nu_c [L^2 / T] the viscosity at r_c, gamma < 2.
    The disk mass decays as m_disk T^(-1 / (2 (2 - gamma))) (mass accreted onto the star).
    """
    if gamma >= 2.0:
        raise ValueError("lbp_sigma needs gamma < 2")
    two_m_g = 2.0 - gamma
    t_s = r_c ** 2 / (3.0 * two_m_g ** 2 * nu_c)
    big_t = 1.0 + np.asarray(t, dtype=float) / t_s
    x = np.asarray(r, dtype=float) / r_c
    return (two_m_g * m_disk / (2.0 * np.pi * r_c ** 2) * x ** (-gamma)
            * big_t ** (-(2.5 - gamma) / two_m_g) * np.exp(-x ** two_m_g / big_t))


def drift_velocity(St, eta, v_k, v_g=0.0):
    """Radial dust velocity in a gas disk [same unit as v_k], negative = inward.

        v_r = -2 St eta v_k / (1 + St^2) + v_g / (1 + St^2)
    (Weidenschilling 1977, MNRAS 180, 57; Nakagawa, Sekiya & Hayashi 1986, Icarus 67,
    375; Takeuchi & Lin 2002, ApJ 581, 1344; Birnstiel, Dullemond & Brauer 2010,
    A&A 513, A79).
    St: Stokes number []; eta: pressure-support parameter [], positive when the gas
    orbits at (1 - eta) v_k, i.e. eta = -(1/2) (h_g / r)^2 dlnP/dlnr; v_k: Keplerian
    speed; v_g: radial gas velocity (same unit as v_k).
    """
    St = np.asarray(St, dtype=float)
    return (-2.0 * St * eta * v_k + v_g) / (1.0 + St * St)
