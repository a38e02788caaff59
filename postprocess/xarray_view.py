"""Run.to_xarray(): a run's arrays as an xarray.Dataset (xarray is optional: Debian's
python3-xarray)."""
import numpy as np


def run_to_xarray(run):
    """xarray.Dataset of `run` (a reader.Run): /snapshots on dims (t, r), (t, r_f) or
    (t, monitor); /disk on r; /timeseries on t_series (and monitor, budget_column);
    coordinates t [yr], r [au] (cell centres), r_f [au] (faces), monitor (names) with
    r_monitor [au]; every variable's `units` and `description` attributes from the file;
    /summary scalars and the root attributes as the dataset's attributes."""
    try:
        import xarray as xr
    except ImportError as err:
        raise ImportError("Run.to_xarray needs xarray (Debian: apt install python3-xarray; "
                          "in a venv made with --system-site-packages it is then seen)") from err
    n = len(run.r_c)
    n_mon = len(run.pebble_names)
    coords = {"t": ("t", run.time, _attrs(run, "snapshots/time")),
              "r": ("r", run.r_c, _attrs(run, "grid/r_c")),
              "r_f": ("r_f", run.r_f, _attrs(run, "grid/r_f"))}
    if n_mon:
        coords["monitor"] = ("monitor", np.array(run.pebble_names))
        coords["r_monitor"] = ("monitor", run.monitor_r_au, _attrs(run, "pebbles/r_au"))
    variables = {}
    for name, a in run.snapshots.items():
        if name == "time":
            continue
        dims = _dims(a.shape[1:], n, n_mon, ("t",))
        if dims is not None:
            variables[name] = (dims, a, _attrs(run, f"snapshots/{name}"))
    for name, a in run.disk.items():
        if a.shape == (n,):
            variables[f"disk_{name}"] = (("r",), a, _attrs(run, f"disk/{name}"))
    variables["area"] = (("r",), run.area, _attrs(run, "grid/area"))
    ts = run.timeseries
    if ts:
        coords["t_series"] = ("t_series", ts["time"], _attrs(run, "timeseries/time"))
        for name, a in ts.items():
            if name == "time":
                continue
            if name == "mass_budget" and run.budget_columns and \
                    a.shape[1] == len(run.budget_columns):
                coords["budget_column"] = ("budget_column", np.array(run.budget_columns))
                dims = ("t_series", "budget_column")
            else:
                dims = _dims(a.shape[1:], n, n_mon, ("t_series",))
            if dims is not None:
                variables[f"series_{name}"] = (dims, a, _attrs(run, f"timeseries/{name}"))
    attrs = {k: v for k, v in run.attrs.items()}
    attrs.update({f"summary_{k}": v for k, v in run.summary.items() if np.isscalar(v)})
    attrs["path"] = run.path
    attrs["finished"] = int(run.finished)
    ds = xr.Dataset(variables, coords=coords, attrs=attrs)
    if "t_first_pl" in run.summary and np.ndim(run.summary["t_first_pl"]) == 1:
        ds["t_first_pl_final"] = (("r",), run.summary["t_first_pl"],
                                  _attrs(run, "summary/t_first_pl"))
    return ds


def _dims(shape, n, n_mon, lead):
    """The dims of an array with leading dims `lead` and trailing shape `shape`."""
    if shape == ():
        return lead
    if shape == (n,):
        return (*lead, "r")
    if shape == (n + 1,):
        return (*lead, "r_f")
    if n_mon and shape == (n_mon,):
        return (*lead, "monitor")
    return None


def _attrs(run, path):
    """{'units': ..., 'description': ...} of a dataset of the file."""
    return {"units": run.units.get(path, ""), "description": run.descriptions.get(path, "")}
