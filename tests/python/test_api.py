"""The conventions of the Python API (postprocess/, `import panoptic` when installed), on
real panoptic runs: every accessor returns (t, value), time first; every value comes in
the unit its docstring states (/snapshots grams converted to M_earth); a radius that is
not a pebble-flux monitor raises, naming the monitors; a killed run's file (left open
for SWMR writing) opens; panoptic.run raises with panoptic's own message; every plot
function draws into a given ax=; the command line writes PDF without a footer.

    PYTHONPATH=.:tests/regression /usr/bin/python3 tests/python/test_api.py \
        --exe build/panoptic --workdir DIR
"""
import contextlib
import io
import os
import signal
import subprocess
import time
import warnings

import numpy as np

import postprocess as panoptic
from postprocess import plot, plot_run, reader

from common import REPO, Checks, parse_args  # noqa: E402

M_EARTH = 5.972e27      # [g], src/core/units.hpp
MYR = 3.156e13          # [s]
# a reduced fiducial scene: 48 cells to 2000 yr, planetesimals form by ~300 yr
TINY = {"grid.n_cells": 48, "output.t_end_yr": 2e3, "output.n_snapshots": 8}
# slow enough to be caught mid-run (tests/regression/output/test_killed_run.py)
SLOW = ["growth.enabled=false", "porosity.enabled=false", "planetesimals.coagulation=false",
        'planetesimals.si="none"', "grid.n_cells=3000", "solver.rtol=1e-10",
        "output.n_snapshots=400", "output.t_end_yr=1e7", "transport.St=0.05"]


def accessors(c, run):
    """(t, value) order and units of every time-series accessor."""
    ts_t, snap_t = run.timeseries["time"], run.time
    for name, (t, v) in {"planetesimal_mass()": run.planetesimal_mass(),
                         "pebble_flux('snow line')": run.pebble_flux("snow line"),
                         "budget('m_out_inner')": run.budget("m_out_inner"),
                         "series('m_pl_coag')": run.series("m_pl_coag"),
                         "mass_flow(5.0)": run.mass_flow(5.0)}.items():
        c.check(np.ndim(t) == 1 and t.shape == v.shape[:1] and np.all(np.diff(t) > 0) and
                (np.array_equal(t, ts_t) or np.array_equal(t, snap_t)),
                f"{name} returns (t, value): t rising, [yr], {len(t)} samples")
    i = 3
    t, profile = run.at_time("sigma_d", run.time[i])
    c.check(t == run.time[i] and np.array_equal(profile, run.snapshots["sigma_d"][i]),
            f"at_time returns (t, profile): t = {t:g} yr first")

    m_pl = run.summary["m_pl_coag"]
    t, m = run.series("m_pl_coag")
    c.check(m_pl > 0 and np.isclose(m[-1], m_pl, rtol=1e-6) and
            run.series_unit("m_pl_coag") == "M_earth",
            f"series('m_pl_coag') in M_earth: {m[-1]:.6g} = /summary {m_pl:.6g}")
    grams = run.snapshots["m_pl_coag"][-1]
    c.check(np.isclose(grams / M_EARTH, m_pl, rtol=1e-6) and run.unit("snapshots/m_pl_coag") == "g",
            f"/snapshots/m_pl_coag is {grams:.4g} g = {grams / M_EARTH:.6g} M_earth (converted)")
    t, total = run.planetesimal_mass()
    c.check(np.isclose(total[-1], m_pl + run.summary["m_pl_si"], rtol=1e-6),
            f"planetesimal_mass() [M_earth] = m_pl_coag + m_pl_si of /summary ({total[-1]:.6g})")
    k = run.pebble_names.index("snow line")
    t, flux = run.pebble_flux("snow line")
    snap = run.snapshots["pebble_flux"][-1, k] / (M_EARTH / MYR)
    c.check(t[-1] == run.time[-1] and np.isclose(flux[-1], snap, rtol=1e-9),
            f"pebble_flux in M_earth/Myr: {flux[-1]:.6g} = /snapshots {snap:.6g} (g/s converted)")
    t, flow = run.mass_flow(run.monitor_r_au[k])
    c.check(np.isclose(flow[-1], snap, rtol=1e-6),
            f"mass_flow at the snow-line face [M_earth/Myr] = pebble_flux there ({flow[-1]:.6g})")


