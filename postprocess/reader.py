"""Read a panoptic run file (HDF5) into numpy arrays.

Layout (written by the C++ code):
    /                attrs config_toml, git_sha, version, scene (str)
    /grid/r_c, r_f   cell centres (N,) and faces (N+1,) [au]; /grid/area (N,) [cm^2]
    /disk/*          static gas-disk fields at cell centres (N,); attr r_snow_au
    /snapshots/*     time (nt,) [yr] and per-snapshot fields (nt, ...), e.g.
                     sigma_d, sigma_g [g cm^-2] (nt, N), m_dust [g] (nt,); attr
                     budget_terms (";"-separated names of the mass-budget datasets)
    /timeseries/*    finer-sampled diagnostics: time (ns,) [yr], pebble_flux
                     [M_earth Myr^-1] and m_through [M_earth] (ns, n_monitors),
                     mass_budget [M_earth] (ns, n_terms + 1); attr
                     mass_budget_columns of the group (";"-separated, "error" last)
    /pebbles/r_au    pebble-flux monitor radii (n_monitors,) [au]; attr names
                     (";"-separated, same order)
    /summary/*       end-of-run numbers: 1-element datasets (m_pl_coag [M_earth],
                     r_min_pl_si [au], budget_error, ...) and t_first_pl (N,) [yr]
    /solver          attrs nst, nfe, nje, nsetups, netf, nni, nncf, nreinit, wall_s,
                     status
Every dataset carries `units` and `description` attributes. /timeseries, /pebbles and
/summary are absent from older and transport-only files; /summary is written when the
run completes, /solver also when it stops or fails (its status says which).

Arrays come back in the units of the file (each dataset's `units` attribute; run.unit()
gives it): /snapshots in cgs with times in yr and radii in au, /timeseries and /summary
in M_earth, Myr and au. The same short name can live in two groups in different units
(snapshots/m_pl_coag [g], summary/m_pl_coag [M_earth]): field() then takes /snapshots
and warns; give the path to choose.

Usage:
    run = load_run("out/run.h5")
    run.field("sigma_d")                    # (nt, N) [g cm^-2]
    run.unit("sigma_d")                     # "g cm^-2"
    profile, t = run.at_time("sigma_d", 1e5)   # nearest snapshot, [g cm^-2] and [yr]
    t, m_pl = run.planetesimal_mass()       # (ns,) [yr], [M_earth] (all channels)
    t, flux = run.pebble_flux("snow line")  # (ns,) [yr], [M_earth Myr^-1]
    t, m = run.budget("m_out_inner")        # (ns,) [yr], [M_earth]
    run.dust_mass()                         # (nt,) [g]
"""
import os
import tomllib
import warnings

import h5py
import numpy as np

# The unit constants of the C++ code (src/core/units.hpp), for conversions of the file's units
M_EARTH = 5.972e27      # [g]
M_SUN = 1.989e33        # [g]
AU = 1.496e13           # [cm]
YR = 3.156e7            # [s]
MYR = 1e6 * YR          # [s]

