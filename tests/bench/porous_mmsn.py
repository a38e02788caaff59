#!/usr/bin/env python3
"""The porous MMSN comparison of issue 35 (spec §15.5; Okuzumi et al. 2012) read from
runs of params/tests/porous_mmsn_distribution.toml (size distribution, any resolution) and
of the same scene with model.kind = "single_size". For every run:
- per snapshot: the outermost cell whose mass-dominating St >= 10, the dust mass on the
  grid and through r_in [M_earth]; the mass in St >= 10 bodies (a distribution's bins
  with St_k >= 10, a single-size run's cells with St >= 10) [M_earth] and the cells
  where such bodies hold more than 1e-3 of the cell's dust;
- the internal density range of aggregates of 1 g .. 1e10 g at 3-10 au over all
  snapshots: a distribution's bins holding > 1e-6 of their cell's mass (rho0 phi_k,
  rho0 = rho_int/phi of the mass-dominating particle: one species, no snow line), a
  single-size run's mass-dominating particle.
Usage: porous_mmsn.py RUN.h5 [RUN2.h5 ...]. Results: tests/bench/results/porous_mmsn.md."""
import argparse

import h5py
import numpy as np

M_EARTH = 5.9722e27  # [g]


def open_run(path):
    """The file, readable while its run still writes it (SWMR)."""
    try:
        return h5py.File(path, "r", swmr=True, libver="latest")
    except OSError:
        return h5py.File(path, "r")


def density_range(f, r_au, m_lo=1.0, m_hi=1e10, r_lo=3.0, r_hi=10.0):
    s = f["snapshots"]
    rho0 = np.nanmedian(s["rho_int"][:] / s["phi"][:])
    cells = (r_au >= r_lo) & (r_au <= r_hi)
    if "sigma" in s and "m_bins" in f["grid"]:
        m = f["grid/m_bins"][:]
        nb = len(m)
        bins = (m >= m_lo) & (m <= m_hi)
        rho = []
        for k in range(len(s["time"])):
            sig = s["sigma"][k].reshape(len(r_au), nb)[cells]
            phi = s["phi_bins"][k].reshape(len(r_au), nb)[cells]
            total = sig.sum(axis=1, keepdims=True)
            held = (sig > 1e-6 * total) & bins[None, :]
            rho.extend(rho0 * phi[held])
        return np.array(rho), "bins holding > 1e-6 of their cell's mass"
    m = s["m"][:][:, cells]
    held = (m >= m_lo) & (m <= m_hi)
    return s["rho_int"][:][:, cells][held], "mass-dominating particle"


def big_bodies(f, k, r_au):
    """Mass in St >= 10 bodies [M_earth] at snapshot k, and the radii [au] of the cells
    where they hold more than 1e-3 of the cell's dust."""
    s = f["snapshots"]
    area = f["grid/area"][:]  # [cm^2]
    if "sigma" in s:
        nb = len(f["grid/m_bins"])
        sig = s["sigma"][k].reshape(len(r_au), nb)
        big = sig * (s["st_bins"][k].reshape(len(r_au), nb) >= 10.0)
        in_cell, of_cell = big.sum(axis=1), sig.sum(axis=1)
    else:
        of_cell = s["sigma_d"][k]
        in_cell = of_cell * (s["St"][k] >= 10.0)
    held = r_au[in_cell > 1e-3 * of_cell]
    return float((in_cell * area).sum()) / M_EARTH, held


def report(path):
    with open_run(path) as f:
        s = f["snapshots"]
        r_au = f["grid/r_c"][:]  # [au] (its units attribute)
        assert f["grid/r_c"].attrs["units"] in (b"au", "au")
        t = s["time"][:]
        st = s["St"][:]
        kind = "distribution" if "sigma" in s else "single size"
        print(f"\n{path} ({kind}, {len(r_au)} cells"
              + (f", {len(f['grid/m_bins'])} bins" if "m_bins" in f["grid"] else "") + ")")
        print(f"{'t [yr]':>10} {'St>=10 to [au]':>15} {'max St':>9} "
              f"{'M_d grid':>9} {'through r_in':>12} {'in St>=10':>9} [M_earth]  "
              f"{'cells holding St>=10 [au]'}")
        for k in range(len(t)):
            big = np.where(st[k] >= 10.0)[0]
            front = f"{r_au[big.max()]:.2f}" if big.size else "-"
            m_grid = float(s["m_dust"][k]) / M_EARTH
            m_out = float(s["m_out_inner"][k]) / M_EARTH
            m_big, held = big_bodies(f, k, r_au)
            cells = f"{held.min():.2f}-{held.max():.2f}" if held.size else "-"
            print(f"{t[k]:10.4g} {front:>15} {st[k].max():9.3g} {m_grid:9.3f} {m_out:12.3f} "
                  f"{m_big:9.2f}            {cells}")
        rho, what = density_range(f, r_au)
        if rho.size:
            print(f"rho_int of 1 g .. 1e10 g at 3-10 au ({what}, {rho.size} values): "
                  f"{rho.min():.3g} .. {rho.max():.3g} g cm^-3")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    for path in ap.parse_args().runs:
        report(path)


if __name__ == "__main__":
    main()
