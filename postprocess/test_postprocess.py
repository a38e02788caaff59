"""Self-test of the postprocessing package.

    /usr/bin/python3 -m postprocess.test_postprocess

Builds synthetic run files (the layout of postprocess/reader.py) in a temporary
directory, reads them back, checks the closed forms of postprocess/analytic.py and
runs the plot command. Prints one line per check and "N passed, M failed" last;
exit status 0 when every check passed, 1 otherwise.
"""
import contextlib
import io
import os
import sys
import tempfile
import traceback
import warnings

import h5py
import numpy as np

from postprocess import analytic, plot, reader

AU = 1.496e13    # [cm]
YR = 3.156e7     # [s]
CONFIG_TOML = '[grid]\nr_in_au = 0.1\nr_out_au = 1000.0\nn_cells = 200\n\n[disk]\nalpha = 1e-3\n'
SNOW_AU = 3.0


# --- synthetic run files ---------------------------------------------------------------

def synthetic_profiles(r_au, time_yr):
    """Gas (LBP, r_c = 30 au) and dust (1 % of gas, drained from outside in) [g cm^-2].

    Dust beyond the drift front is exactly zero, to exercise masking on log axes; a
    factor 3 bump just outside the snow line makes the snow line visible.
    """
    sigma_g = analytic.lbp_sigma(r_au[None, :] * AU, time_yr[:, None] * YR,
                                 m_disk=0.05 * 1.989e33, r_c=30 * AU,
                                 nu_c=(30 * AU) ** 2 / (3 * 1e5 * YR))
    t_drift = 3e3 * r_au[None, :]                      # [yr], drift time scale
    depletion = np.exp(-time_yr[:, None] / t_drift)
    bump = 1.0 + 2.0 * np.exp(-0.5 * (np.log(r_au / (1.3 * SNOW_AU)) / 0.15) ** 2)
    sigma_d = 0.01 * sigma_g * depletion * bump[None, :]
    sigma_d[sigma_d < 1e-12 * sigma_d.max()] = 0.0
    return sigma_g, sigma_d


def write_dataset(group, name, data, units, description, extendible=False):
    """Dataset with `units` and `description` attributes (extendible along axis 0)."""
    data = np.asarray(data)
    options = {"maxshape": (None,) + data.shape[1:], "chunks": True} if extendible else {}
    dset = group.create_dataset(name, data=data, **options)
    dset.attrs["units"] = units
    dset.attrs["description"] = description


def write_run(path, n_cells=200, time_yr=None, killed=False):
    """Synthetic run file following the layout; returns the arrays written.

    killed=True imitates a writer killed mid-snapshot: /snapshots/sigma_g is one row
    shorter than the other snapshot datasets and /solver is missing.
    """
    time_yr = np.concatenate([[0.0], np.geomspace(10.0, 1e6, 40)]) if time_yr is None else time_yr
    r_f = np.geomspace(0.1, 1000.0, n_cells + 1)
    r_c = np.sqrt(r_f[1:] * r_f[:-1])
    area = np.pi * (r_f[1:] ** 2 - r_f[:-1] ** 2) * AU ** 2
    sigma_g, sigma_d = synthetic_profiles(r_c, time_yr)
    m_dust = sigma_d @ area
    snapshots = {
        "time": (time_yr, "yr", "snapshot time"),
        "sigma_d": (sigma_d, "g cm^-2", "dust surface density"),
        "sigma_g": (sigma_g, "g cm^-2", "gas surface density"),
        "St": (np.full_like(sigma_d, 1e-2), "", "Stokes number"),
        "m_dust": (m_dust, "g", "total dust mass on the grid"),
        "m_out_inner": (m_dust[0] - m_dust, "g", "cumulative dust mass lost through r_in"),
        "a": (np.full_like(sigma_d, 1e-4), "cm", "grain size (a later-version field)"),
    }
    with h5py.File(path, "w") as f:
        f.attrs["config_toml"] = CONFIG_TOML
        f.attrs["git_sha"] = np.bytes_(b"0123456789abcdef0123456789abcdef01234567")
        f.attrs["version"] = "0.1.0"
        f.attrs["scene"] = "synthetic"
        grid = f.create_group("grid")
        write_dataset(grid, "r_c", r_c, "au", "cell centres")
        write_dataset(grid, "r_f", r_f, "au", "cell faces")
        write_dataset(grid, "area", area, "cm^2", "annulus areas")
        disk = f.create_group("disk")
        disk.attrs["r_snow_au"] = SNOW_AU
        write_dataset(disk, "T", 280.0 * r_c ** -0.5, "K", "midplane temperature")
        write_dataset(disk, "alpha", np.full(n_cells, 1e-3), "", "turbulence parameter")
        snap = f.create_group("snapshots")
        for name, (data, units, description) in snapshots.items():
            data = data[:-1] if killed and name == "sigma_g" else data
            write_dataset(snap, name, data, units, description, extendible=True)
        if not killed:
            solver = f.create_group("solver")
            for key, value in dict(nst=1234, nfe=2345, nje=56, netf=3, nni=2000, nncf=1).items():
                solver.attrs[key] = np.int64(value)
            solver.attrs["wall_s"] = 12.5
            solver.attrs["status"] = "success"
    return {"r_c": r_c, "r_f": r_f, "area": area, "time": time_yr, "sigma_d": sigma_d,
            "sigma_g": sigma_g, "m_dust": m_dust}


