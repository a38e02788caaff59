"""Postprocessing for panoptic run files (one HDF5 file per run).

Modules:
    reader    -- ``load_run(path) -> Run``: read a run file into numpy arrays.
    analytic  -- closed-form solutions used by the regression tests.
    plot      -- ``python3 -m postprocess.plot RUN.h5``: Sigma_d and dust-to-gas profiles.
    plot_run  -- ``python3 -m postprocess.plot_run RUN.h5``: every figure of a run (the
                 above, r-t maps, pebble flux, planetesimals, mass budget).
    plot_scan -- ``python3 -m postprocess.plot_scan DIR``: maps and lines of a scan's
                 outcomes (summary.h5); ``load_summary(DIR)``.
    plot_observe -- ``python3 -m postprocess.plot_observe OBS.h5``: images and profiles
                 of a ``panoptic observe`` output.
    test_postprocess -- self-test, ``python3 -m postprocess.test_postprocess``.
"""
