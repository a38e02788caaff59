"""Read a panoptic run file (HDF5) into numpy arrays.

Layout (written by the C++ code):
    /                attrs config_toml, git_sha, version, scene, label, overrides (str)
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

The accessors return (t, value) (time first) in the unit their docstring states:
masses in M_earth, mass flows in M_earth Myr^-1, times in yr, radii in au (a /snapshots
mass in g is converted). The raw arrays (run.snapshots, run.field) stay in the units of
the file (each dataset's `units` attribute; run.unit() gives it): /snapshots in cgs with
times in yr and radii in au, /timeseries and /summary in M_earth, Myr and au. The same
short name can live in two groups in different units (snapshots/m_pl_coag [g],
summary/m_pl_coag [M_earth]): field() then takes /snapshots and warns; give the path, or
use series(), which states its unit.

Usage:
    run = load_run("out/run.h5")
    t, profile = run.at_time("sigma_d", 1e5)  # nearest snapshot: [yr], (N,) [g cm^-2]
    t, m_pl = run.planetesimal_mass()       # (ns,) [yr], [M_earth] (all channels)
    t, m = run.series("m_pl_coag")          # (ns,) [yr], [M_earth] (g converted)
    t, flux = run.pebble_flux("snow line")  # (ns,) [yr], [M_earth Myr^-1]; or a monitor
                                            # radius [au]; any other radius raises
    t, flux = run.mass_flow(5.0)            # (nt,) [yr], [M_earth Myr^-1] at 5 au
    t, m = run.budget("m_out_inner")        # (ns,) [yr], [M_earth]
    run.field("sigma_d"), run.unit("sigma_d")   # (nt, N) raw array, "g cm^-2"
    run.dust_mass()                         # (nt,) [g] (the snapshots' sum)
    run.to_xarray()                         # xarray.Dataset, dims t and r (if installed)
"""
import json
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