def monitor_rule(c, run):
    """A radius that is not a monitor raises, naming the monitors; a monitor's face or
    nominal radius selects it."""
    names, faces = run.pebble_names, run.monitor_r_au
    k3 = names.index("3 au")
    for key in ("3 au", 3.0, float(faces[k3])):
        t, flux = run.pebble_flux(key)
        c.check(np.array_equal(flux, run.timeseries["pebble_flux"][:, k3]),
                f"pebble_flux({key!r}) is the 3 au monitor (face {faces[k3]:.6g} au)")
    for r in (5.0, 100.0, 2.9):
        try:
            run.pebble_flux(r)
            c.check(False, f"pebble_flux({r}) raised")
        except KeyError as err:
            text = str(err)
            c.check("not a pebble-flux monitor" in text and "3 au (3" in text and
                    "snow line (" in text and "mass_flow" in text,
                    f"pebble_flux({r}) raises, naming the monitors: {text[:100]}...")


def killed_file(c, exe, wd):
    """A run killed with SIGKILL leaves its file open for SWMR writing: plain h5py refuses
    it, panoptic.load_run opens it; a file that cannot be opened says how to recover."""
    out = os.path.join(wd, "killed.h5")
    if os.path.exists(out):
        os.remove(out)
    cmd = [exe, "run", os.path.join(REPO, "params/fiducial.toml"), "-o", out, "--overwrite"]
    for s in SLOW:
        cmd += ["--set", s]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline, rows = time.time() + 60, 0
    os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"   # read while it writes
    while time.time() < deadline and proc.poll() is None and rows < 4:
        time.sleep(0.05)
        try:
            with reader.open_output(out) as f:
                rows = f["snapshots/time"].shape[0]
        except Exception:  # noqa: BLE001 - a file being written fails in many ways
            rows = 0
    del os.environ["HDF5_USE_FILE_LOCKING"]
    running = proc.poll() is None
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    c.check(running and rows >= 4, f"run killed with SIGKILL after {rows} snapshots")
    plain = subprocess.run(["/usr/bin/python3", "-c", f"import h5py; h5py.File({out!r}, 'r')"],
                           capture_output=True, text=True)
    c.check(plain.returncode != 0 and "already open for write" in plain.stderr,
            "plain h5py.File(path) refuses the killed run's file (\"already open for write\")")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = panoptic.load_run(out)
    c.check(run.n_snapshots >= 3 and not run.finished,
            f"panoptic.load_run opens it: {run.n_snapshots} snapshots, not finished")
    original = reader._open_swmr_read

    def refuse(path):
        raise OSError("unable to open file (simulated)")
    reader._open_swmr_read = refuse
    try:
        reader.load_run(out)
        c.check(False, "an unreadable killed file raises")
    except OSError as err:
        c.check(f"h5clear -s {out}" in str(err),
                f"where SWMR reading fails too, the message says how to recover: {err}")
    finally:
        reader._open_swmr_read = original


def launch_errors(c, exe, wd):
    """panoptic.run raises PanopticError with panoptic's own stderr and exit code."""
    try:
        panoptic.run(os.path.join(REPO, "params/fiducial.toml"), set={"disk.alpha": -1.0},
                     out=os.path.join(wd, "bad.h5"), exe=exe)
        c.check(False, "panoptic.run with disk.alpha = -1 raised")
    except panoptic.PanopticError as err:
        c.check(err.returncode != 0 and "alpha" in str(err) and err.stderr.strip() in str(err),
                f"panoptic.run raises with panoptic's message (exit {err.returncode}): "
                f"{str(err).splitlines()[0][:90]}")
    try:
        panoptic.run("params/fiducial.toml", exe=os.path.join(wd, "no_such_exe"))
        c.check(False, "a missing executable raises")
    except FileNotFoundError as err:
        c.check("no_such_exe" in str(err), "a missing executable is named")


