"""The mass budget of test_mass_budget.py for variants: evolving gas, transport alone with
a radially varying St (both to 1e-12), and loose tolerances, rtol = 1e-3 and (fiducial)
1e-2.

At rtol = 1e-3 CVODE accepts steps whose Sigma_d dips below zero by up to about its
absolute tolerance (solver.atol_sigma = 1e-8 of the largest initial Sigma_d). Sigma_d
carries no >= 0 constraint, so the restart of CVODE at every snapshot
(solver.reinit_at_snapshots) keeps those negatives and the budget stays exact to
round-off. With the constraint the restart clipped them to zero, adding that much dust:
8e-11 relative on this run at an earlier commit (atol_sigma = 1e-12, then the default);
with today's code and a restored constraint this run happens to close to 6e-15, and it
is test_lbp_viscous that fails (dust budget 2.7e-8 at N = 100). (It runs
compact_fragmentation: the fiducial scene at rtol = 1e-3 takes minutes.)
"""

from common import Checks, budget_error, load_run, parse_args, run
from test_mass_budget import check_budgets

VARIANTS = [
    ("compact_fragmentation, viscous gas, 1e5 yr", "params/compact_fragmentation.toml",
     ["gas.evolve=true", "output.t_end_yr=1e5"]),
    ("transport alone, St ∝ r^-1, 64 cells", "params/fiducial.toml",
     ["growth.enabled=false", "porosity.enabled=false", "planetesimals.coagulation=false",
      'planetesimals.si="none"', "transport.St=0.03", "transport.St_slope=-1",
      "grid.n_cells=64"]),
]


def check_loose(args, c, label, scene, sets, name):
    """Runs `scene` with `sets` (a loose tolerance) and checks its budget to 1e-12 at every
    snapshot."""
    out = f"{args.workdir}/{name}.h5"
    run(args.exe, scene, out, sets)
    r = load_run(out)
    err = budget_error(r.snapshots, r.budget_terms)
    print(f"{label}: max budget error {err:.1e}")
    c.check(err < 1e-12, f"{label}: budget closes to 1e-12 ({err:.1e})")


def main():
    args = parse_args()
    c = Checks()
    check_budgets(VARIANTS, args, c)
    check_loose(args, c, "compact_fragmentation, rtol 1e-3",
                "params/compact_fragmentation.toml",
                ["solver.rtol=1e-3"], "loose")
    # Sigma_pl is out of CVODE's error test; were it still constrained to be >= 0, CVODE
    # would clip its negative excursions to zero at any size and lose that mass: 2.4e-8
    # on fiducial at rtol 1e-2 (2d99b3b), where Newton iterates of drained cells go
    # slightly negative.
    check_loose(args, c, "fiducial, rtol 1e-2", "params/fiducial.toml",
                ["solver.rtol=1e-2"], "loose_fiducial")
    c.finish()


if __name__ == "__main__":
    main()