# Conversions of a /snapshots unit to the unit of the accessors (series, mass_flow)
TO_ACCESSOR_UNIT = {"g": (M_EARTH, "M_earth"), "g s^-1": (M_EARTH / MYR, "M_earth Myr^-1")}

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
        attrs       root attributes as str (config_toml, git_sha, version, scene, label,
                    overrides)
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

    def __repr__(self):
        state = "finished" if self.finished else "unfinished"
        span = f"{self.time[0]:g}-{self.time[-1]:g} yr" if len(self.time) else "no snapshots"
        return (f"<panoptic Run {self.path!r}: {self.scene or 'run'}, {len(self.r_c)} cells, "
                f"{self.n_snapshots} snapshots ({span}), {state}>")

    @property
    def scene(self):
        """The run's label: its scene's name with the overrides it ran with (root
        attribute `label`, "fiducial+disk.sigma_1au=5100": src/run/README.md, Variants),
        else the scene name (root attribute `scene`), "" if absent."""
        return self.attrs.get("label") or self.attrs.get("scene", "")

    @property
    def overrides(self):
        """The overrides the run applied on top of its scene file, in order (root
        attribute `overrides`, a JSON list: a preset's items, then the --set items), []
        if absent."""
        text = self.attrs.get("overrides", "")
        try:
            return list(json.loads(text)) if text else []
        except ValueError:
            return []

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
                                  f"the path to choose (run.series({key!r}) states its "
                                  f"unit)", stacklevel=2)
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
        """(time [yr], inward pebble flux [M_earth Myr^-1]) through one monitor on the
        /timeseries samples. `monitor`: its name ("snow line", "r_in", "3 au":
        run.pebble_names) or its radius [au] (run.monitor_r_au, the face it sits on, or
        the radius its name gives: 3.0 for "3 au"). Any other radius raises KeyError
        naming the monitors; run.mass_flow(r) gives the flow at any radius from the
        snapshots."""
        i = self._monitor(monitor)
        if "pebble_flux" not in self.timeseries:
            raise KeyError(f"{self.path} has no /timeseries/pebble_flux (an older file?): "
                           f"use snapshots['pebble_flux'] [g s^-1]")
        return self.timeseries["time"], self.timeseries["pebble_flux"][:, i]

    def mass_flow(self, r_au):
        """(snapshot times [yr], inward dust mass flow [M_earth Myr^-1]) at radius r_au
        [au], interpolated linearly in log r between the two cell faces around it from
        /snapshots/mdot_d (positive outward in the file; the sign is flipped here). On
        the snapshots, coarser than pebble_flux's /timeseries at a monitor."""
        if "mdot_d" not in self.snapshots:
            raise KeyError(f"{self.path} has no /snapshots/mdot_d (an older file?)")
        r = float(r_au)
        if not self.r_f[0] <= r <= self.r_f[-1]:
            raise ValueError(f"r = {r:g} au is outside the grid ({self.r_f[0]:g}-"
                             f"{self.r_f[-1]:g} au)")
        log_rf = np.log(self.r_f)
        j = int(np.clip(np.searchsorted(log_rf, np.log(r)) - 1, 0, len(log_rf) - 2))
        w = (np.log(r) - log_rf[j]) / (log_rf[j + 1] - log_rf[j])
        mdot = self.snapshots["mdot_d"]
        inward = -((1.0 - w) * mdot[:, j] + w * mdot[:, j + 1])
        return self.time, inward / (M_EARTH / MYR)

    def series(self, name):
        """(time [yr], value) of a scalar-per-time quantity, in the accessors' units:
        a mass-budget column ("m_dust", "m_pl_coag", "m_pl_si", "m_out_inner",
        "m_sublimated", "error") [M_earth] on the /timeseries samples when the file has
        them; else the /snapshots dataset of that name on the snapshots, a mass [g]
        converted to M_earth and a flow [g s^-1] to M_earth Myr^-1 (other units as in
        the file: run.series_unit(name))."""
        if name in self._budget_names():
            return self.budget(name)
        if name not in self.snapshots or name == "time":
            raise KeyError(f"{name!r} is not a budget column or /snapshots dataset of "
                           f"{self.path}{_process_hint(name)}; budget columns: "
                           f"{self._budget_names()}, snapshots: {sorted(self.snapshots)}")
        factor, _ = TO_ACCESSOR_UNIT.get(self.units.get(f"snapshots/{name}", ""), (1.0, ""))
        return self.time, self.snapshots[name] / factor

    def series_unit(self, name):
        """The unit of run.series(name)'s values."""
        if name in self._budget_names():
            return "M_earth"
        unit = self.unit(f"snapshots/{name}")
        return TO_ACCESSOR_UNIT.get(unit, (1.0, unit))[1]

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
        """Index of a pebble-flux monitor by name or radius [au] (its face's radius or the
        radius its name says, to 1e-6); KeyError naming the monitors otherwise."""
        if isinstance(monitor, str):
            if monitor not in self.pebble_names:
                raise KeyError(f"no pebble-flux monitor {monitor!r} in {self.path}; "
                               f"monitors: {self._monitor_list()}")
            return self.pebble_names.index(monitor)
        r = np.asarray(self.monitor_r_au, dtype=float)
        if r.size == 0:
            raise KeyError(f"{self.path} has no pebble-flux monitors")
        want = float(monitor)
        for i, (name, r_face) in enumerate(zip(self.pebble_names, r)):
            nominal = _radius_in_name(name)
            if any(x is not None and abs(x - want) <= 1e-6 * abs(want)
                   for x in (float(r_face), nominal)):
                return i
        raise KeyError(f"r = {want:g} au is not a pebble-flux monitor of {self.path}; "
                       f"monitors: {self._monitor_list()}. run.mass_flow({want:g}) gives "
                       f"the flow there on the snapshots, or add the radius to "
                       f"pebbles.radii_au and run again")

    def _monitor_list(self):
        """'snow line (2.73 au), 3 au (2.98 au), ...' of the monitors."""
        return ", ".join(f"{n} ({r:.4g} au)" for n, r in zip(self.pebble_names,
                                                            self.monitor_r_au))

    def dust_mass(self):
        """Total dust mass on the grid per snapshot, sum(sigma_d * area) [g], (nt,)."""
        return self.snapshots["sigma_d"] @ self.area

    def at_time(self, name, t_yr):
        """(time [yr], profile) of snapshot field `name` (in its /snapshots unit,
        run.unit(name)) at the snapshot nearest t_yr (warned when t_yr lies outside the
        snapshots' span, or the nearest snapshot is more than 10 % away from it: compare
        the time returned)."""
        if name not in self.snapshots:
            self.field(f"snapshots/{name}")  # raises with the reason
        i = int(np.argmin(np.abs(self.time - t_yr)))
        t = float(self.time[i])
        if t_yr < self.time[0] or t_yr > self.time[-1] or abs(t - t_yr) > 0.1 * abs(t_yr):
            warnings.warn(f"{self.path}: no snapshot near t = {t_yr:g} yr; the nearest is at "
                          f"{t:g} yr (snapshots span {self.time[0]:g}-{self.time[-1]:g} yr)",
                          stacklevel=2)
        return t, self.snapshots[name][i]

    @property
    def has_distribution(self):
        """True for a size-distribution run (model.kind = "distribution"): the file has
        /snapshots/sigma and the mass grid /grid/m_bins, a_bins."""
        return "sigma" in self.snapshots and "m_bins" in self.grid

    def size_distribution(self, t_yr):
        """(time [yr], sigma (N, n_bins) [g cm^-2]) of a size-distribution run at the
        snapshot nearest t_yr (as at_time): the dust surface density of each mass bin
        /grid/m_bins [g] (radii /grid/a_bins [cm]) in each cell; its sum over the bins is
        /snapshots/sigma_d. KeyError for a single-size run."""
        if not self.has_distribution:
            raise KeyError(f"{self.path} holds no size distribution (/snapshots/sigma, "
                           f"/grid/m_bins): a run with model.kind = \"distribution\" has")
        t, flat = self.at_time("sigma", t_yr)
        return t, np.asarray(flat).reshape(len(self.r_c), len(self.grid["m_bins"]))

    def to_xarray(self):
        """The snapshots as an xarray.Dataset: dims t [yr] and r [au] (cell centres) or
        r_f [au] (faces) or monitor, each variable with its `units` and `description`
        attributes; the /disk fields on r; /timeseries on t_series [yr]; the /summary
        scalars and root attributes as dataset attributes. ImportError if xarray is not
        installed (Debian: python3-xarray)."""
        from .xarray_view import run_to_xarray
        return run_to_xarray(self)


