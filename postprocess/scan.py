"""A parameter scan's table: DIR/summary.h5 (written by `panoptic scan ... -o DIR`).

    df = load_scan("out/scan_mass_alpha")     # pandas.DataFrame, one row per run
    df.attrs["units"]["m_pl_coag"]            # "M_earth"
    load_run(df.path[0])                      # a run of it

load_summary(DIR) gives the same as a dict of numpy arrays (the figures of plot_scan
use it).
"""
import os

import h5py
import numpy as np


def _str(v):
    """An HDF5 string (bytes or str) as str."""
    return v.decode() if isinstance(v, bytes) else str(v)


def _summary_path(scan_dir):
    """DIR/summary.h5, FileNotFoundError saying what to give when it is missing."""
    path = os.path.join(scan_dir, "summary.h5")
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path} not found: give the directory of `panoptic scan "
                                f"... -o DIR` (the summary is written when its runs end)")
    return path


def load_summary(scan_dir):
    """The summary table: dict with 'status', 'name', 'axes' {key: (values, spacing)},
    'outcome' {name: values}, 'units' {name: units attribute}, 'sampling', 'scene' (the
    base scene's name)."""
    with h5py.File(_summary_path(scan_dir), "r") as f:
        dec = lambda a: np.array([x.decode() for x in a])  # noqa: E731
        axes = {}
        for k in _str(f.attrs["axes"]).split(","):
            ds = f["axes"][k]
            sp = _str(ds.attrs.get("spacing", "list"))
            v = ds[()] if ds.dtype.kind == "f" else dec(ds[()])
            if sp == "list" and v.dtype.kind == "f" and np.all(v > 0) and (
                    v.max() >= 100 * v.min() * (1 - 1e-9)):
                sp = "log"  # a list of positive numbers over two decades or more
            axes[k] = (v, sp)
        return {"status": dec(f["runs/status"][()]), "name": dec(f["runs/name"][()]),
                "axes": axes, "sampling": _str(f.attrs["sampling"]),
                "scene": os.path.splitext(os.path.basename(_str(f.attrs.get("scene", ""))))[0],
                "outcome": {k: ds[()] for k, ds in f["outcome"].items()},
                "units": {k: _str(ds.attrs.get("units", "")) for k, ds in f["outcome"].items()}}


def load_scan(scan_dir):
    """The scan as a pandas.DataFrame, one row per run (in manifest order).

    Columns: `name`, `status` ("completed", "failed", "interrupted", "incomplete",
    "not run"), `path` (the run's output DIR/runs/<name>.h5, absolute), one column per
    scan axis (its scene key, e.g. "disk.alpha", in the key's unit), one per outcome
    (the runs' /summary scalars: m_pl_coag [M_earth], t_first_pl_min [yr], ...; NaN
    where a run has none), and the bookkeeping of /runs (`exit_code`, `wall_s` [s],
    `steps`, `error`) when present.
    df.attrs: "units" {column: unit ("" = dimensionless or the key's own)}, "axes"
    [keys], "spacing" {key: "lin"|"log"|"list"}, "outcomes" [names], "sampling"
    ("grid", "lhs", ...), "scene" (the base scene's name), "dir" (absolute).
    """
    import pandas as pd
    s = load_summary(scan_dir)
    root = os.path.abspath(scan_dir)
    columns = {"name": s["name"], "status": s["status"],
               "path": [os.path.join(root, "runs", f"{n}.h5") for n in s["name"]]}
    units = {"name": "", "status": "", "path": ""}
    for key, (values, _) in s["axes"].items():
        columns[key] = values
        units[key] = _key_unit(key)
    for name, values in s["outcome"].items():
        columns[name] = values
        units[name] = s["units"].get(name, "")
    with h5py.File(_summary_path(scan_dir), "r") as f:
        for name, unit in (("exit_code", ""), ("wall_s", "s"), ("steps", ""), ("error", "")):
            if f"runs/{name}" in f:
                a = f[f"runs/{name}"][()]
                columns[name] = [_str(x) for x in a] if a.dtype.kind in "SO" else a
                units[name] = unit
    df = pd.DataFrame(columns)
    df.attrs.update({"units": units, "axes": list(s["axes"]),
                     "spacing": {k: sp for k, (_, sp) in s["axes"].items()},
                     "outcomes": list(s["outcome"]), "sampling": s["sampling"],
                     "scene": s["scene"], "dir": root})
    return df


_SUFFIX_UNITS = (("_msun", "M_sun"), ("_lsun", "L_sun"), ("_au", "au"), ("_yr", "yr"),
                 ("_m_s", "m s^-1"), ("_um", "um"), ("_cm", "cm"), ("_K", "K"))
_KEY_UNITS = {"disk.T_1au": "K", "disk.sigma_1au": "g cm^-2"}


def _key_unit(key):
    """The unit of a scene key, from its suffix (`_au`, `_msun`, ...); "" otherwise."""
    if key in _KEY_UNITS:
        return _KEY_UNITS[key]
    for suffix, unit in _SUFFIX_UNITS:
        if key.endswith(suffix):
            return unit
    return ""
