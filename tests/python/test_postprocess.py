"""Self-test of the postprocessing package.

    PYTHONPATH=. /usr/bin/python3 tests/python/test_postprocess.py   (from the repository root)

Builds synthetic run files (the layout of postprocess/reader.py, with and without the
/timeseries, /pebbles and /summary groups, growth and planetesimal fields) in a temporary
directory, reads them back, checks the closed forms of postprocess/analytic.py and
runs the plot commands (postprocess.plot, postprocess.plot_run). Prints one line per
check and "N passed, M failed" last; exit status 0 when every check passed, 1 otherwise.
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
import pandas as pd

# the repository root, for `postprocess` when run without PYTHONPATH
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from postprocess import (analytic, model_error, plot, plot_distribution, plot_run,  # noqa: E402
                         plot_scan, reader)

AU = 1.496e13    # [cm]
YR = 3.156e7     # [s]
CONFIG_TOML = '[grid]\nr_in_au = 0.1\nr_out_au = 1000.0\nn_cells = 200\n\n[disk]\nalpha = 1e-3\n'
SNOW_AU = 3.0
M_EARTH = 5.972e27   # [g]
MYR = 3.156e13       # [s]
MONITORS = ("snow line", "3 au", "10 au", "30 au", "r_in")


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


def write_run(path, n_cells=200, time_yr=None, killed=False, status="completed"):
    """Synthetic run file following the layout; returns the arrays written.

    killed=True imitates a writer killed mid-snapshot: /snapshots/sigma_g is one row
    shorter than the other snapshot datasets and /solver is missing. `status`: /solver's
    (panoptic writes "completed", "failed" or "stopped by ...; restart from ...").
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
            solver.attrs["status"] = status
    return {"r_c": r_c, "r_f": r_f, "area": area, "time": time_yr, "sigma_d": sigma_d,
            "sigma_g": sigma_g, "m_dust": m_dust}


def add_diagnostics(path, ref, planetesimals="formed", killed=False, names=None):
    """Add the later-version datasets to a file made by write_run (in place).

    Growth field phi; pebble monitors (/pebbles/r_au, attr names, snapshot pebble_flux
    [g s^-1] and m_through [g]); /timeseries (time, pebble_flux, m_through, mass_budget)
    on 4 samples per snapshot interval; planetesimals="formed": sigma_pl(_coag, _si),
    m_pl_*, t_first_pl growing in 1.5-4 au after 1e3 yr (formed: Sigma_pl above 1e-6 of
    the largest initial Sigma_d, /summary/formed_threshold, as the C++), "none": the same fields all
    zero/NaN, None: no planetesimal fields; /summary unless killed. killed=True also
    leaves /timeseries/time two rows shorter than the other /timeseries datasets (the
    writer appends time last). Returns a dict of what was written.
    """
    r_c, r_f, area, time = ref["r_c"], ref["r_f"], ref["area"], ref["time"]
    nt, n = ref["sigma_d"].shape
    sigma_d0 = ref["sigma_d"][0]
    zone = (r_c > 1.5) & (r_c < 4.0)
    growth = np.clip(np.log10(np.maximum(time, 1.0) / 1e3), 0.0, None)[:, None]   # 0 until 1e3 yr
    coag = np.where(zone[None, :] & (r_c[None, :] < 3.0), 1e-3 * sigma_d0 * growth, 0.0)
    si = np.where(zone[None, :] & (r_c[None, :] >= 3.0), 1e-4 * sigma_d0 * growth, 0.0)
    if planetesimals == "none":
        coag, si = np.zeros_like(coag), np.zeros_like(si)
    threshold = 1e-6 * sigma_d0.max()     # src/run/diagnostics.cpp kFormedFraction
    formed = (coag + si) > threshold
    t_first = np.full((nt, n), np.nan)
    for i in range(nt):
        first = formed[: i + 1].argmax(axis=0)
        t_first[i] = np.where(formed[: i + 1].any(axis=0), time[first], np.nan)
    m_coag, m_si = coag @ area, si @ area
    r_mon = np.array([SNOW_AU, 3.2, 10.0, 30.0, r_f[0]])
    m_through = (ref["m_dust"][0] - ref["m_dust"])[:, None] * np.linspace(1.6, 1.0, 5)[None, :]
    flux = np.gradient(m_through, time * YR, axis=0)
    ts_time = np.concatenate([np.linspace(t0, t1, 5)[1:] for t0, t1 in zip(time[:-1], time[1:])])
    interp = lambda y: np.stack([np.interp(ts_time, time, c) for c in np.atleast_2d(y.T)], axis=1)
    dust = np.interp(ts_time, time, ref["m_dust"])
    pl_c, pl_s = np.interp(ts_time, time, m_coag), np.interp(ts_time, time, m_si)
    inner = np.interp(ts_time, time, m_through[:, -1])
    sublimated = np.zeros_like(dust)
    error = np.abs(dust + pl_c + pl_s + inner + sublimated - ref["m_dust"][0])
    budget = np.stack([dust, pl_c, pl_s, inner, sublimated, error], axis=1) / M_EARTH
    series = {"time": ts_time, "pebble_flux": interp(flux) / (M_EARTH / MYR),
              "m_through": interp(m_through) / M_EARTH, "mass_budget": budget}
    with h5py.File(path, "a") as f:
        snap = f["snapshots"]
        write_dataset(snap, "phi", np.full((nt, n), 0.3), "", "filling factor", extendible=True)
        write_dataset(snap, "pebble_flux", flux, "g s^-1", "inward dust flow", extendible=True)
        write_dataset(snap, "m_through", m_through, "g", "cumulative", extendible=True)
        if planetesimals is not None:
            for name, data, units in (("sigma_pl", coag + si, "g cm^-2"),
                                      ("sigma_pl_coag", coag, "g cm^-2"),
                                      ("sigma_pl_si", si, "g cm^-2"), ("m_pl_coag", m_coag, "g"),
                                      ("m_pl_si", m_si, "g"), ("t_first_pl", t_first, "yr")):
                write_dataset(snap, name, data, units, name, extendible=True)
        peb = f.create_group("pebbles")
        write_dataset(peb, "r_au", r_mon, "au", "monitor radii")
        peb.attrs["names"] = ";".join(MONITORS) if names is None else names
        ts = f.create_group("timeseries")
        for name, data in series.items():
            data = data[:-2] if killed and name == "time" else data
            write_dataset(ts, name, data, {"time": "yr", "pebble_flux": "M_earth Myr^-1"}.get(
                name, "M_earth"), f"synthetic {name}", extendible=True)
        if not killed:
            summary = f.create_group("summary")
            scalars = {"m_pl_coag": m_coag[-1] / M_EARTH, "m_pl_si": m_si[-1] / M_EARTH,
                       "m_peb_snowline": m_through[-1, 0] / M_EARTH,
                       "m_peb_r_in": m_through[-1, -1] / M_EARTH,
                       "m_dust_final": ref["m_dust"][-1] / M_EARTH,
                       "budget_error": error[-1] / ref["m_dust"][0], "formed_threshold": threshold}
            for c, mask in (("coag", coag[-1] > threshold), ("si", si[-1] > threshold)):
                scalars[f"r_min_pl_{c}"] = r_c[mask].min() if mask.any() else np.nan
                scalars[f"r_max_pl_{c}"] = r_c[mask].max() if mask.any() else np.nan
            for name, value in scalars.items():
                write_dataset(summary, name, [value], "", name)
            write_dataset(summary, "t_first_pl", t_first[-1], "yr", "first formation")
    return {"series": series, "r_mon": r_mon, "t_first": t_first[-1], "m_coag": m_coag,
            "threshold": threshold,
            "n_series": len(ts_time) - (2 if killed else 0)}


