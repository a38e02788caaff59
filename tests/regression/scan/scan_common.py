"""Shared helpers of the scan tests (test_scan_*.py): write a scan file of a tiny
reduced fiducial scene, run `panoptic scan`, read DIR/summary.h5."""
import os

import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import REPO, run_checked, text

# The fiducial physics (growth, porosity, planetesimals, snow line) on 32 cells to 300 yr:
# about 0.2-0.5 s a run, with planetesimals formed in most runs.
FAST = ["grid.n_cells=32", "output.t_end_yr=300.0", "output.t_first_yr=10.0",
        "output.n_snapshots=6"]


def write_scan(path, axes, sets=FAST, extra=""):
    """axes: list of TOML bodies of [[axis]] tables."""
    text = "[scan]\n"
    text += f'scene = "{os.path.join(REPO, "params/fiducial.toml")}"\n'
    text += "set = [" + ", ".join(f'"{s}"' for s in sets) + "]\n" + extra
    for a in axes:
        text += "\n[[axis]]\n" + a + "\n"
    with open(path, "w") as f:
        f.write(text)
    return path


def scan(exe, scan_file, out, *opts, mpi=None, expect=0, env=None):
    cmd = [exe, "scan", scan_file, "-o", out, *opts]
    if mpi:
        cmd = ["mpirun", "--oversubscribe", "-n", str(mpi)] + cmd
    e = dict(os.environ)
    e.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})
    if env:
        e.update(env)
    return run_checked(cmd, expect, env=e)


def summary(out):
    """DIR/summary.h5 as a dict of numpy arrays: runs/*, axes/*, outcome/*."""
    d = {}
    with open_output(os.path.join(out, "summary.h5")) as f:
        for g in ("runs", "axes", "outcome"):
            for k, ds in f[g].items():
                v = ds[()]
                if v.dtype.kind == "S":
                    v = np.array([x.decode() for x in v])
                d[f"{g}/{k}"] = v
    return d


def run_summary(h5):
    """The /summary scalars of one run file, as the scan table should hold them."""
    out = {}
    with open_output(h5) as f:
        for k, ds in f["summary"].items():
            v = ds[()]
            if v.size == 1:
                out[k] = float(v[0])
            elif k == "t_first_pl":
                out["t_first_pl_min"] = float(np.nanmin(v)) if np.isfinite(v).any() else np.nan
    return out


def run_summary_units(h5):
    """The `units` attribute of each /summary scalar of one run file (t_first_pl's as
    t_first_pl_min's), as the scan's /outcome should carry them."""
    out = {}
    with open_output(h5) as f:
        for k, ds in f["summary"].items():
            name = "t_first_pl_min" if k == "t_first_pl" else k
            out[name] = text(ds.attrs["units"])
    return out


def run_id(h5):
    with open_output(h5) as f:
        return f.attrs["run_id"]
