"""Shared helpers of the regression tests: run the panoptic executable on a scene with
overrides, read its output with postprocess.reader, and report checks.

Every test script (tests/regression/<topic>/test_X.py) is called by CTest as
    PYTHONPATH=.:tests/regression /usr/bin/python3 tests/regression/<topic>/test_X.py \
        --exe build/panoptic --workdir DIR
runs panoptic, compares with postprocess.analytic, prints the numbers it measured and
exits 1 when a check fails."""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

from postprocess.reader import load_run  # noqa: E402

import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def parse_args():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True, help="the panoptic executable")
    ap.add_argument("--workdir", required=True, help="where run outputs go")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    return args


def write_file(folder, name, text):
    """Writes `text` to folder/name (a scene, a table the test makes) and returns the path."""
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def run_checked(cmd, expect=0, env=None):
    """Runs cmd; returns the CompletedProcess. Raises SystemExit, printing the command and
    its output, when the exit code is not `expect` (None: any)."""
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if expect is not None and p.returncode != expect:
        print(" ".join(cmd))
        print(p.stdout)
        print(p.stderr)
        raise SystemExit(f"the command above exited with {p.returncode}, expected {expect}")
    return p


def run(exe, scene, out, sets=(), expect=0):
    """Runs `panoptic run scene --set ... -o out --overwrite` (run_checked)."""
    cmd = [exe, "run", os.path.join(REPO, scene), "-o", out, "--overwrite"]
    for s in sets:
        cmd += ["--set", s]
    return run_checked(cmd, expect)


BUDGET_TERMS = ("m_dust", "m_out_inner", "m_sublimated", "m_pl_coag", "m_pl_si")


def budget_error(snapshots, terms=None):
    """Largest relative error of the dust mass budget over the snapshots: the sum of the
    budget terms (attribute budget_terms of /snapshots, passed as `terms`; the built-in
    ones of a file without it) against the first. The grid, r_in and sublimated terms are
    required; a term that is neither listed nor present is a process that is off."""
    names = list(terms) if terms else [t for t in BUDGET_TERMS if t in snapshots]
    for t in BUDGET_TERMS[:3]:
        if t not in names:
            raise KeyError(f"budget term {t} missing from /snapshots")
    m = sum(snapshots[t] for t in names)
    return float(np.max(np.abs(m / m[0] - 1)))


class Checks:
    """Collects named pass/fail checks and prints 'N passed, M failed' at the end."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed else 0)


__all__ = ["parse_args", "run", "Checks", "load_run", "REPO"]


# The constants of spec §1.1, copied from the spec (not read from src/core/units.hpp)
SPEC_G, SPEC_MSUN, SPEC_AU = 6.674e-8, 1.989e33, 1.496e13
SPEC_KB, SPEC_MH = 1.3807e-16, 1.6735e-24


def alpha_cs_h(config, r_au):
    """nu = alpha c_s H [cm^2 s^-1] of the scene's power-law temperature (spec §1.3, §1.5):
    T = T_1au L^(1/4) r^-q (above disk.T_floor), c_s^2 = k_B T/(mu m_H), H = c_s/Omega_K,
    worked out from the scene's keys and the spec's constants, not from the run's /disk
    fields, so that a factor wrong in the code's c_s or H does not move the reference."""
    d, s = config["disk"], config["star"]
    r_au = np.asarray(r_au, dtype=float)
    temp = np.maximum(d["T_1au"] * s["luminosity_lsun"] ** 0.25 * r_au ** -d["q"],
                      d["T_floor"])
    cs2 = SPEC_KB * temp / (d["mu"] * SPEC_MH)
    omega = np.sqrt(SPEC_G * s["mass_msun"] * SPEC_MSUN / (r_au * SPEC_AU) ** 3)
    return d["alpha"] * cs2 / omega


def text(v):
    """An HDF5 string attribute as str (h5py gives bytes for fixed-length strings)."""
    return v.decode() if isinstance(v, bytes) else str(v)


YR = 3.156e7  # [s]
M0_SIL = 1.26e-14  # [g] the heavier monomer (silicate, 0.1 um, 3 g cm^-3; run header)


def run_with_triples(exe, scene, out, centres):
    """Runs `scene` for the growth tests on the grid (test_fragmentation_limit,
    test_erosion_stall, test_porosity_along_paths): diffusion off, rtol 1e-7, snapshots
    in triples 1e-4 apart (relative) around each of `centres` [yr], the run ending at
    the last. Returns the run and the indices of the triples' middle snapshots (for
    growth_along_paths and carried_rate, which difference k - 1 and k + 1)."""
    times = ", ".join(f"{t * (1 + d):.6g}" for t in centres for d in (-1e-4, 0, 1e-4))
    run(exe, scene, out,
        ["transport.diffusion=false", "solver.rtol=1e-7", f"output.times_yr=[{times}]",
         f"output.t_end_yr={centres[-1] * (1 + 1e-4):.6g}"])
    return load_run(out), [3 * j + 2 for j in range(len(centres))]