# --- checks: each returns a one-line description of what it verified --------------------

def check_reader_complete(tmp):
    path = os.path.join(tmp, "full.h5")
    ref = write_run(path)
    run = reader.load_run(path)
    for name in ("r_c", "r_f", "area", "time"):
        assert np.array_equal(getattr(run, name), ref[name]), name
    for name in ("sigma_d", "sigma_g", "m_dust"):
        assert np.array_equal(run.field(name), ref[name]), name
    assert set(run.snapshots) == {"time", "sigma_d", "sigma_g", "St", "m_dust",
                                  "m_out_inner", "a"}, sorted(run.snapshots)
    assert run.units["snapshots/sigma_d"] == "g cm^-2" and run.units["grid/area"] == "cm^2"
    assert len(run.units) == 3 + 2 + 7, sorted(run.units)
    assert np.array_equal(run.field("disk/T"), run.disk["T"]) and run.field("T") is run.disk["T"]
    assert run.r_snow_au == SNOW_AU
    assert run.attrs["git_sha"].startswith("0123456789") and run.scene == "synthetic"
    assert run.config == {"grid": {"r_in_au": 0.1, "r_out_au": 1000.0, "n_cells": 200},
                          "disk": {"alpha": 1e-3}}, run.config
    assert run.solver == {"nst": 1234, "nfe": 2345, "nje": 56, "netf": 3, "nni": 2000,
                          "nncf": 1, "wall_s": 12.5, "status": "success"}, run.solver
    assert all(type(run.solver[k]) is int for k in ("nst", "nfe", "nje", "netf", "nni", "nncf"))
    assert np.allclose(run.dust_mass(), ref["m_dust"], rtol=1e-13)
    profile, t = run.at_time("sigma_d", 1.2e4)
    i = int(np.argmin(np.abs(ref["time"] - 1.2e4)))
    assert t == ref["time"][i] and np.array_equal(profile, ref["sigma_d"][i])
    try:
        run.field("no_such_field")
        raise AssertionError("field() accepted an unknown name")
    except KeyError:
        pass
    return (f"reader: grid, {len(run.snapshots)} snapshot fields x {run.n_snapshots} rows, "
            "units, disk, attrs, config, solver, dust_mass, at_time, field")