def write_full_run(path, planetesimals="formed", killed=False, names=None, time_yr=None):
    """write_run + add_diagnostics; returns (write_run dict, add_diagnostics dict)."""
    ref = write_run(path, killed=killed, time_yr=time_yr)
    return ref, add_diagnostics(path, ref, planetesimals, killed, names)


def run_plot_run(argv):
    """plot_run.main(argv) -> (status, written paths, stderr text)."""
    with contextlib.redirect_stdout(io.StringIO()) as out, \
            contextlib.redirect_stderr(io.StringIO()) as err:
        status = plot_run.main(argv)
    return status, out.getvalue().split(), err.getvalue()


ALL_PNGS = ["sigma_d.png", "dust_to_gas.png", "rt_St.png", "rt_a.png", "rt_phi.png",
            "rt_dust_to_gas.png", "pebble_flux.png", "sigma_pl.png", "mass_budget.png"]


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
                          "nncf": 1, "wall_s": 12.5, "status": "completed"}, run.solver
    assert all(type(run.solver[k]) is int for k in ("nst", "nfe", "nje", "netf", "nni", "nncf"))
    assert np.allclose(run.dust_mass(), ref["m_dust"], rtol=1e-13)
    t, profile = run.at_time("sigma_d", 1.2e4)
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


def check_reader_torn_dataset(tmp):
    # a dataset whose header a SIGKILL tore (its checksum fails): left out, warned; the
    # rest of the file reads
    path = os.path.join(tmp, "torn.h5")
    ref = write_run(path)
    with h5py.File(path, "a", libver="latest") as f:
        g = f["snapshots"]
        g.create_dataset("torn", data=np.ones((len(ref["time"]), 3)))  # header checksummed
        addr = g.id.links.get_info(b"torn").u
    with open(path, "r+b") as fh:
        fh.seek(addr + 24)
        torn = bytes(x ^ 0xA5 for x in fh.read(8))
        fh.seek(addr + 24)
        fh.write(torn)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = reader.load_run(path)
    assert "torn" not in run.snapshots and run.n_snapshots == len(ref["time"])
    assert np.array_equal(run.field("sigma_d"), ref["sigma_d"])
    assert any("/snapshots/torn cannot be read" in str(w.message) for w in caught), \
        [str(w.message) for w in caught]
    return "reader: a dataset with a torn header left out, warned; the rest read"


