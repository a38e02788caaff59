"""Shared helpers of the regression tests: run the panoptic executable on a scene with
overrides, read its output with postprocess.reader, and report checks.

Every test script is called by CTest as
    /usr/bin/python3 tests/regression/test_X.py --exe build/panoptic --workdir DIR
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


# The constants of spec §1.1, copied from the spec (not read from src/units.hpp)
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
