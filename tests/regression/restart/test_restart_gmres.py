"""solver.linear = "gmres" (src/solver/cell_block_preconditioner.hpp; issue 35 item 5) on
params/tests/distribution_small.toml (12 cells, 50 bins): the run header names the solver
and the run reports its linear iterations; a restart from the mid-run checkpoint writes
/snapshots, /timeseries and /summary identical in every bit, with the same solver
statistics; and the final sigma(r, m) matches that of the same run with KLU to the
solver's tolerance: |sigma_gmres - sigma_klu| / (rtol |sigma_klu| + atol) below 1 in every
bin (CVODE's weights; atol = solver.atol_sigma times the largest initial Sigma_d, the
bins' scale). GMRES solves each Newton system only to a fraction of the tolerance, so
the two runs differ by a fraction of the tolerance, not by round-off."""
import numpy as np

from common import Checks, parse_args
from postprocess.reader import open_output
from restart_common import panoptic, restarted_from_prev, solver_attrs

SCENE = "params/tests/distribution_small.toml"
GROUPS = ("snapshots", "timeseries", "summary")
GMRES = ['solver.linear="gmres"']
RTOL, ATOL_SIGMA = 1e-6, 1e-8  # the scene's solver.rtol and solver.atol_sigma (defaults)


def final_sigma(path):
    with open_output(path) as f:
        return f["snapshots/sigma"][-1], f["snapshots/sigma_d"][0].max()


def main():
    args = parse_args()
    c = Checks()
    klu = f"{args.workdir}/klu.h5"
    gmres = f"{args.workdir}/gmres.h5"
    p_klu = panoptic(args.exe, SCENE, "-o", klu, "--overwrite", sets=['solver.linear="klu"'])
    p = panoptic(args.exe, SCENE, "-o", gmres, "--overwrite", sets=GMRES)
    c.check("Newton systems solved by gmres (solver.linear)" in p.stdout
            and "Newton systems solved by klu (solver.linear)" in p_klu.stdout,
            "the run header names the solver")
    c.check("GMRES:" in p.stdout and "GMRES:" not in p_klu.stdout,
            "the GMRES run reports its linear iterations")
    s_klu, scale = final_sigma(klu)
    s_gmres, _ = final_sigma(gmres)
    worst = np.max(np.abs(s_gmres - s_klu) / (RTOL * np.abs(s_klu) + ATOL_SIGMA * scale))
    c.check(worst < 1.0, f"final sigma of GMRES against KLU: largest weighted "
            f"difference {worst:.3g} (< 1)")
    full, again, k = restarted_from_prev(c, args.exe, args.workdir, SCENE,
                                         [*GMRES, "checkpoint.every_snapshots=2"],
                                         "gmres_restart", "GMRES run", GROUPS)
    s, r = solver_attrs(again), solver_attrs(full)
    keys = ("nst", "nfe", "nje", "nni", "nreinit")
    c.check(all(s[key] == r[key] for key in keys) and s["nje"] > 0,
            "the same solver statistics (" + ", ".join(f"{key} {s[key]}" for key in keys)
            + ")")
    c.finish()


if __name__ == "__main__":
    main()