def as_run(run):
    """`run` itself when it is a Run, else the Run read from the path `run`."""
    return run if isinstance(run, Run) else load_run(os.fspath(run))


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
                             f"panoptic.load_scan(DIR) (postprocess.load_scan in the "
                             f"repository)")
        if "image" in f or "spectral_index" in f or "flux" in f:
            raise ValueError(f"{path} is an observe output; read it with "
                             f"panoptic.load_observation, plot it with panoptic-plot-observe")
        raise ValueError(f"{path} is not a panoptic run file (no /snapshots)")


_PROCESS_OF = {
    "m": "growth", "phi": "porosity", "a": "growth", "rho_int": "growth", "dv": "growth",
    "t_grow": "growth", "dv_ls": "erosion", "sigma_pl": "a planetesimal channel",
    "sigma_pl_coag": "planetesimals.coagulation", "sigma_pl_si": "planetesimals.si",
    "t_first_pl": "a planetesimal channel", "m_pl_coag": "a planetesimal channel",
    "m_pl_si": "a planetesimal channel", "m_out_gas": "gas.evolve",
    "m_peb_snowline": "a snow line on the grid",
    "top_bin_fraction": 'model.kind = "distribution"',
    "top_bin_fraction_max": 'model.kind = "distribution"'}


def _process_hint(key):
    """" (written only with <process> on)" for a dataset a process owns, else ""."""
    return f" (written only with {_PROCESS_OF[key]} on)" if key in _PROCESS_OF else ""


def _radius_in_name(name):
    """3.0 for a monitor named "3 au", None for "snow line" or "r_in"."""
    number, _, unit = name.strip().partition(" ")
    try:
        return float(number) if unit == "au" else None
    except ValueError:
        return None


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
    """A run's output, read-only: h5py.File(path, 'r'); for a run's output whose writer
    still runs or was killed (panoptic writes its output in HDF5's SWMR mode, and HDF5
    refuses a plain open of such a file, "file is already open for write"), the file
    opened for SWMR reading: every row flushed before, consistent. Where that fails too,
    OSError saying how to recover the file (`h5clear -s`)."""
    if os.path.isdir(path):
        raise IsADirectoryError(f"{path} is a directory; give a run's .h5 file (a scan's "
                                f"runs are in {os.path.join(str(path), 'runs')})")
    try:
        return h5py.File(path, "r")
    except OSError as err:
        if "unable to lock file" in str(err):
            raise OSError(f"{path} is open for writing (a panoptic run still going?): HDF5's "
                          f"file lock refuses a reader; set HDF5_USE_FILE_LOCKING=FALSE in "
                          f"the environment before h5py is imported to read it while it "
                          f"runs") from err
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