def check_reader_killed(tmp):
    path = os.path.join(tmp, "killed.h5")
    ref = write_run(path, killed=True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = reader.load_run(path)
    nt = len(ref["time"]) - 1
    assert run.n_snapshots == nt and all(a.shape[0] == nt for a in run.snapshots.values())
    assert np.array_equal(run.field("sigma_d"), ref["sigma_d"][:nt])
    assert run.solver == {}
    assert any("unequal lengths" in str(w.message) for w in caught), [str(w.message) for w in caught]
    return f"reader: killed run (sigma_g one row short, no /solver) cut to {nt} rows, warned"


def check_i0e_vs_numpy(tmp):
    x = np.concatenate([np.linspace(0.0, 60.0, 60001), np.geomspace(1e-10, 700.0, 20001)])
    ref = np.i0(x) * np.exp(-x)
    rel = np.abs(analytic.i0e(x) / ref - 1.0)
    assert rel.max() < 1e-12, (rel.max(), x[rel.argmax()])
    assert analytic.i0e(-2.5) == analytic.i0e(2.5) and analytic.i0e(0.0) == 1.0
    return f"i0e vs np.i0 * exp(-x) on {x.size} points in [0, 700]: max rel err {rel.max():.1e}"


def check_i0e_large_x(tmp):
    x = np.geomspace(1e3, 1e300, 200)
    value = analytic.i0e(x)
    y = 1.0 / (8.0 * x)     # A&S 9.7.1 through (8x)^-3; the next term is < 1.2e-13 here
    four_terms = (1.0 + y * (1.0 + y * (9.0 / 2.0 + y * 225.0 / 6.0))) / np.sqrt(2 * np.pi * x)
    assert np.all(np.isfinite(value)) and np.all(value > 0)
    assert np.allclose(value, four_terms, rtol=1e-12, atol=0.0)
    assert np.all(np.diff(value) < 0)
    return "i0e for x in [1e3, 1e300]: finite, decreasing, = asymptotic series to 1e-12"


def trapezoid(y, x):
    """Trapezoid rule (numpy 1.24 has trapz, numpy 2 renames it)."""
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def check_ring_mass(tmp):
    mass, r0, diffusivity = 2.0, 1.0, 0.01
    r = np.linspace(0.0, 40.0, 400001)
    worst = 0.0
    for t in (0.1, 1.0, 10.0, 100.0):    # from a narrow ring to a spread-out disk
        sigma = analytic.ring_diffusion(r, t, r0, diffusivity, mass)
        worst = max(worst, abs(trapezoid(2 * np.pi * r * sigma, r) / mass - 1.0))
    assert worst < 1e-6, worst
    return f"ring_diffusion conserves mass, sqrt(Dt)/r0 = 0.03..1: max rel err {worst:.1e}"


def check_ring_gaussian_limit(tmp):
    mass, r0, diffusivity, t = 1.0, 1000.0, 1.0, 1.0   # sqrt(2 D t) / r0 = 1.4e-3
    width = np.sqrt(2 * diffusivity * t)
    r = r0 + np.linspace(-4, 4, 801) * width
    sigma = analytic.ring_diffusion(r, t, r0, diffusivity, mass)
    gauss = mass / (2 * np.pi * r0) * np.exp(-0.5 * ((r - r0) / width) ** 2) / (
        np.sqrt(2 * np.pi) * width)
    rel = np.abs(sigma / gauss - 1.0)
    assert rel.max() < 4 * width / r0, rel.max()   # leading correction: (r - r0) / (2 r0)
    return f"ring_diffusion -> Gaussian / (2 pi r0) for r0 >> sqrt(Dt): max rel diff {rel.max():.1e}"


def check_lbp(tmp):
    m_disk, r_c, nu_c = 3.0, 2.0, 0.5
    r = np.geomspace(1e-20, 1e5, 250001) * r_c
    sigma0 = analytic.lbp_sigma(r, 0.0, m_disk, r_c, nu_c, gamma=1.0)
    assert np.allclose(sigma0, m_disk / (2 * np.pi * r_c * r) * np.exp(-r / r_c), rtol=1e-13)
    for gamma in (1.0, 0.5, 1.5):
        t_s = r_c ** 2 / (3 * (2 - gamma) ** 2 * nu_c)
        masses = []
        for t in (0.0, t_s, 10 * t_s):
            sigma = analytic.lbp_sigma(r, t, m_disk, r_c, nu_c, gamma)
            masses.append(trapezoid(2 * np.pi * r ** 2 * sigma, np.log(r)))
            expected = m_disk * (1 + t / t_s) ** (-1 / (2 * (2 - gamma)))
            assert abs(masses[-1] / expected - 1) < 1e-6, (gamma, t, masses[-1], expected)
        assert masses[0] > masses[1] > masses[2]
    return ("lbp_sigma: t = 0 gamma = 1 form; disk mass = m_disk at t = 0 and decays as "
            "T^(-1/(2(2-gamma))) for gamma = 0.5, 1, 1.5")


def check_drift_velocity(tmp):
    v = analytic.drift_velocity(np.array([1e-3, 1.0, 1e3]), 2e-3, 3e6)
    assert np.allclose(v, [-2e-3 * 2e-3 * 3e6 / (1 + 1e-6), -2e-3 * 3e6,
                           -2e3 * 2e-3 * 3e6 / (1 + 1e6)], rtol=1e-14)
    assert np.isclose(analytic.drift_velocity(0.0, 2e-3, 3e6, v_g=-5.0), -5.0)
    return "drift_velocity: maximal at St = 1 (-eta v_k), gas coupling at St = 0"


def check_plot(tmp):
    path = os.path.join(tmp, "plotme.h5")
    write_run(path)
    written = []
    for argv in ([path], [path, "-o", os.path.join(tmp, "chosen"), "--times-yr", "0,1e3,1e5"]):
        with contextlib.redirect_stdout(io.StringIO()) as out:
            assert plot.main(argv) == 0
        written += out.getvalue().split()
    assert written[0] == os.path.join(tmp, "plotme_plots", "sigma_d.png"), written
    assert len(written) == 4 and all(_is_png(p) for p in written), written
    return "plot.main writes sigma_d.png and dust_to_gas.png (default and -o/--times-yr)"


def check_plot_single_snapshot(tmp):
    path = os.path.join(tmp, "single.h5")
    write_run(path, time_yr=np.array([0.0]))
    with contextlib.redirect_stdout(io.StringIO()) as out:
        assert plot.main([path]) == 0
    assert all(_is_png(p) for p in out.getvalue().split())
    assert plot.select_snapshots(np.array([5.0])) == [0]
    return "plot.main with nt == 1 (t = 0 only)"


def check_snapshot_selection(tmp):
    time = np.concatenate([[0.0], np.geomspace(1.0, 1e6, 500)])
    chosen = plot.select_snapshots(time)
    assert chosen[0] == 0 and chosen[-1] == len(time) - 1 and len(chosen) <= plot.MAX_CURVES
    log_steps = np.diff(np.log10(time[chosen[1:]]))
    assert np.allclose(log_steps, log_steps.mean(), rtol=0.05), log_steps
    assert plot.nearest_snapshots(time, [0.0, 1e6, 2e6]) == [0, len(time) - 1]
    return f"select_snapshots: {len(chosen)} of {len(time)}, evenly spaced in log t"


def _is_png(path):
    """True if path exists and starts with the PNG signature."""
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n"


CHECKS = [check_reader_complete, check_reader_killed, check_i0e_vs_numpy, check_i0e_large_x,
          check_ring_mass, check_ring_gaussian_limit, check_lbp, check_drift_velocity,
          check_snapshot_selection, check_plot, check_plot_single_snapshot]


def main():
    """Run every check; returns the exit status."""
    passed = failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for check in CHECKS:
            try:
                print(f"ok    {check.__name__}: {check(tmp)}")
                passed += 1
            except Exception:
                print(f"FAIL  {check.__name__}:\n{traceback.format_exc()}")
                failed += 1
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