def beside_snow_face(r):
    """Cells of run r beside its snow-line face, two on each side (and the cell that
    holds r_snow): there the sublimation makes ln m jump, so the growth tests leave
    them out."""
    i_snow = int(np.searchsorted(r.r_f, r.r_snow_au))
    near = np.zeros(len(r.r_c), dtype=bool)
    near[max(i_snow - 3, 0):i_snow + 2] = True
    return near


def growth_along_paths(r, k):
    """What the transport and the growth law do to ln m of each cell at snapshot k of run
    r (diffusion off), worked out from the snapshots, for the growth tests on the grid
    (test_fragmentation_limit, test_erosion_stall). Snapshots k - 1 and k + 1 must lie
    just before and after k (d ln m/dt is their centred difference). Returns a dict of
    per-cell arrays:
      t_coag     m / (dm/dt)_coag [s], (dm/dt)_coag = f_grow 2 sqrt(pi) a^2 dv Sigma_d / h_d
                 (spec §4.1) with h_d = H / sqrt(1 + St/alpha (1 + 2 St)/(1 + St)) (§2)
      continuum  t_coag (d ln m/dt + v_r d ln m/dr), v_r the mean of the cell's two faces
                 and d ln m/dr centred: the growth factor the transport equation of ln m
                 (spec §6.2) asks for, to the scheme's O(dr/r)
      discrete   t_coag (d ln m/dt - inflow terms): the same in the first-order upwind
                 scheme's own form. With Q_m = Sigma_d ln m carried by the dust flow,
                 A_i Sigma_i d ln m_i/dt = sum over the faces where dust flows in, of the
                 inflow [g/s] times (ln m of the upwind cell - ln m_i), plus A_i Sigma_i
                 times the growth rate (the planetesimal sinks take Q_m and Sigma_d in
                 proportion, to the decoder's regularisation (eps/Sigma_d)^2 with eps =
                 10 solver.atol_sigma max Sigma_d0, and leave ln m alone; in the fiducial
                 scene's converting cells at Sigma_d/Sigma_g ~ 1e-6, where t_coag is
                 ~1e4 yr, that regularisation is 2 % of the growth), so this equals the
                 growth factor to the time difference's and the integration's errors."""
    cfg = r.config
    f_grow = cfg.get("growth", {}).get("f_grow", 1.0)
    H, alpha = r.disk["h_g"], r.disk["alpha"]
    rc = r.r_c * SPEC_AU
    m, a, dv = (r.snapshots[n][k] for n in ("m", "a", "dv"))
    st, sigma_d = r.snapshots["St"][k], r.snapshots["sigma_d"][k]
    h_d = H / np.sqrt(1 + st / alpha * (1 + 2 * st) / (1 + st))
    t_coag = m / (f_grow * 2 * np.sqrt(np.pi) * a**2 * dv * sigma_d / h_d)
    x = np.log(m)
    dx_dt = (np.log(r.snapshots["m"][k + 1]) - np.log(r.snapshots["m"][k - 1])) / (
        (r.time[k + 1] - r.time[k - 1]) * YR)
    v_r = 0.5 * (r.snapshots["v_r"][k][:-1] + r.snapshots["v_r"][k][1:])
    continuum = t_coag * (dx_dt + v_r * np.gradient(x, rc))
    discrete = t_coag * carried_rate(r, k, lambda j: np.log(r.snapshots["m"][j]))
    return {"t_coag": t_coag, "continuum": continuum, "discrete": discrete}


def carried_rate(r, k, values):
    """The rate of change [s^-1] of a particle attribute carried by the dust flow (ln m
    with Q_m, ln(1/phi) with Q_phi: spec §6.2), following the particles, at snapshot k
    (k - 1, k + 1 just around it; diffusion off), in the first-order upwind scheme's own
    form: d x_i/dt minus, for each face where dust flows in, the inflow [g/s] times (x of
    the upwind cell - x_i) over A_i Sigma_i. `values(j)` gives x at snapshot j."""
    x = values(k)
    dx_dt = (values(k + 1) - values(k - 1)) / ((r.time[k + 1] - r.time[k - 1]) * YR)
    mdot = r.snapshots["mdot_d"][k]  # [g/s] on the faces, positive outward
    inflow = np.zeros(len(x))
    outer_in = mdot[1:] < 0  # dust enters cell i through its outer face i + 1
    inflow[:-1] += np.where(outer_in[:-1], -mdot[1:-1] * (x[1:] - x[:-1]), 0.0)
    inner_in = mdot[:-1] > 0  # ... or through its inner face i
    inflow[1:] += np.where(inner_in[1:], mdot[1:-1] * (x[:-1] - x[1:]), 0.0)
    return dx_dt - inflow / (r.area * r.snapshots["sigma_d"][k])