def check_reader_new_groups(tmp):
    path = os.path.join(tmp, "groups.h5")
    ref, diag = write_full_run(path)
    run = reader.load_run(path)
    assert set(run.timeseries) == {"time", "pebble_flux", "m_through", "mass_budget"}
    for name, data in diag["series"].items():
        assert np.array_equal(run.timeseries[name], data), name
    assert run.timeseries["mass_budget"].shape == (len(diag["series"]["time"]), 6)
    assert run.pebble_names == list(MONITORS), run.pebble_names
    assert np.array_equal(run.monitor_r_au, diag["r_mon"]) and set(run.pebbles) == {"r_au"}
    assert isinstance(run.summary["m_pl_coag"], float) and run.summary["m_pl_coag"] > 0
    assert np.isnan(run.summary["r_min_pl_si"]) or run.summary["r_min_pl_si"] >= 3.0
    assert np.array_equal(run.summary["t_first_pl"], diag["t_first"], equal_nan=True)
    assert run.units["timeseries/pebble_flux"] == "M_earth Myr^-1"
    assert run.descriptions["timeseries/mass_budget"] == "synthetic mass_budget"
    assert run.field("timeseries/m_through") is run.timeseries["m_through"]
    assert run.field("budget_error") == run.summary["budget_error"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert run.field("pebble_flux") is run.snapshots["pebble_flux"]   # snapshots first
    # ... in other units than /timeseries/pebble_flux: said
    assert any("different units" in str(w.message) for w in caught), caught
    assert run.unit("sigma_d") == "g cm^-2" and run.unit("timeseries/pebble_flux") == \
        "M_earth Myr^-1"
    # the notebook helpers read the /timeseries columns by name
    t, m_pl = run.planetesimal_mass()
    mb = run.timeseries["mass_budget"]
    cols = run.budget_columns or ["m_dust", "m_pl_coag", "m_pl_si", "m_out_inner",
                                  "m_sublimated", "error"]
    assert np.array_equal(t, run.timeseries["time"])
    assert np.array_equal(m_pl, mb[:, cols.index("m_pl_coag")] + mb[:, cols.index("m_pl_si")])
    t, out = run.budget("m_out_inner")
    assert np.array_equal(out, mb[:, cols.index("m_out_inner")])
    for key in (MONITORS[1], float(diag["r_mon"][1])):   # by name and by radius
        t, flux = run.pebble_flux(key)
        assert np.array_equal(flux, run.timeseries["pebble_flux"][:, 1]), key
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run.at_time("sigma_d", 1e12)
    assert any("no snapshot near" in str(w.message) for w in caught), caught
    assert run.finished and run.n_snapshots == len(ref["time"])
    return (f"reader: /timeseries ({len(run.timeseries['time'])} rows), /pebbles "
            f"({len(run.pebble_names)} named monitors), /summary ({len(run.summary)} entries)")


def check_reader_refuses_other_files(tmp):
    """A checkpoint, a directory or an HDF5 file without /snapshots is named as such."""
    chk = os.path.join(tmp, "x.chk.h5")
    with h5py.File(chk, "w") as f:
        f.attrs["format"] = "panoptic checkpoint 1"
        f.attrs["output_file"] = "/data/x.h5"
    other = os.path.join(tmp, "other.h5")
    with h5py.File(other, "w") as f:
        f.create_dataset("x", data=[1.0])
    for path, text in ((chk, "is a checkpoint, not a run's output; load the run's output "
                             "/data/x.h5"),
                       (other, "is not a panoptic run file"),
                       (tmp, "is a directory")):
        try:
            reader.load_run(path)
        except (ValueError, IsADirectoryError) as err:
            assert text in str(err), str(err)
        else:
            raise AssertionError(f"{path} loaded")
    return "reader: a checkpoint, a directory and a foreign HDF5 file are named as such"


def check_reader_groups_absent(tmp):
    path = os.path.join(tmp, "old_layout.h5")
    write_run(path)
    run = reader.load_run(path)
    assert run.timeseries == {} and run.pebbles == {} and run.summary == {}
    assert run.pebble_names == [] and run.monitor_r_au.size == 0
    assert run.finished     # /solver is there
    return "reader: file without /timeseries, /pebbles, /summary gives empty dicts"


def check_reader_stopped_or_failed_not_finished(tmp):
    # a stopped or failed run writes /solver as well: only "completed" is finished
    seen = {}
    for status in ("completed", "failed", "stopped by SIGINT; restart from run.chk.h5"):
        path = os.path.join(tmp, "status.h5")
        write_run(path, status=status)
        seen[status.split(";")[0]] = reader.load_run(path).finished
    assert seen == {"completed": True, "failed": False, "stopped by SIGINT": False}, seen
    return "reader: only a /solver status of completed counts as finished"


def check_reader_timeseries_killed(tmp):
    path = os.path.join(tmp, "killed_groups.h5")
    ref, diag = write_full_run(path, killed=True)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = reader.load_run(path)
    ns = diag["n_series"]
    assert all(a.shape[0] == ns for a in run.timeseries.values()), ns
    assert np.array_equal(run.timeseries["mass_budget"], diag["series"]["mass_budget"][:ns])
    messages = [str(w.message) for w in caught]
    assert any("/timeseries datasets have unequal lengths" in m for m in messages), messages
    assert run.summary == {} and not run.finished
    assert run.n_snapshots == len(ref["time"]) - 1
    return f"reader: killed run, /timeseries cut to its {ns} time rows (warned), no /summary"


def check_reader_timeseries_zero_rows(tmp):
    # rows read back as zeros amid the valid ones: what a run killed while a restart cut
    # the file leaves behind (src/run/diagnostics.cpp drops them on the next restart; files
    # restarted before that fix have them between valid rows)
    path = os.path.join(tmp, "zero_rows.h5")
    _, diag = write_full_run(path)
    ns = len(diag["series"]["time"])
    lo, hi = ns - 12, ns - 5
    with h5py.File(path, "a") as f:
        for name, ds in f["timeseries"].items():
            ds[lo:hi] = np.zeros((hi - lo,) + ds.shape[1:])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = reader.load_run(path)
    kept = np.r_[0:lo, hi:ns]
    assert all(a.shape[0] == ns - (hi - lo) for a in run.timeseries.values()), ns
    assert np.array_equal(run.timeseries["m_through"], diag["series"]["m_through"][kept])
    assert np.array_equal(run.timeseries["time"], diag["series"]["time"][kept])
    messages = [str(w.message) for w in caught]
    assert any("7 /timeseries rows do not rise in time" in m for m in messages), messages
    return (f"reader: /timeseries with {hi - lo} zeroed rows amid {ns} drops exactly those "
            f"(warned)")


def check_reader_monitor_names(tmp):
    path = os.path.join(tmp, "bad_names.h5")
    write_full_run(path, names="snow line;r_in")      # 2 names for 5 radii
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = reader.load_run(path)
    assert run.pebble_names == [f"{r:.3g} au" for r in run.monitor_r_au], run.pebble_names
    assert any("do not match" in str(w.message) for w in caught)
    return "reader: /pebbles names that do not match r_au fall back to the radii, warned"


def check_plot_run_full(tmp):
    path = os.path.join(tmp, "full_run.h5")
    write_full_run(path)
    status, written, err = run_plot_run([path])
    outdir = os.path.join(tmp, "full_run_plots")
    assert status == 0, err
    assert written == [os.path.join(outdir, name) for name in ALL_PNGS], (written, err)
    assert all(_is_png(p) for p in written) and err == "", err
    status, written, _ = run_plot_run([path, "-o", os.path.join(tmp, "elsewhere")])
    assert status == 0 and len(written) == len(ALL_PNGS)
    assert all(p.startswith(os.path.join(tmp, "elsewhere")) for p in written)
    return f"plot_run.main writes all {len(ALL_PNGS)} PNGs (default outdir and -o)"


def check_plot_functions_return_figures(tmp):
    """Every figure function returns its Figure and, given no path, writes nothing (for
    notebooks)."""
    path = os.path.join(tmp, "nb_run.h5")
    write_full_run(path)
    run = reader.load_run(path)
    before = set(os.listdir(tmp))
    figs = [job(None) for _, job in plot_run.figures(run)]
    assert all(hasattr(f, "savefig") and f.axes for f in figs), figs
    assert set(os.listdir(tmp)) == before, set(os.listdir(tmp)) - before
    return f"the {len(figs)} figure functions return Figures and write nothing without a path"


def check_plot_run_transport_only(tmp):
    path = os.path.join(tmp, "transport.h5")
    write_run(path)           # older layout: no phi, no planetesimals, no /timeseries
    status, written, err = run_plot_run([path])
    names = [os.path.basename(p) for p in written]
    assert status == 0, err
    assert names == ["sigma_d.png", "dust_to_gas.png", "rt_St.png", "rt_a.png",
                     "rt_dust_to_gas.png", "mass_budget.png"], (names, err)
    assert all(_is_png(p) for p in written)
    for skipped in ("rt_phi.png", "pebble_flux.png", "sigma_pl.png"):
        assert f"skipped {skipped}" in err, err
    return "plot_run.main on an older transport-only file: 6 PNGs, 3 skipped with a note"


def check_plot_run_degraded(tmp):
    results = []
    for label, options in (("no planetesimals formed", {"planetesimals": "none"}),
                           ("planetesimals off", {"planetesimals": None}),
                           ("killed run", {"killed": True})):
        path = os.path.join(tmp, f"degraded_{len(results)}.h5")
        write_full_run(path, **options)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            status, written, err = run_plot_run([path])
        names = [os.path.basename(p) for p in written]
        expected = [n for n in ALL_PNGS if not (options.get("planetesimals", "") is None
                                                 and n == "sigma_pl.png")]
        assert status == 0 and names == expected, (label, names, err)
        assert all(_is_png(p) for p in written), label
        results.append(f"{label}: {len(names)}")
    return "plot_run.main degrades gracefully (" + ", ".join(results) + " PNGs)"


def check_plot_run_failure_status(tmp):
    path = os.path.join(tmp, "failing.h5")
    write_full_run(path)
    original = plot_run.plot_sigma_pl

    def broken(run, out_path):
        raise RuntimeError("deliberate failure")
    plot_run.plot_sigma_pl = broken
    try:
        status, written, err = run_plot_run([path, "-o", os.path.join(tmp, "failing")])
    finally:
        plot_run.plot_sigma_pl = original
    assert status == 1 and "FAILED sigma_pl.png" in err and "deliberate failure" in err, err
    assert len(written) == len(ALL_PNGS) - 1 and all(_is_png(p) for p in written), written
    return "plot_run.main: a failing figure is reported, the others written, exit status 1"


def check_plot_run_single_snapshot(tmp):
    path = os.path.join(tmp, "single_full.h5")
    write_run(path, time_yr=np.array([0.0]))
    status, written, err = run_plot_run([path])
    names = [os.path.basename(p) for p in written]
    assert status == 0 and names == ["sigma_d.png", "dust_to_gas.png"], (names, err)
    assert err.count("skipped") == len(ALL_PNGS) - 2, err
    return "plot_run.main with nt == 1 (t = 0 only): Sigma_d figures, the rest skipped"


def check_plot_run_helpers(tmp):
    edges = plot_run.time_edges(np.array([10.0, 100.0, 1000.0]))
    assert np.allclose(edges, [10 ** 0.5, 10 ** 1.5, 10 ** 2.5, 10 ** 3.5])
    assert np.allclose(plot_run.time_edges(np.array([100.0])), [10 ** 1.5, 10 ** 2.5])
    mask = np.array([[True, True, False, True],
                     [False, True, False, False]])
    x, y = np.arange(5.0), np.arange(3.0)
    boxes = plot_run.mask_rectangles(mask, x, y)
    assert boxes == [[(0, 0), (2, 0), (2, 1), (0, 1)], [(3, 0), (4, 0), (4, 1), (3, 1)],
                     [(1, 1), (2, 1), (2, 2), (1, 2)]], boxes
    # perimeter of the True region: 2x1 block (6) + 1x1 block (4) + 1x1 below (4) - shared 2
    assert len(plot_run.mask_outline(mask, x, y)) == 12
    lo, hi, extend = plot_run.log_limits(np.geomspace(1e-10, 1.0, 1001), 6)
    assert np.isclose(hi, np.percentile(np.geomspace(1e-10, 1.0, 1001), 99.5))
    assert np.isclose(lo, hi * 1e-6) and extend == "both"
    assert plot_run.log_limits(np.full(5, 2.0), 6) == (0.2, 2.0, "neither")
    assert plot_run.log_limits(np.array([0.0, np.nan]), 6) is None
    assert plot_run.unit_tex("g cm^-2") == "g cm$^{-2}$" and plot_run.unit_tex("") == ""
    return "plot_run helpers: time_edges, mask_rectangles, mask_outline, log_limits, unit_tex"


@contextlib.contextmanager
def captured_figures():
    """Collect the figures plot_run saves (list of Figure), still writing them."""
    figures, original = [], plot_run.save

    def keep(fig, run, out_path):
        figures.append(fig)
        original(fig, run, out_path)
    plot_run.save = keep
    try:
        yield figures
    finally:
        plot_run.save = original


def check_plot_run_formed_threshold(tmp):
    # Sigma_pl at the outer edge above 1e-6 of the cell's own initial Sigma_d but below
    # /summary/formed_threshold (1e-6 of the largest): not a planetesimal zone (the C++
    # counts no cell there: r_max_pl_*, t_first_pl), so neither hatched nor zoomed to
    path = os.path.join(tmp, "outer_edge.h5")
    ref, diag = write_full_run(path)
    threshold = diag["threshold"]
    sigma_d0 = ref["sigma_d"][0]
    edge = (ref["r_c"] > 100.0) & (sigma_d0 > 0)
    assert edge.any() and np.all(0.01 * threshold > 1e-6 * sigma_d0[edge])
    with h5py.File(path, "a") as f:
        for name in ("sigma_pl_si", "sigma_pl"):
            data = f["snapshots"][name][()]
            data[1:, edge] += 0.01 * threshold
            f["snapshots"][name][...] = data
    run = reader.load_run(path)
    assert plot_run.formed_threshold(run) == threshold
    with captured_figures() as figures:
        plot_run.plot_sigma_pl(run, os.path.join(tmp, "outer_edge_pl.png"))
        plot_run.plot_map(run, os.path.join(tmp, "outer_edge_St.png"), **dict(plot_run.MAPS)[
            "rt_St.png"])
    x_hi = figures[0].axes[0].get_xlim()[1]
    assert x_hi < 20.0, x_hi       # zoomed to the 1.5-4 au zone, widened 4x
    hatched = [c for c in figures[1].axes[0].collections if c.get_hatch()]
    boxes = np.concatenate([box.vertices for box in hatched[0].get_paths()])
    assert boxes[:, 0].max() < 4.5, boxes[:, 0].max()
    last_row = boxes[:, 1].max()
    formed_last = np.zeros(len(ref["r_c"]), bool)
    for box in hatched[0].get_paths():
        x0, x1 = box.vertices[:, 0].min(), box.vertices[:, 0].max()
        if np.isclose(box.vertices[:, 1].max(), last_row):
            formed_last |= (ref["r_c"] > x0) & (ref["r_c"] < x1)
    assert np.array_equal(formed_last, np.isfinite(run.summary["t_first_pl"]))
    with h5py.File(path, "a") as f:      # a killed run: no /summary, the same threshold
        del f["summary"]
    assert np.isclose(plot_run.formed_threshold(reader.load_run(path)), threshold, rtol=1e-14)
    return ("plot_run: the planetesimal zone is Sigma_pl > /summary/formed_threshold (not "
            "1e-6 of each cell's Sigma_d): Sigma_pl figure's zoom, r-t hatching = t_first_pl")


def check_snow_line_off(tmp):
    # snowline.enabled = false: panoptic still writes /disk r_snow_au (where T = T_sub)
    # and a pebble monitor named "snow line" there; the figures must not show a snow line
    path = os.path.join(tmp, "snow_off.h5")
    write_full_run(path)
    with h5py.File(path, "a") as f:
        f.attrs["config_toml"] = CONFIG_TOML + "\n[snowline]\nenabled = false\nf_ice = 0.5\n"
    run = reader.load_run(path)
    assert np.isnan(run.r_snow_au) and run.pebble_names[0] == "snow line"
    assert run.config["snowline"]["enabled"] is False
    labels = []
    with captured_figures() as figures:
        plot_run.plot_map(run, os.path.join(tmp, "snow_off_St.png"),
                          **dict(plot_run.MAPS)["rt_St.png"])
        plot_run.plot_pebble_flux(run, os.path.join(tmp, "snow_off_flux.png"))
    for fig in figures:
        for ax in fig.axes:
            if ax.get_legend() is not None:
                labels += [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels and not any(text.startswith("snow line") for text in labels), labels
    assert any("snow line off" in text for text in labels), labels
    fig, ax = plot.new_figure()
    plot.mark_snow_line(ax, run)
    assert not ax.lines
    with h5py.File(path, "a") as f:      # the same file with the snow line on: drawn
        f.attrs["config_toml"] = CONFIG_TOML + "\n[snowline]\nenabled = true\n"
    assert reader.load_run(path).r_snow_au == SNOW_AU
    return ("snowline.enabled = false: no snow line drawn or named (r_snow_au NaN), "
            "T_sub monitor labelled")


def check_t_first_off_axis_label(tmp):
    # two snapshots, 0 and 1e6 yr: the r-t map's time axis starts at the row's lower edge
    # 10^5.5 yr; the cells that formed before it (all, here: after 1e3 yr) are off the axis
    path = os.path.join(tmp, "two_snapshots.h5")
    write_full_run(path, time_yr=np.array([0.0, 1e6]))
    with h5py.File(path, "a") as f:      # formed between the snapshots, as in a real run
        t_first = f["summary/t_first_pl"][()]
        t_first[np.isfinite(t_first)] = np.geomspace(2e3, 1e6, np.isfinite(t_first).sum())
        f["summary/t_first_pl"][...] = t_first
    run = reader.load_run(path)
    t_first = run.summary["t_first_pl"]
    with captured_figures() as figures:
        plot_run.plot_map(run, os.path.join(tmp, "two_St.png"), **dict(plot_run.MAPS)["rt_St.png"])
    ax = figures[0].axes[0]
    bottom = ax.get_ylim()[0]
    assert np.isclose(bottom, 10 ** 5.5), bottom
    label = [t.get_text() for t in ax.get_legend().get_texts() if "first" in t.get_text()][0]
    n_early = int(np.sum(t_first < bottom))
    expected = f"{n_early} cells before {plot.format_years(bottom)}, off"
    assert n_early > 0 and expected in label, label
    return f"r-t map: t_first_pl cells below the time axis counted against its bottom ({label})"


def write_scan_summary(path_dir, axes, status, outcomes, sampling):
    """DIR/summary.h5 in the layout of `panoptic scan` (params/README.md, Scans): axes {key: (values,
    spacing)}, status (list of str), outcomes {name: (values, units)}."""
    os.makedirs(path_dir, exist_ok=True)
    with h5py.File(os.path.join(path_dir, "summary.h5"), "w") as f:
        f.attrs["axes"] = ",".join(axes)
        f.attrs["sampling"] = sampling
        for key, (values, spacing) in axes.items():
            f.create_dataset(f"axes/{key}", data=np.asarray(values, float))
            f[f"axes/{key}"].attrs["spacing"] = spacing
        f.create_dataset("runs/status", data=np.array([x.encode() for x in status]))
        f.create_dataset("runs/name", data=np.array([f"run_{i:05d}".encode()
                                                     for i in range(len(status))]))
        for name, (values, units) in outcomes.items():
            f.create_dataset(f"outcome/{name}", data=np.asarray(values, float))
            f[f"outcome/{name}"].attrs["units"] = units


def marker_lines(ax, label):
    """The Line2D of ax with the given legend label."""
    return [line for line in ax.get_lines() if line.get_label() == label]


def check_plot_scan(tmp):
    # 3 x 2 grid: run 1 failed (NaN outcomes), run 4 completed without planetesimals
    # (t_first_pl_min NaN)
    mass, alpha = np.repeat([0.5, 1.0, 2.0], 2), np.tile([1e-4, 1e-2], 3)
    status = ["completed", "failed", "completed", "completed", "completed", "completed"]
    m_pl = np.array([1.0, np.nan, 3.0, 0.0, 5.0, 6.0])
    t_first = np.array([700.0, np.nan, 300.0, np.nan, 100.0, 50.0])
    grid_dir = os.path.join(tmp, "scan_grid")
    write_scan_summary(grid_dir, {"star.mass_msun": (mass, "list"), "disk.alpha": (alpha, "log")},
                       status, {"m_pl_coag": (m_pl, "M_earth"), "t_first_pl_min": (t_first, "yr")},
                       "grid")
    summary = plot_scan.load_summary(grid_dir)
    fig = plot_scan.line_figure(summary, "star.mass_msun", ["m_pl_coag", "t_first_pl_min"],
                                os.path.join(tmp, "scan_lines.png"))
    ax_m, ax_t = fig.axes[:2]
    # the failed run along the bottom of the panel (axes coordinates), not at a value
    cross, = marker_lines(ax_m, "not completed")
    to_axes = (cross.get_transform() - ax_m.transAxes).transform(cross.get_xydata())
    assert np.allclose(cross.get_xdata(), [0.5]) and np.allclose(to_axes[:, 1], 0.03), to_axes
    # the run without a value of t_first_pl_min is shown, at its mass
    circle, = marker_lines(ax_t, "completed, no value (NaN)")
    assert np.allclose(circle.get_xdata(), [1.0])
    assert not marker_lines(ax_m, "completed, no value (NaN)")
    # one joined line per alpha: the runs of a line differ only in the mass
    alpha_label = plot_scan.key_label("disk.alpha")   # typeset: "$\\alpha$"
    data = [line for line in ax_m.get_lines() if line.get_label().startswith(alpha_label)]
    assert [line.get_linestyle() for line in data] == ["-", "-"]
    assert np.allclose(data[0].get_ydata(), [1.0, 3.0, 5.0]), data[0].get_ydata()
    assert np.allclose(data[1].get_ydata(), [0.0, 6.0]), data[1].get_ydata()
    fig = plot_scan.map_figure(summary, "star.mass_msun", "disk.alpha", "t_first_pl_min",
                               os.path.join(tmp, "scan_map.png"))
    ax = fig.axes[0]
    mesh = [c for c in ax.collections if hasattr(c, "get_array") and c.get_array() is not None][0]
    Z = np.ma.filled(mesh.get_array(), np.nan).reshape(2, 3)   # rows alpha, columns mass
    assert np.allclose(Z, [[700.0, 300.0, 100.0], [np.nan, np.nan, 50.0]], equal_nan=True), Z
    circle, = marker_lines(ax, "completed, no value (NaN)")
    cross, = marker_lines(ax, "not completed")
    assert np.allclose(circle.get_xydata(), [[1.0, 1e-2]]) and np.allclose(
        cross.get_xydata(), [[0.5, 1e-2]])
    # each run's value written on its cell, ticks at the sampled values, typeset labels
    texts = sorted(t.get_text() for t in ax.texts)
    assert texts == sorted(["700", "300", "100", "50"]), texts
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0.5", "1", "2"], \
        [t.get_text() for t in ax.get_xticklabels()]
    assert ax.get_xlabel() == plot_scan.KEY_LABELS["star.mass_msun"]

    # Latin hypercube over three axes: points not joined, the NaN run marked on the map
    rng = np.random.default_rng(1)
    n = 8
    lhs = {"star.mass_msun": (rng.uniform(0.3, 2.0, n), "lin"),
           "disk.alpha": (10 ** rng.uniform(-4, -2, n), "log"),
           "disk.T_1au": (rng.uniform(150, 300, n), "lin")}
    m_peb = rng.uniform(0.1, 1.0, n)
    m_peb[3] = np.nan
    lhs_dir = os.path.join(tmp, "scan_lhs")
    write_scan_summary(lhs_dir, lhs, ["completed"] * n, {"m_peb_snowline": (m_peb, "M_earth")},
                       "lhs")
    summary = plot_scan.load_summary(lhs_dir)
    fig = plot_scan.line_figure(summary, "star.mass_msun", ["m_peb_snowline"],
                                os.path.join(tmp, "lhs_lines.png"))
    points = [line for line in fig.axes[0].get_lines() if line.get_marker() == "o"
              and not line.get_label().startswith("completed")]
    assert points and all(line.get_linestyle() == "None" for line in points)
    assert "not joined" in fig._suptitle.get_text()
    fig = plot_scan.map_figure(summary, "star.mass_msun", "disk.alpha", "m_peb_snowline",
                               os.path.join(tmp, "lhs_map.png"))
    circle, = marker_lines(fig.axes[0], "completed, no value (NaN)")
    assert np.allclose(circle.get_xydata(),
                       [[lhs["star.mass_msun"][0][3], lhs["disk.alpha"][0][3]]])
    # a list axis 1e-4, 1e-3, 1e-2 (two decades, 100 x 1e-4 rounds above 1e-2): log
    list_dir = os.path.join(tmp, "scan_list")
    write_scan_summary(list_dir, {"disk.alpha": ([1e-4, 1e-3, 1e-2], "list"),
                                  "star.mass_msun": ([0.5, 1.0, 1.5], "list")},
                       ["completed"] * 3, {"m_pl_coag": ([1.0, 2.0, 3.0], "M_earth")}, "grid")
    axes = plot_scan.load_summary(list_dir)["axes"]
    assert axes["disk.alpha"][1] == "log" and axes["star.mass_msun"][1] == "list", axes
    with contextlib.redirect_stdout(io.StringIO()) as out:
        status = plot_scan.main([grid_dir])
    written = out.getvalue().split()
    assert status == 0 and all(_is_png(p) for p in written) and len(written) == 2, written
    return ("plot_scan: failed runs along the panel bottom, NaN outcomes marked (lines, grid "
            "map, LHS scatter), map cells in place, LHS points not joined")


def check_dust_to_gas_map_centre(tmp):
    # gas drained at the outer edge after t = 0 (an evolving LBP disk): ratios up to
    # ~1e10 there; the map's white must stay the initial ratio (0.01 here), not move to
    # the middle of the range and be called "initial"
    path = os.path.join(tmp, "drained_edge.h5")
    ref = write_run(path)
    with h5py.File(path, "a") as f:
        sigma_g = f["snapshots/sigma_g"][()]
        edge = ref["r_c"] > 0.3 * ref["r_c"][-1]
        sigma_g[1:, edge] *= 1e-12
        f["snapshots/sigma_g"][...] = sigma_g
    run = reader.load_run(path)
    initial = plot_run.dust_to_gas_reference(run)
    assert np.isclose(initial, 0.01, rtol=1e-6), initial
    with captured_figures() as figures:
        plot_run.plot_map(run, os.path.join(tmp, "drained_dtg.png"),
                          **dict(plot_run.MAPS)["rt_dust_to_gas.png"])
    mesh = figures[0].axes[0].collections[0]
    assert np.isclose(10 ** mesh.norm.vcenter, initial, rtol=1e-9), 10 ** mesh.norm.vcenter
    bar_label = figures[0].axes[1].get_ylabel()
    assert f"initial {initial:.3g}" in bar_label, bar_label
    return f"dust-to-gas map with a drained gas edge: white = the initial ratio ({bar_label})"


def check_plot_unfinished_title(tmp):
    # a killed run's profile figures must not call its last snapshot t_end
    titles = {}
    for label, options in (("killed", {"killed": True}), ("complete", {})):
        path = os.path.join(tmp, f"title_{label}.h5")
        write_run(path, **options)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = reader.load_run(path)
        indices = plot.select_snapshots(run.time)
        for make in (plot.plot_sigma_d, plot.plot_dust_to_gas):
            fig = make(run, indices, os.path.join(tmp, f"title_{label}.png"))
            titles.setdefault(label, []).append(fig.axes[0].get_title())
    assert all("unfinished, last snapshot" in t and "end" not in t
               for t in titles["killed"]), titles
    assert all("t_\\mathrm{end}" in t and "unfinished" not in t for t in titles["complete"]), titles
    return f"plot: an unfinished run's profile figures say so ({titles['killed'][0]!r})"


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


def write_distribution_run(path, n_cells=12, n_bins=20):
    """A synthetic size-distribution run (model.kind = "distribution"): /snapshots/sigma
    (nt, n_cells * n_bins) cell by cell, deflated as panoptic writes it, the mass grid,
    and sigma_d, a, St from it; returns (time, sigma (nt, n_cells, n_bins), a_bins)."""
    time_yr = np.array([0.0, 1e3, 1e4])
    write_run(path, n_cells=n_cells, time_yr=time_yr)
    with h5py.File(path, "r") as f:
        r_c = f["grid/r_c"][:]
    m_bins = np.geomspace(1e-12, 1e2, n_bins)
    a_bins = (3 * m_bins / (4 * np.pi * 1.67)) ** (1 / 3)
    # a log-normal in a per cell, its peak growing with time and shrinking with r
    peak = 1e-4 * (1 + time_yr[:, None, None] / 1e2) / r_c[None, :, None]
    sigma = np.exp(-0.5 * np.log(a_bins[None, None, :] / peak) ** 2) * r_c[None, :, None] ** -1
    sigma[..., -3:] = 0.0                       # empty top bins, as before growth
    with h5py.File(path, "a") as f:
        f.attrs["config_toml"] = (CONFIG_TOML + '\n[model]\nkind = "distribution"\n'
                                  '[material]\nice_rho0 = 1.67\n[fragmentation]\n'
                                  'enabled = true\nv_frag_ice_m_s = 1.0\n')
        write_dataset(f["grid"], "m_bins", m_bins, "g", "mass of every bin")
        write_dataset(f["grid"], "a_bins", a_bins, "cm", "radius of every bin")
        write_dataset(f["disk"], "c_s", np.full(n_cells, 5e4), "cm s^-1", "sound speed")
        write_dataset(f["disk"], "eta", np.full(n_cells, 2e-3), "", "eta")
        snap = f["snapshots"]
        for name in ("sigma_d", "a", "St"):
            del snap[name]
        dset = snap.create_dataset("sigma", data=sigma.reshape(len(time_yr), -1),
                                   chunks=(1, n_cells * n_bins), compression="gzip",
                                   shuffle=True, maxshape=(None, n_cells * n_bins))
        dset.attrs["units"], dset.attrs["description"] = "g cm^-2", "sigma(r, m)"
        dominant = a_bins[np.argmax(sigma, axis=2)]
        write_dataset(snap, "sigma_d", sigma.sum(axis=2), "g cm^-2", "sum of the bins", True)
        write_dataset(snap, "a", dominant, "cm", "mass-dominating radius", True)
        write_dataset(snap, "St", dominant / 10.0, "", "St of the mass-dominating bin", True)
    return time_yr, sigma, a_bins


def check_distribution_panel(tmp):
    """run.size_distribution gives sigma (cells, bins) of the chosen snapshot, whose sum
    over the bins is sigma_d; the panel's map shows exactly those values (bins as rows),
    its sigma(a) curves are those of the nearest cells, and the command writes a PNG."""
    path = os.path.join(tmp, "distribution.h5")
    time_yr, sigma, a_bins = write_distribution_run(path)
    run = reader.load_run(path)
    assert run.has_distribution and not reader.load_run(write_full_run_path(tmp)).has_distribution
    t, s = run.size_distribution(1.1e3)
    assert t == 1e3 and s.shape == sigma.shape[1:], (t, s.shape)
    assert np.array_equal(s, sigma[1])
    assert np.allclose(s.sum(axis=1), run.at_time("sigma_d", t)[1], rtol=1e-14)
    fig = plot_distribution.panel(run, 1e3, radii_au=[1.0, 10.0])
    ax_map, ax_dist = fig.axes[0], fig.axes[1]
    shown = ax_map.collections[0].get_array()
    values = np.ma.filled(shown, 0.0).reshape(len(a_bins), -1)
    top = sigma[1].max()
    expect = np.where(sigma[1].T > top * 10.0 ** -plot_distribution.DECADES, sigma[1].T, 0.0)
    assert np.array_equal(values, expect), "map differs from sigma(r, a)"
    i10 = int(np.argmin(np.abs(np.log(run.r_c / 10.0))))
    y = ax_dist.lines[1].get_ydata()
    assert np.array_equal(np.nan_to_num(y), sigma[1][i10]), "sigma(a) at 10 au"
    a_rep = ax_map.lines[0].get_ydata()
    assert np.array_equal(a_rep, a_bins[np.argmax(sigma[1], axis=1)])
    out = os.path.join(tmp, "dist_plots")
    with contextlib.redirect_stdout(io.StringIO()):
        assert plot_distribution.main([path, "-o", out, "--time-yr", "1e4"]) == 0
    assert _is_png(os.path.join(out, "distribution.png"))
    return f"sigma {s.shape}, sums equal sigma_d, map and curves equal the data"


def check_distribution_limits_at_rho_int(tmp):
    """The panel's fragmentation and drift limits are Epstein Stokes numbers written as
    radii: without /snapshots/rho_int at the scene's ice_rho0 (1.67); with it (a porous
    run) at each cell's rho_int, so a_limit scales as 1.67 / rho_int cell by cell, and a
    cell whose rho_int is 0 (no dust) has no limit (NaN)."""
    path = os.path.join(tmp, "distribution_rho.h5")
    write_distribution_run(path, n_cells=40)
    a_frag, a_drift = plot_distribution.size_limits(reader.load_run(path), 1e3)
    n = len(a_frag)
    rho_int = np.geomspace(1e-4, 1.0, 3 * n).reshape(3, n)  # per snapshot and cell
    rho_int[1, 5] = 0.0
    with h5py.File(path, "a") as f:
        write_dataset(f["snapshots"], "rho_int", rho_int, "g cm^-3", "internal density", True)
    a_frag_p, a_drift_p = plot_distribution.size_limits(reader.load_run(path), 1e3)
    live = rho_int[1] > 0
    scale = 1.67 / rho_int[1][live]
    assert np.allclose(a_frag_p[live], a_frag[live] * scale, rtol=1e-13, atol=0)
    assert np.allclose(a_drift_p[live], a_drift[live] * scale, rtol=1e-13, atol=0)
    assert np.isnan(a_frag_p[5]) and np.isnan(a_drift_p[5])
    return f"limits x 1.67/rho_int over {int(live.sum())} cells, NaN where rho_int = 0"


def check_model_error(tmp):
    """compare_runs of a run against itself is exactly nothing; against a copy with one
    cell's Sigma_d x 1.25 and St x 2, m_out_inner + 1 % of the initial dust and another
    [model] and porosity.bins, it gives those numbers and no scene warning; a copy with another disk.alpha
    is warned about by key; other grids are refused, by the command line too (status 1);
    the command line writes both tables as CSV (--csv, with --r-au)."""
    path = os.path.join(tmp, "model_error_ref.h5")
    ref, _ = write_full_run(path)
    profiles, outcomes = model_error.compare_runs(path, path)
    ratios = [c for c in profiles.columns if c.endswith(("_median", "_worst"))]
    assert np.all(profiles[ratios].to_numpy() == 1.0), "self ratios"
    others = profiles.drop(columns=["t_yr", "dusty_cells", *ratios]).to_numpy()
    assert others.size and np.all(others == 0.0), "self differences"
    assert np.all(outcomes["difference"] == 0.0) and len(outcomes) >= 8, outcomes
    # the perturbed copy: cell k is the dustiest one at the two times compared
    chosen = [ref["time"][20], ref["time"][-1]]
    k = int(np.argmax(np.minimum(ref["sigma_d"][20], ref["sigma_d"][-1])))
    other = os.path.join(tmp, "model_error_run.h5")
    write_full_run(other)
    m0 = ref["m_dust"][0]
    with h5py.File(other, "a") as f:
        f["snapshots/sigma_d"][:, k] *= 1.25
        f["snapshots/St"][:] *= 2.0
        f["snapshots/m_out_inner"][:] += 0.01 * m0
        f.attrs["config_toml"] = (CONFIG_TOML + '\n[model]\nkind = "distribution"\n'
                                  '\n[porosity]\nbins = "track"\n')
    # a distribution's mean mass, which the single size's m stands for
    for name, value in ((other, {"m": 1e-3}), (path, {"m": 1e-3, "m_mean": 2.5e-4})):
        with h5py.File(name, "a") as f:
            for field, v in value.items():
                write_dataset(f["snapshots"], field, np.full_like(ref["sigma_d"], v), "g",
                              field, extendible=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # [model] and porosity.bins: not warned about
        profiles, _ = model_error.compare_runs(other, path, times_yr=chosen)
    assert np.array_equal(profiles["t_yr"], chosen), profiles["t_yr"]
    i = [int(np.argmin(np.abs(ref["time"] - t))) for t in profiles["t_yr"]]
    sd = ref["sigma_d"][i]
    expect = 0.25 * sd[:, k] * ref["area"][k] / (sd @ ref["area"])
    assert np.allclose(profiles["sigma_d_l1"], expect, rtol=1e-12, atol=0.0), \
        (profiles["sigma_d_l1"], expect)
    assert np.allclose(profiles["sigma_d_worst"], 1.25, rtol=1e-12), profiles["sigma_d_worst"]
    assert np.all(profiles["sigma_d_median"] == 1.0), "one cell of many moves no median"
    assert np.allclose(profiles[["St_median", "St_worst"]], 2.0, rtol=1e-14)
    assert np.all(profiles["m_median"] == 1.0) and np.allclose(profiles["m_mean_median"], 4.0)
    assert np.allclose(profiles["m_out_inner"], 0.01, rtol=1e-12)
    # another disk is not the model's error: warned, by key
    with h5py.File(other, "a") as f:
        f.attrs["config_toml"] = CONFIG_TOML.replace("1e-3", "1e-4")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model_error.compare_runs(other, path)
    assert any("disk.alpha" in str(w.message) for w in caught), [str(w.message) for w in caught]
    # another grid is refused
    coarse = os.path.join(tmp, "model_error_coarse.h5")
    write_run(coarse, n_cells=100)
    try:
        model_error.compare_runs(coarse, path)
        raise AssertionError("different grids accepted")
    except ValueError as err:
        assert "100 cells" in str(err) and "[grid]" in str(err), err
    with contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(io.StringIO()) as err:
        status = model_error.main([coarse, path])
    assert status == 1 and "radial grids differ" in err.getvalue(), (status, err.getvalue())
    prefix = os.path.join(tmp, "model_error")
    with contextlib.redirect_stdout(io.StringIO()) as out:
        assert model_error.main([path, path, "--csv", prefix, "--r-au", "1,100"]) == 0
    written = pd.read_csv(f"{prefix}_profiles.csv")
    assert "sigma_d_l1" in out.getvalue() and len(written) == len(reader.load_run(path).time)
    assert (written["sigma_d_l1"] == 0).all() and len(pd.read_csv(f"{prefix}_outcomes.csv")) >= 8
    return f"self: 0; Sigma_d L1 {profiles['sigma_d_l1'].iloc[-1]:.3g} as expected; grids checked"


def write_full_run_path(tmp):
    """A single-size run file (no distribution)."""
    path = os.path.join(tmp, "single_size_for_distribution.h5")
    write_run(path, n_cells=8)
    return path


def _is_png(path):
    """True if path exists and starts with the PNG signature."""
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n"


CHECKS = [check_reader_complete, check_reader_killed, check_reader_torn_dataset,
          check_reader_new_groups,
          check_reader_groups_absent, check_reader_refuses_other_files,
          check_reader_stopped_or_failed_not_finished,
          check_reader_timeseries_killed,
          check_reader_timeseries_zero_rows, check_reader_monitor_names,
          check_i0e_vs_numpy, check_i0e_large_x, check_ring_mass, check_ring_gaussian_limit,
          check_lbp, check_drift_velocity, check_snapshot_selection, check_plot,
          check_plot_single_snapshot, check_plot_run_helpers, check_plot_run_full,
          check_plot_functions_return_figures,
          check_plot_run_formed_threshold,
          check_snow_line_off, check_t_first_off_axis_label, check_plot_scan,
          check_dust_to_gas_map_centre, check_plot_unfinished_title,
          check_plot_run_transport_only, check_plot_run_degraded,
          check_plot_run_failure_status, check_plot_run_single_snapshot,
          check_distribution_panel, check_distribution_limits_at_rho_int, check_model_error]


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
