"""`panoptic run --threads N` (src/core/worker_threads.hpp): the worker threads share the
size distribution's cells, and the results do not depend on their number.
params/tests/distribution_small.toml (12 cells, 50 bins), porous (GMRES with the cell-block
preconditioner, whose blocks the threads factorise) and compact (the block solver), on 1,
2 and 3 threads: /snapshots, /timeseries and /summary identical in every bit, with the
same solver statistics. `--threads 0` stops before anything is written, exit 2, with a
message naming the option, the value and the fix."""
import os

from common import Checks, parse_args
from restart_common import panoptic, snapshot_differences, solver_attrs

SCENE = "params/tests/distribution_small.toml"
GROUPS = ("snapshots", "timeseries", "summary")
KEYS = ("nst", "nfe", "nje", "nni", "nreinit")


def main():
    args = parse_args()
    c = Checks()
    for porous in ("true", "false"):
        # compact: the block solver, by name (GMRES is solver.linear = "auto"'s choice)
        sets = [f"porosity.enabled={porous}"] + ([] if porous == "true"
                                                 else ['solver.linear="block"'])
        out = {}
        for threads in (1, 2, 3):
            out[threads] = f"{args.workdir}/porous_{porous}_t{threads}.h5"
            panoptic(args.exe, SCENE, "-o", out[threads], "--overwrite", "--threads",
                     str(threads), sets=sets)
        ref = solver_attrs(out[1])
        for threads in (2, 3):
            diffs = snapshot_differences(out[1], out[threads], GROUPS)
            c.check(not diffs, f"porosity.enabled={porous}, {threads} threads against 1: "
                    f"identical /snapshots, /timeseries, /summary {diffs or ''}")
            s = solver_attrs(out[threads])
            c.check(all(s[k] == ref[k] for k in KEYS) and ref["nst"] > 0,
                    "the same solver statistics ("
                    + ", ".join(f"{k} {s[k]}" for k in KEYS) + ")")
    bad = f"{args.workdir}/zero_threads.h5"
    if os.path.exists(bad):
        os.remove(bad)
    p = panoptic(args.exe, SCENE, "-o", bad, "--threads", "0", expect=2)
    c.check("--threads 0" in p.stderr and "at least 1" in p.stderr
            and "--threads 1" in p.stderr,
            f"--threads 0 is refused by name, value and fix: {p.stderr.strip()!r}")
    c.check(not os.path.exists(bad), "nothing is written")
    c.finish()


if __name__ == "__main__":
    main()
