"""Read a panoptic run file (HDF5) into numpy arrays.

Layout (written by the C++ code):
    /                attrs config_toml, git_sha, version, scene (str)
    /grid/r_c, r_f   cell centres (N,) and faces (N+1,) [au]; /grid/area (N,) [cm^2]
    /disk/*          static gas-disk fields at cell centres (N,); attr r_snow_au
    /snapshots/*     time (nt,) [yr] and per-snapshot fields (nt, ...), e.g.
                     sigma_d, sigma_g [g cm^-2] (nt, N), m_dust [g] (nt,)
    /solver          attrs nst, nfe, nje, netf, nni, nncf, wall_s, status
Every dataset carries `units` and `description` attributes.

Usage:
    run = load_run("out/run.h5")
    run.field("sigma_d")        # (nt, N) [g cm^-2]
    run.dust_mass()             # (nt,) [g]
    profile, t = run.at_time("sigma_d", 1e5)
"""
import tomllib
import warnings

import h5py
import numpy as np


class Run:
    """Contents of one run file, fully loaded into memory.

    Attributes:
        path        file the run was read from
        r_c, r_f    cell centres (N,) and faces (N+1,) [au]
        area        cell (annulus) areas (N,) [cm^2]
        grid        dict name -> array of every /grid dataset (r_c, r_f, area, ...)
        time        snapshot times (nt,) [yr]
        snapshots   dict name -> array with first dimension nt (every /snapshots dataset,
                    including "time")
        disk        dict name -> array (N,), static gas-disk fields
        r_snow_au   snow-line radius [au], NaN if the disk has none
        units       dict dataset path ("snapshots/sigma_d", "grid/r_c", ...) -> unit str
        attrs       root attributes as str (config_toml, git_sha, version, scene)
        solver      dict of /solver attributes (empty if the run did not finish)
        config      the resolved scene, config_toml parsed with tomllib (empty if absent)
    """

    def __init__(self, path, grid, disk, r_snow_au, snapshots, units, attrs, solver):
        self.path = str(path)
        self.r_c = grid["r_c"]
        self.r_f = grid["r_f"]
        self.area = grid["area"]
        self.grid = grid
        self.disk = disk
        self.r_snow_au = r_snow_au
        self.snapshots = snapshots
        self.time = snapshots["time"]
        self.units = units
        self.attrs = attrs
        self.solver = solver
        self.config = _parse_config(attrs.get("config_toml", ""), self.path)

    @property
    def scene(self):
        """Scene name (root attribute `scene`), "" if absent."""
        return self.attrs.get("scene", "")

    @property
    def n_snapshots(self):
        """Number of complete snapshots nt."""
        return len(self.time)

    def field(self, name):
        """Array of a dataset, by short name or by path.

        A short name ("sigma_d", "T", "r_c") is looked up in /snapshots, then /disk,
        then /grid; a path ("disk/T", "snapshots/St") selects the group explicitly.
        """
        groups = {"snapshots": self.snapshots, "disk": self.disk, "grid": self.grid}
        group, _, key = name.strip("/").rpartition("/")
        if group:
            if group in groups and key in groups[group]:
                return groups[group][key]
        else:
            for fields in groups.values():
                if key in fields:
                    return fields[key]
        raise KeyError(f"{name!r} not in {self.path}; datasets: {sorted(self.units)}")

    def dust_mass(self):
        """Total dust mass on the grid per snapshot, sum(sigma_d * area) [g], (nt,)."""
        return self.snapshots["sigma_d"] @ self.area

    def at_time(self, name, t_yr):
        """(profile, time [yr]) of snapshot field `name` at the snapshot nearest t_yr."""
        i = int(np.argmin(np.abs(self.time - t_yr)))
        return self.snapshots[name][i], float(self.time[i])


def load_run(path):
    """Read the run file at `path` (read-only) and return a Run.

    Snapshot datasets are cut to the smallest first dimension among them, so a file
    whose writer was killed between two dataset appends still loads consistently.
    """
    with _open_read_only(path) as f:
        units = {}
        f.visititems(lambda name, obj: _collect_units(units, name, obj))
        grid = _read_group(f, "grid")
        disk = _read_group(f, "disk")
        r_snow_au = float(f["disk"].attrs.get("r_snow_au", np.nan)) if "disk" in f else np.nan
        snapshots = _truncate_to_common_length(_read_group(f, "snapshots"), path)
        attrs = {k: _to_str(v) for k, v in f.attrs.items()}
        solver = {k: _to_python(v) for k, v in f["solver"].attrs.items()} if "solver" in f else {}
    return Run(path, grid, disk, r_snow_au, snapshots, units, attrs, solver)


def _open_read_only(path):
    """h5py.File(path, 'r'), with a hint when a killed writer left the file flagged."""
    try:
        return h5py.File(path, "r")
    except OSError as err:
        if "consistency flags" in str(err):
            raise OSError(f"{path}: the writer did not close the file; run "
                          f"`h5clear -s {path}` (on a copy, if you prefer) and retry") from err
        raise


def _collect_units(units, name, obj):
    """visititems callback: record the `units` attribute of every dataset."""
    if isinstance(obj, h5py.Dataset):
        units[name] = _to_str(obj.attrs.get("units", ""))


def _read_group(f, group):
    """dict name -> array of the datasets directly inside `group` (empty if absent)."""
    if group not in f:
        return {}
    return {name: obj[()] for name, obj in f[group].items() if isinstance(obj, h5py.Dataset)}


def _truncate_to_common_length(snapshots, path):
    """Cut every snapshot array to the smallest first dimension among them."""
    lengths = {name: a.shape[0] for name, a in snapshots.items() if a.ndim >= 1}
    if "time" not in lengths:
        raise KeyError(f"{path}: /snapshots/time is missing")
    nt = min(lengths.values())
    short = sorted(name for name, n in lengths.items() if n > nt)
    if short:
        warnings.warn(f"{path}: snapshot datasets have unequal lengths (killed run?); "
                      f"using the first {nt} rows of {', '.join(short)}", stacklevel=3)
    return {name: (a[:nt] if name in lengths else a) for name, a in snapshots.items()}


def _parse_config(text, path):
    """config_toml as a dict; {} (with a warning if non-empty) when it does not parse."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        warnings.warn(f"{path}: config_toml does not parse: {err}", stacklevel=4)
        return {}


def _to_str(value):
    """HDF5 string attribute (str, bytes, numpy bytes or 1-element array) as str."""
    if isinstance(value, np.ndarray) and value.size == 1:
        value = value.item()
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8")
    return str(value)


def _to_python(value):
    """HDF5 attribute value as a plain Python int / float / str."""
    if isinstance(value, np.ndarray) and value.size == 1:
        value = value.item()
    if isinstance(value, (bytes, np.bytes_, str)):
        return _to_str(value)
    return value.item() if isinstance(value, np.generic) else value
