"""solver.method = "implicit_euler" (DustPy's step, src/solver/implicit_euler_integrator.hpp;
issue 35 item 5) on params/tests/distribution_small.toml (12 cells, 50 bins), compact and
porous: the run header names the scheme; a restart from the mid-run checkpoint writes
/snapshots, /timeseries and /summary identical in every bit, with the same solver
statistics (one right-hand side and one Jacobian per step); the dust budget closes to
round-off (the step conserves what the model conserves; no floor); and against the BDF
run (rtol 1e-6) at 3 000 yr: Sigma_d within 2e-3 in every cell that holds 1e-6 of the
largest (measured 1.0e-4 compact, 5.9e-5 porous), the bins holding >= 10 % of their
cell's Sigma_d within 0.2 (measured 0.036, 0.095: the first-order scheme's error at cfl
0.1; bins holding >= 1 % differ by up to 0.54, 0.58)."""
import numpy as np

from common import Checks, budget_error, load_run, parse_args
from restart_common import panoptic, restarted_from_prev, solver_attrs

SCENE = "params/tests/distribution_small.toml"
GROUPS = ("snapshots", "timeseries", "summary")
EULER = ['solver.method="implicit_euler"']


def main():
    args = parse_args()
    c = Checks()
    for porous in ("false", "true"):
        label = "porous" if porous == "true" else "compact"
        sets = [*EULER, f"porosity.enabled={porous}"]
        bdf = f"{args.workdir}/bdf_{label}.h5"
        panoptic(args.exe, SCENE, "-o", bdf, "--overwrite",
                 sets=[f"porosity.enabled={porous}"])
        full, again, k = restarted_from_prev(c, args.exe, args.workdir, SCENE,
                                             [*sets, "checkpoint.every_snapshots=2"],
                                             f"euler_{label}", f"implicit Euler {label}",
                                             GROUPS)
        s, r = solver_attrs(again), solver_attrs(full)
        keys = ("nst", "nfe", "nje", "nsetups", "nreinit")
        c.check(all(s[key] == r[key] for key in keys) and s["nst"] == s["nfe"] == s["nje"]
                and s["netf"] == 0,
                f"{label}: the same solver statistics, one RHS and Jacobian per step ("
                + ", ".join(f"{key} {s[key]}" for key in keys) + ")")
        run, ref = load_run(full), load_run(bdf)
        err = budget_error(run.snapshots, run.budget_terms)
        c.check(err < 1e-13, f"{label}: dust budget closes to {err:.2g} (< 1e-13)")
        sd, sd_ref = run.snapshots["sigma_d"][-1], ref.snapshots["sigma_d"][-1]
        held = sd_ref > 1e-6 * sd_ref.max()
        worst = float(np.max(np.abs(sd[held] / sd_ref[held] - 1.0)))
        c.check(worst < 2e-3, f"{label}: final Sigma_d within {worst:.2g} of BDF's "
                f"(< 2e-3) in {held.sum()} cells")
        n = len(sd_ref)
        sig = run.snapshots["sigma"][-1].reshape(n, -1)
        sig_ref = ref.snapshots["sigma"][-1].reshape(n, -1)
        big = sig_ref >= 0.1 * sd_ref[:, None]
        worst = float(np.max(np.abs(sig[big] / sig_ref[big] - 1.0)))
        c.check(worst < 0.2, f"{label}: the {big.sum()} bins holding >= 10 % of their "
                f"cell's Sigma_d within {worst:.2g} of BDF's (< 0.2)")
    p = panoptic(args.exe, SCENE, "-o", f"{args.workdir}/header.h5", "--overwrite",
                 sets=[*EULER, "output.t_end_yr=100"])
    c.check("linearly implicit Euler steps of cfl = 0.1" in p.stdout,
            "the run header names the scheme")
    c.finish()


if __name__ == "__main__":
    main()