# The mass-budget terms of a file written before the attributes that name them
# (/snapshots budget_terms, /timeseries mass_budget_columns), in their column order
BUILT_IN_BUDGET_TERMS = ("m_dust", "m_pl_coag", "m_pl_si", "m_out_inner", "m_sublimated")


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
        r_snow_au   snow-line radius [au], NaN if the disk has none: also when the scene
                    has snowline.enabled = false (icy solids everywhere), whose /disk
                    attribute r_snow_au still holds the radius where T = T_sub
        timeseries  dict name -> array with first dimension ns (every /timeseries
                    dataset, including "time" [yr]); {} if the file has none
        pebbles     dict name -> array of every /pebbles dataset (r_au [au]); {} if none
        pebble_names  monitor names (list of str, one per pebbles["r_au"] entry)
        budget_terms  names of the /snapshots datasets [g] whose sum is the dust mass
                    budget (list of str; [] for a file written before the attribute)
        budget_columns  names of the /timeseries/mass_budget columns, "error" last
                    ([] for a file written before the attribute: the six columns
                    m_dust, m_pl_coag, m_pl_si, m_out_inner, m_sublimated, error)
        summary     dict name -> value of every /summary dataset: 1-element datasets as
                    float (m_pl_coag [M_earth], r_min_pl_coag [au], budget_error, ...),
                    others as arrays (t_first_pl (N,) [yr]); {} if absent
        units       dict dataset path ("snapshots/sigma_d", "grid/r_c", ...) -> unit str
        descriptions  dict dataset path -> `description` attribute str
        attrs       root attributes as str (config_toml, git_sha, version, scene)
        solver      dict of /solver attributes (empty for a killed run)
        config      the resolved scene, config_toml parsed with tomllib (empty if absent)
    """

    def __init__(self, path, grid, disk, r_snow_au, snapshots, units, attrs, solver,
                 budget_terms=(), budget_columns=(),
                 timeseries=None, pebbles=None, pebble_names=None, summary=None,
                 descriptions=None):
        self.path = str(path)
        self.r_c = grid["r_c"]
        self.r_f = grid["r_f"]
        self.area = grid["area"]
        self.grid = grid
        self.disk = disk
        self.r_snow_au = r_snow_au
        self.snapshots = snapshots
        self.time = snapshots["time"]
        self.timeseries = timeseries or {}
        self.pebbles = pebbles or {}
        self.pebble_names = list(pebble_names or [])
        self.budget_terms = list(budget_terms)
        self.budget_columns = list(budget_columns)
        self.summary = summary or {}
        self.units = units
        self.descriptions = descriptions or {}
        self.attrs = attrs
        self.solver = solver
        self.config = _parse_config(attrs.get("config_toml", ""), self.path)
        if self.config.get("snowline", {}).get("enabled") is False:
            self.r_snow_au = np.nan     # no snow line in the run, only where T = T_sub

    @property
    def scene(self):
        """Scene name (root attribute `scene`), "" if absent."""
        return self.attrs.get("scene", "")

    @property
    def n_snapshots(self):
        """Number of complete snapshots nt."""
        return len(self.time)

    @property
    def finished(self):
        """True when the run completed: /solver's status is "completed". A run stopped
        (SIGINT, SIGTERM, --max-wall) or failed writes /solver too, with another status;
        a killed run has none. Files without a status count as finished with /summary."""
        status = self.solver.get("status")
        if status is None:
            return bool(self.summary)
        return _to_str(status) == "completed"

    @property
    def monitor_r_au(self):
        """Pebble-flux monitor radii (n_monitors,) [au]; empty if the file has none."""
        return self.pebbles.get("r_au", np.zeros(0))

    def field(self, name):
        """Array of a dataset, by short name or by path.

        A short name ("sigma_d", "T", "r_c") is looked up in /snapshots, then /disk,
        /grid, /timeseries, /summary and /pebbles; a path ("disk/T", "snapshots/St",
        "timeseries/pebble_flux") selects the group explicitly.
        """
        groups = {"snapshots": self.snapshots, "disk": self.disk, "grid": self.grid,
                  "timeseries": self.timeseries, "summary": self.summary,
                  "pebbles": self.pebbles}
        group, _, key = name.strip("/").rpartition("/")
        if group:
            if group in groups and key in groups[group]:
                return groups[group][key]
        else:
            found = [g for g, fields in groups.items() if key in fields]
            if found:
                units = {self.units.get(f"{g}/{key}", "") for g in found}
                if len(units) > 1:
                    warnings.warn(f"{name!r} is in {', '.join('/' + g for g in found)} in "
                                  f"different units; returning /{found[0]}/{key} "
                                  f"[{self.units.get(f'{found[0]}/{key}', '')}]: give "
                                  f"the path to choose", stacklevel=2)
                return groups[found[0]][key]
        raise KeyError(f"{name!r} not in {self.path}{_process_hint(key)}; datasets: "
                       f"{sorted(self.units)}")

    def unit(self, name):
        """The `units` attribute of the dataset field(name) returns ("" for a
        dimensionless one)."""
        group, _, key = name.strip("/").rpartition("/")
        if group:
            return self.units[f"{group}/{key}"]
        for g in ("snapshots", "disk", "grid", "timeseries", "summary", "pebbles"):
            if f"{g}/{key}" in self.units:
                return self.units[f"{g}/{key}"]
        raise KeyError(f"{name!r} not in {self.path}{_process_hint(key)}")

    def planetesimal_mass(self):
        """(time [yr], planetesimal mass [M_earth]) of all channels together, on the
        /timeseries samples (or, in a file without them, the snapshots); zeros where the
        scene has no planetesimal channel."""
        names = self._budget_names()
        if names:
            cols = [names.index(c) for c in ("m_pl_coag", "m_pl_si") if c in names]
            mb = self.timeseries["mass_budget"]
            return self.timeseries["time"], mb[:, cols].sum(axis=1)
        m = sum(self.snapshots.get(c, np.zeros_like(self.time)) for c in ("m_pl_coag", "m_pl_si"))
        return self.time, np.asarray(m, dtype=float) / M_EARTH

    def pebble_flux(self, monitor):
        """(time [yr], inward pebble flux [M_earth Myr^-1]) through one monitor, given by
        its name ("snow line", "r_in", "3 au": run.pebble_names) or radius [au] (the
        nearest monitor), on the /timeseries samples."""
        i = self._monitor(monitor)
        if "pebble_flux" not in self.timeseries:
            raise KeyError(f"{self.path} has no /timeseries/pebble_flux (an older file?): "
                           f"use snapshots['pebble_flux'] [g s^-1]")
        return self.timeseries["time"], self.timeseries["pebble_flux"][:, i]

    def budget(self, term):
        """(time [yr], mass [M_earth]) of one mass-budget column on the /timeseries
        samples: "m_dust" (on the grid), "m_pl_coag", "m_pl_si", "m_out_inner" (through
        r_in), "m_sublimated", or "error" (|sum - initial|); run.budget_columns lists
        them."""
        names = self._budget_names()
        if term not in names:
            raise KeyError(f"{term!r} is not a budget column of {self.path}; columns: "
                           f"{names}")
        return self.timeseries["time"], self.timeseries["mass_budget"][:, names.index(term)]

    def _budget_names(self):
        """The /timeseries/mass_budget column names ([] without the dataset): the
        attribute's, or the six of a file written before it."""
        if "mass_budget" not in self.timeseries:
            return []
        if self.budget_columns:
            return self.budget_columns
        default = [*BUILT_IN_BUDGET_TERMS, "error"]
        return default if self.timeseries["mass_budget"].shape[1] == 6 else []

    def _monitor(self, monitor):
        """Index of a pebble-flux monitor by name or radius [au]."""
        if isinstance(monitor, str):
            if monitor not in self.pebble_names:
                raise KeyError(f"no pebble-flux monitor {monitor!r} in {self.path}; "
                               f"monitors: {self.pebble_names}")
            return self.pebble_names.index(monitor)
        r = np.asarray(self.monitor_r_au)
        if r.size == 0:
            raise KeyError(f"{self.path} has no pebble-flux monitors")
        return int(np.argmin(np.abs(np.log(r / float(monitor)))))

    def dust_mass(self):
        """Total dust mass on the grid per snapshot, sum(sigma_d * area) [g], (nt,)."""
        return self.snapshots["sigma_d"] @ self.area

    def at_time(self, name, t_yr):
        """(profile, time [yr]) of snapshot field `name` at the snapshot nearest t_yr
        (warned when t_yr lies outside the snapshots' span, or the nearest snapshot is
        more than 10 % away from it: compare the time returned)."""
        if name not in self.snapshots:
            self.field(f"snapshots/{name}")  # raises with the reason
        i = int(np.argmin(np.abs(self.time - t_yr)))
        t = float(self.time[i])
        if t_yr < self.time[0] or t_yr > self.time[-1] or abs(t - t_yr) > 0.1 * abs(t_yr):
            warnings.warn(f"{self.path}: no snapshot near t = {t_yr:g} yr; the nearest is at "
                          f"{t:g} yr (snapshots span {self.time[0]:g}-{self.time[-1]:g} yr)",
                          stacklevel=2)
        return self.snapshots[name][i], t


