#!/usr/bin/env python3
"""DustPy 1.0.8's gas time step on its default disk (not a test; results/implicit_euler.md,
"Why DustPy takes more steps"): the gas alone, on DustPy's grid (100 cells from 1 to 1000 au,
the first and last boundary cells), with DustPy's discretisation rebuilt from its equations:
the viscous velocity at the cell centres from nu Sigma_g r^(1/2) interpolated linearly onto
the faces (gas.f90 v_visc), upwind face fluxes (gas.f90 fi), the cells' source terms (gas.f90
s_hyd), the inner boundary cell at a constant gradient and the outer at 1e-100
(simulation.py, utils/boundary.py), and the rule of gas.f90 timestep (cells 2..Nr-1, S < 0,
Sigma_g > 1e-100). Stepped explicitly (1 yr or 0.1 of the rule); prints the gas's step
0.1 min Sigma_g/|S| at the given times.
Usage: /usr/bin/python3 tests/bench/dustpy_gas_dt.py
"""
import numpy as np

AU, YR = 1.495978707e13, 3.15576e7
G, M_SUN, K_B, M_P = 6.6743e-8, 1.98841e33, 1.380649e-16, 1.67262192e-24
FLOOR = 1e-100  # DustPy's gas floor and outer boundary value

ri = np.logspace(0.0, 3.0, 101) * AU  # DustPy's faces; centres are their means
r = 0.5 * (ri[1:] + ri[:-1])
n = r.size
temp = 221.35 * (r / AU) ** -0.5  # DustPy's passive disk (shared/anchors/README.md)
cs2 = K_B * temp / (2.3 * M_P)
nu = 1e-3 * cs2 / np.sqrt(G * M_SUN / r**3)  # alpha c_s H
rc, m_disk = 60.0 * AU, 0.05 * M_SUN
sigma = m_disk / (2.0 * np.pi * rc**2) * (r / rc) ** -1 * np.exp(-r / rc)


def to_faces(y):
    """Linear in r between centres, extrapolated from the edge pairs."""
    slope = np.diff(y) / np.diff(r)
    yi = np.empty(n + 1)
    yi[1:n] = y[:-1] + slope * (ri[1:n] - r[:-1])
    yi[0] = y[0] + slope[0] * (ri[0] - r[0])
    yi[n] = y[-1] + slope[-1] * (ri[n] - r[-1])
    return yi


def set_boundaries(s):
    d = ri[1] / ri[2] * (r[1] - r[0]) / (r[2] - r[1])  # constant gradient inside
    s[0] = (1.0 + d) * r[1] / r[0] * s[1] - r[2] / r[0] * d * s[2]
    s[-1] = FLOOR
    return s


def sources(s):
    v = -3.0 * np.diff(to_faces(s * nu * np.sqrt(r))) / np.diff(ri) / (s * np.sqrt(r))
    v[0] = (v[2] - v[1]) * (r[0] - r[1]) / (r[2] - r[1]) + v[1]
    v[-1] = (v[-2] - v[-3]) * (r[-1] - r[-3]) / (r[-2] - r[-3]) + v[-3]
    vi = to_faces(v)
    vi[0], vi[-1] = v[0], v[-1]
    out, inw = np.maximum(vi, 0.0), np.minimum(vi, 0.0)
    out[0], inw[-1] = 0.0, 0.0
    flux = np.empty(n + 1)
    flux[1:n] = s[:-1] * out[1:n] + s[1:] * inw[1:n]
    flux[0], flux[n] = s[0] * inw[0], s[-1] * out[n]
    return 2.0 * (flux[:-1] * ri[:-1] - flux[1:] * ri[1:]) / np.diff(ri**2)


def rule(s, rate):
    """min Sigma/|S| over the interior cells that shrink above the floor, and the cell."""
    inner = np.arange(1, n - 1)
    keep = inner[(rate[inner] < 0.0) & (s[inner] > FLOOR)]
    if keep.size == 0:
        return np.inf, -1
    q = s[keep] / -rate[keep]
    return q.min(), keep[q.argmin()]


sigma = set_boundaries(sigma)
t, marks = 0.0, [0.0, 1e2, 1e3, 1e4, 2e4, 5e4, 1e5]
while marks:
    rate = sources(sigma)
    dt, cell = rule(sigma, rate)
    if t >= marks[0] * YR:
        print(f"t = {marks.pop(0):8.0f} yr: gas step 0.1 x {dt / YR:.4g} yr, "
              f"set by cell {cell} (r = {r[cell] / AU:.4g} au)")
    h = min(YR, 0.1 * dt)
    sigma = set_boundaries(np.maximum(sigma + h * rate, FLOOR))
    t += h
