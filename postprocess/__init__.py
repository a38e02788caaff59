"""panoptic's Python side: read, plot, scan and launch panoptic runs.

Installed (``pip install --no-build-isolation ./postprocess``) it is ``import panoptic``;
in the repository, from its root, the same modules are ``import postprocess``.

    run = panoptic.load_run("out/fiducial.h5")        # a Run: arrays + accessors
    t, m_pl = run.planetesimal_mass()                  # (t [yr], [M_earth])
    df = panoptic.load_scan("out/scan")                # one row per run (pandas)
    run = panoptic.run("params/fiducial.toml", set={"disk.alpha": 1e-3}, out="a.h5")
    panoptic.overlay_profiles([run_a, run_b], "sigma_d", t_yr=1e5)
    profiles, outcomes = panoptic.compare_runs("single.h5", "distribution.h5")

Modules:
    reader    -- load_run(path) -> Run, open_output(path) (a killed run's file too)
    scan      -- load_scan(DIR) -> pandas.DataFrame; load_summary(DIR) (dict)
    launch    -- run(scene, set=..., out=..., exe=...) -> Run (the panoptic executable)
    observation -- load_observation(OBS.h5) -> Observation
    overlay   -- figures of several runs: profiles at a time, outcomes vs time
    model_error -- compare_runs(run, reference) -> (profiles, outcomes) DataFrames: a
                 run of a scene against a reference run of it (single size against
                 size distribution), cell by cell; panoptic-model-error
    style     -- figure sizes (column widths), save with or without the footer
    analytic  -- closed-form solutions used by the regression tests
    plot, plot_run, plot_scan, plot_observe, plot_distribution -- the figures and their
                 command lines (panoptic-plot-profiles, panoptic-plot, panoptic-plot-scan,
                 panoptic-plot-observe, panoptic-plot-distribution; python3 -m postprocess.plot_run from the repository)
"""
import sys

if sys.version_info < (3, 11):
    raise ImportError(f"panoptic needs Python >= 3.11 (tomllib reads a run's scene); this "
                      f"is {sys.version.split()[0]} ({sys.executable})")

# Names resolved on first use (PEP 562), so that `import postprocess.analytic` in a test
# does not pull in matplotlib and pandas.
_EXPORTS = {"Run": "reader", "load_run": "reader", "open_output": "reader",
            "load_scan": "scan", "load_summary": "scan",
            "run": "launch", "PanopticError": "launch", "find_executable": "launch",
            "Observation": "observation", "load_observation": "observation",
            "overlay_profiles": "overlay", "overlay_series": "overlay",
            "compare_runs": "model_error"}
__version__ = "0.1.0"
__all__ = [*_EXPORTS, "__version__"]


_SUBMODULES = ("reader", "scan", "launch", "observation", "overlay", "style", "plot",
               "plot_run", "plot_scan", "plot_observe", "plot_distribution", "analytic",
               "xarray_view", "model_error")


def __getattr__(name):
    import importlib
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    if name not in _EXPORTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted([*globals(), *_EXPORTS, *_SUBMODULES])