def load_run(path):
    """Read the run file at `path` (read-only) and return a Run.

    Snapshot datasets are cut to the smallest first dimension among them, so a file
    whose writer was killed between two dataset appends still loads consistently;
    /timeseries likewise (its writer appends `time` last, so the rows kept are those
    that have a time). Missing /timeseries, /pebbles or /summary give empty dicts.
    """
    with open_output(path) as f:
        _refuse_other_files(f, path)
        units, descriptions = {}, {}
        for group in f:  # group by group: an unreadable object costs its group's units
            try:
                f[group].visititems(lambda name, obj, g=group: _collect_units(
                    units, descriptions, f"{g}/{name}", obj))
            except (KeyError, OSError, RuntimeError):
                pass  # named by _read_group
        grid = _read_group(f, "grid")
        disk = _read_group(f, "disk")
        r_snow_au = float(f["disk"].attrs.get("r_snow_au", np.nan)) if "disk" in f else np.nan
        snapshots = _truncate_to_common_length(_read_group(f, "snapshots"), path)
        timeseries = _read_timeseries(f, path)
        pebbles = _read_group(f, "pebbles")
        pebble_names = _monitor_names(f, pebbles.get("r_au"), path)
        summary = {name: (float(a.ravel()[0]) if a.ndim <= 1 and a.size == 1
                          and a.dtype.kind in "fiu" else a)
                   for name, a in _read_group(f, "summary").items()}
        attrs = {k: _to_str(v) for k, v in f.attrs.items()}
        solver = {k: _to_python(v) for k, v in f["solver"].attrs.items()} if "solver" in f else {}
        budget_terms = _name_list(f, "snapshots", "budget_terms")
        budget_columns = _name_list(f, "timeseries", "mass_budget_columns")
    return Run(path, grid, disk, r_snow_au, snapshots, units, attrs, solver,
               budget_terms=budget_terms, budget_columns=budget_columns,
               timeseries=timeseries, pebbles=pebbles, pebble_names=pebble_names,
               summary=summary, descriptions=descriptions)


