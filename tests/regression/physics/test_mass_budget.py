"""The dust mass budget (spec §6.3, §7): mass on the grid + planetesimals + mass that left
through r_in + ice sublimated at the snow line equals the initial mass to 1e-12 relative at every snapshot of
a whole run: every scene in params/ (growth, erosion, fragmentation), transport alone, with
the gas evolving, and at a loose tolerance (the budget is exact in the discretisation, not
a consequence of accuracy)."""
import glob
import os

import numpy as np

from common import REPO, Checks, budget_error, load_run, parse_args, run

# every scene in params/ as it is, found by glob so that a new scene is checked too
# (issue: the budget closes in every scene); reference.toml is every key at its default
CASES = [(os.path.splitext(os.path.basename(p))[0], os.path.relpath(p, REPO), [])
         for p in sorted(glob.glob(os.path.join(REPO, "params", "*.toml")))]


def check_budgets(cases, args, c):
    """Runs every (label, scene, overrides) and checks its budget at every snapshot."""
    for k, (label, scene, sets) in enumerate(cases):
        out = f"{args.workdir}/budget_{k}.h5"
        run(args.exe, scene, out, sets)
        r = load_run(out)
        c.check(r.budget_terms[:1] == ["m_dust"] and "m_out_inner" in r.budget_terms
                and "m_sublimated" in r.budget_terms,
                f"{label}: /snapshots names its budget terms ({r.budget_terms})")
        err = budget_error(r.snapshots, r.budget_terms)
        m0 = r.snapshots["m_dust"][0]  # the initial dust, all on the grid
        left = r.snapshots["m_out_inner"][-1] / m0
        grid_mass = np.sum(r.snapshots["sigma_d"] * r.area, axis=1)
        consistent = np.max(np.abs(grid_mass / r.snapshots["m_dust"] - 1))
        sub = r.snapshots["m_sublimated"][-1] / m0
        print(f"{label}: {r.n_snapshots} snapshots, {left:.3f} of the dust left through r_in, "
              f"{sub:.3f} sublimated, max budget error {err:.1e}")
        c.check(err < 1e-12, f"{label}: budget closes to 1e-12 ({err:.1e})")
        c.check(consistent < 1e-12, f"{label}: m_dust equals the sum of sigma_d * area")
        c.check(np.all(r.snapshots["sigma_d"] >= 0), f"{label}: no negative Sigma_d")
        ts = r.timeseries["time"]
        c.check(np.all(np.diff(ts) > 0) and ts[-1] == r.time[-1] and
                np.isin(r.time[1:], ts).all(),
                f"{label}: /timeseries/time rises strictly ({len(ts)} rows), with a row at "
                f"every snapshot and the last at t_end")


def main():
    args = parse_args()
    c = Checks()
    c.check(len(CASES) >= 6, f"{len(CASES)} scenes found in params/")
    check_budgets(CASES, args, c)
    c.finish()


if __name__ == "__main__":
    main()