def figures(c, run, wd):
    """Every plot function draws into the axes it is given, on the caller's figure, with
    no footer; the t_first_pl legend entry is drawn as the line is; overlays."""
    fig = plot.style.new_figure(12, 8)
    axes = fig.subplots(3, 3).ravel()
    made = [plot.plot_sigma_d(run, ax=axes[0]), plot.plot_dust_to_gas(run, ax=axes[1]),
            plot_run.plot_map(run, ax=axes[2], **dict(plot_run.MAPS)["rt_St.png"]),
            plot_run.plot_pebble_flux(run, ax=axes[3]),
            plot_run.plot_sigma_pl(run, ax=axes[4]),
            plot_run.plot_mass_budget(run, ax=axes[5]),
            panoptic.overlay_profiles([run, run], "sigma_d", ax=axes[6], labels=["a", "b"]),
            panoptic.overlay_series([run, run], "planetesimal_mass", ax=axes[7]),
            panoptic.overlay_series([run], "pebble_flux", monitor="snow line", ax=axes[8])]
    c.check(all(f is fig for f in made) and all(a.has_data() for a in axes) and not fig.texts,
            f"{len(made)} plot functions draw into the given axes, return the caller's "
            "figure and add no footer")
    ax = axes[2]
    drawn = [line for line in ax.get_lines() if line.get_color() == plot_run.T_FIRST_STYLE["color"]]
    entry = [h for h in ax.get_legend().legend_handles if "first" in h.get_label()] \
        if hasattr(ax.get_legend(), "legend_handles") else \
        [h for h in ax.get_legend().legendHandles if "first" in h.get_label()]
    same = (len(drawn) == 1 and len(entry) == 1 and
            entry[0].get_color() == drawn[0].get_color() and
            entry[0].get_linewidth() == drawn[0].get_linewidth() and
            entry[0].get_path_effects() == drawn[0].get_path_effects())
    c.check(same, "r-t map: the t_first_pl legend entry has the colour, width and edge of "
                  "the line drawn")
    path = os.path.join(wd, "grid_of_panels.pdf")
    fig.savefig(path)
    c.check(open(path, "rb").read(5) == b"%PDF-", "the caller's figure saves as PDF")


def command_line(c, run, wd):
    """panoptic-plot --format pdf --no-footer --title --size column."""
    outdir = os.path.join(wd, "plots_pdf")
    with contextlib.redirect_stdout(io.StringIO()) as out, \
            contextlib.redirect_stderr(io.StringIO()):
        status = plot_run.main([run.path, "-o", outdir, "--format", "pdf", "--no-footer",
                                "--title", "my title", "--size", "column"])
    written = out.getvalue().split()
    c.check(status == 0 and len(written) == 9 and all(
        p.endswith(".pdf") and open(p, "rb").read(5) == b"%PDF-" for p in written),
        f"plot_run --format pdf writes {len(written)} PDF files")
    with plot.style.using(width="column", footer=False, title="my title"):
        fig = plot_run.plot_sigma_pl(run)
    w, _ = fig.get_size_inches()
    footer = [t for t in fig.texts if "panoptic" in t.get_text()]
    c.check(np.isclose(w, 3.5) and fig._suptitle.get_text() == "my title" and not footer,
            f"--size column: {w:g} in wide; --title replaces the title; --no-footer: none")
    fig = plot_run.plot_sigma_pl(run)
    c.check(any(run.path.split("/")[-1] in t.get_text() for t in fig.texts),
            "without --no-footer the footer names the file")


def xarray_view(c, run):
    try:
        import xarray  # noqa: F401 (only whether it is there)
    except ImportError:
        try:
            run.to_xarray()
            c.check(False, "to_xarray without xarray raises")
        except ImportError as err:
            c.check("python3-xarray" in str(err), f"to_xarray without xarray: {err}")
        return
    ds = run.to_xarray()
    c.check(ds["sigma_d"].dims == ("t", "r") and ds["sigma_d"].attrs["units"] == "g cm^-2"
            and ds["mdot_d"].dims == ("t", "r_f"),
            "to_xarray: sigma_d on (t, r) [g cm^-2], mdot_d on (t, r_f)")


def main():
    args = parse_args()
    c = Checks()
    run = panoptic.run(os.path.join(REPO, "params/fiducial.toml"), set=TINY,
                       out=os.path.join(args.workdir, "tiny.h5"), exe=args.exe)
    print(f"{run}")
    accessors(c, run)
    monitor_rule(c, run)
    launch_errors(c, args.exe, args.workdir)
    figures(c, run, args.workdir)
    command_line(c, run, args.workdir)
    xarray_view(c, run)
    killed_file(c, args.exe, args.workdir)
    c.finish()


if __name__ == "__main__":
    main()