def _refuse_other_files(f, path):
    """ValueError naming what `path` is when it is a panoptic file but not a run's output:
    a checkpoint, a scan summary, an observe output."""
    if "format" in f.attrs and _to_str(f.attrs["format"]).startswith("panoptic checkpoint"):
        out = _to_str(f.attrs.get("output_file", ""))
        raise ValueError(f"{path} is a checkpoint, not a run's output; load the run's "
                         f"output {out or '(the .h5 next to it)'}")
    if "snapshots" not in f:
        if "runs" in f and "outcome" in f:
            raise ValueError(f"{path} is a scan summary; read it with "
                             f"postprocess.plot_scan.load_summary")
        if "image" in f or "spectral_index" in f or "flux" in f:
            raise ValueError(f"{path} is an observe output; plot it with "
                             f"postprocess.plot_observe")
        raise ValueError(f"{path} is not a panoptic run file (no /snapshots)")


_PROCESS_OF = {
    "m": "growth", "phi": "porosity", "a": "growth", "rho_int": "growth", "dv": "growth",
    "t_grow": "growth", "dv_ls": "erosion", "sigma_pl": "a planetesimal channel",
    "sigma_pl_coag": "planetesimals.coagulation", "sigma_pl_si": "planetesimals.si",
    "t_first_pl": "a planetesimal channel", "m_pl_coag": "a planetesimal channel",
    "m_pl_si": "a planetesimal channel", "m_out_gas": "gas.evolve",
    "m_peb_snowline": "a snow line on the grid"}


def _process_hint(key):
    """" (written only with <process> on)" for a dataset a process owns, else ""."""
    return f" (written only with {_PROCESS_OF[key]} on)" if key in _PROCESS_OF else ""


def _name_list(f, group, attr):
    """The ";"-separated names of attribute `attr` of `group` ([] when absent)."""
    if group not in f or attr not in f[group].attrs:
        return []
    raw = _to_str(f[group].attrs[attr])
    return [s for s in raw.split(";") if s]


# How often HDF5 re-reads a metadata entry whose checksum fails, in SWMR reading, before
# it gives up: its default, 100, with a back-off that doubles at each attempt, waits
# for ever on an entry a SIGKILL tore (src/io/h5.hpp, kSwmrReadAttempts).
SWMR_READ_ATTEMPTS = 24


def _open_swmr_read(path):
    """h5py.File(path, 'r', swmr=True), with SWMR_READ_ATTEMPTS set through the HDF5
    library h5py uses (h5py does not expose it); without them where that library cannot
    be reached by name."""
    import ctypes
    fapl = h5py.h5p.create(h5py.h5p.FILE_ACCESS)
    for name in ("libhdf5_serial.so.103", "libhdf5.so.103", "libhdf5_serial.so",
                 "libhdf5.so"):
        try:
            fn = ctypes.CDLL(name).H5Pset_metadata_read_attempts
        except (OSError, AttributeError):
            continue
        fn.argtypes, fn.restype = [ctypes.c_int64, ctypes.c_uint], ctypes.c_int
        if fn(fapl.id, SWMR_READ_ATTEMPTS) >= 0:  # not h5py's library if this fails
            fid = h5py.h5f.open(os.fsencode(path),
                                h5py.h5f.ACC_RDONLY | h5py.h5f.ACC_SWMR_READ, fapl=fapl)
            return h5py.File(fid)
    return h5py.File(path, "r", swmr=True)


def open_output(path):
    """A run's output, read-only: h5py.File(path, 'r'); for a run's output whose writer still runs or was killed
    (panoptic writes its output in HDF5's SWMR mode, and HDF5 refuses a plain open of
    such a file), the file opened for SWMR reading: every row flushed before, consistent."""
    if os.path.isdir(path):
        raise IsADirectoryError(f"{path} is a directory; give a run's .h5 file (a scan's "
                                f"runs are in {os.path.join(str(path), 'runs')})")
    try:
        return h5py.File(path, "r")
    except OSError as err:
        if "consistency flags" not in str(err):
            raise
        try:
            return _open_swmr_read(path)
        except OSError:
            raise OSError(f"{path}: the writer did not close the file; run "
                          f"`h5clear -s {path}` (on a copy, if you prefer) and retry") from err


def _collect_units(units, descriptions, name, obj):
    """visititems callback: record the `units` and `description` of every dataset."""
    if isinstance(obj, h5py.Dataset):
        units[name] = _to_str(obj.attrs.get("units", ""))
        descriptions[name] = _to_str(obj.attrs.get("description", ""))


def _read_group(f, group):
    """dict name -> array of the datasets directly inside `group` (empty if absent). A
    dataset HDF5 cannot read (its header torn by a SIGKILL in the middle of its write)
    is left out, with a warning."""
    if group not in f:
        return {}
    out = {}
    for name in f[group]:
        try:
            obj = f[group][name]
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
        except (KeyError, OSError, RuntimeError) as err:
            warnings.warn(f"{f.filename}: /{group}/{name} cannot be read ({err}): left out "
                          f"(torn by a kill? a restart of the run recreates it)",
                          stacklevel=3)
    return out


def _truncate_to_common_length(snapshots, path, group="snapshots", stacklevel=3):
    """Cut every array of `group` to the smallest first dimension among them."""
    lengths = {name: a.shape[0] for name, a in snapshots.items() if a.ndim >= 1}
    if "time" not in lengths:
        raise KeyError(f"{path}: /{group}/time is missing")
    nt = min(lengths.values())
    short = sorted(name for name, n in lengths.items() if n > nt)
    if short:
        kind = "snapshot" if group == "snapshots" else f"/{group}"
        warnings.warn(f"{path}: {kind} datasets have unequal lengths (killed run?); "
                      f"using the first {nt} rows of {', '.join(short)}",
                      stacklevel=stacklevel)
    return {name: (a[:nt] if name in lengths else a) for name, a in snapshots.items()}


def _read_timeseries(f, path):
    """/timeseries cut to a common length, without rows that do not rise in time; {} (with
    a warning) if it has no time."""
    series = _read_group(f, "timeseries")
    if not series:
        return {}
    if "time" not in series:
        warnings.warn(f"{path}: /timeseries has no time dataset; ignored", stacklevel=3)
        return {}
    series = _truncate_to_common_length(series, path, group="timeseries", stacklevel=4)
    return _cut_to_rising_time(series, path)


def _cut_to_rising_time(series, path):
    """The rows of /timeseries whose time is above 0 and at least every time before it.
    The writer samples at rising times, one row per solver step at most; a run killed
    while a restart cut the file can leave rows read back as zeros (HDF5's fill value),
    which are not samples and are dropped (warned); the rows after them are kept."""
    t = series["time"]
    before = np.concatenate([[-np.inf], np.maximum.accumulate(t)[:-1]])
    keep = (t > 0.0) & (t >= before)
    if keep.all():
        return series
    warnings.warn(f"{path}: {int((~keep).sum())} /timeseries rows do not rise in time (left "
                  f"by a run killed while a restart cut the file?); dropped", stacklevel=4)
    return {name: a[keep] for name, a in series.items()}


def _monitor_names(f, r_au, path):
    """Names of the pebble-flux monitors: the `names` attribute of /pebbles (or of
    /pebbles/r_au), split at ";"; "<r> au" for each radius when absent or mismatched."""
    if r_au is None:
        return []
    raw = None
    for obj in (f["pebbles"], f["pebbles"].get("r_au")):
        if obj is not None and "names" in obj.attrs:
            raw = _to_str(obj.attrs["names"])
            break
    names = [n.strip() for n in raw.split(";")] if raw else []
    if len(names) != len(r_au):
        if raw is not None:
            warnings.warn(f"{path}: /pebbles names {raw!r} do not match the "
                          f"{len(r_au)} radii; using the radii", stacklevel=3)
        names = [f"{r:.3g} au" for r in r_au]
    return names


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
