"""Round-off scatter of the work-precision errors (issue 7): how far the error of one
setting (N, grid stretch, rtol) moves under changes that are nothing but round-off. Run on
demand, not in CI.

CVODE's step-size and order choices react to differences at the last bit, and the
switch-like outcomes (the outer edge of the planetesimal zone is a cell centre; the
planetesimal mass of an erosion scene follows a threshold) amplify them. One run per
setting, as in work_precision.py, is then one draw. This script runs each rtol of one grid
K times with rtol scaled by 1 + k * 1e-3 (k = -(K-1)/2 .. (K-1)/2: tolerances that no
user would tell apart) and reports, per rtol and outcome, the median and the largest error
against the reference of the work-precision study, and the steps. Where median and
largest differ by a factor, a single run's error at that rtol is noise.

    /usr/bin/python3 tests/bench/roundoff_scatter.py --exe build/panoptic --workdir DIR \
        --ref DIR_WP/fiducial_N4096_rtol1e-10.h5 [--scene fiducial] [--n-cells 350] \
        [--stretch 0.5] [--rtol 1e-2 1e-3 1e-4 1e-5 1e-6] [--draws 5] [--jobs 2]
        [--set KEY=VALUE ...]

writes DIR/roundoff_scatter_<scene>_N<n>.md (the table, with the median wall time of
each rtol) and .json (every run)."""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, REPO)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from postprocess.reader import load_run  # noqa: E402
import work_precision as wp  # noqa: E402

import numpy as np  # noqa: E402


def run(exe, workdir, scene, n, stretch, rtol, extra=()):
    """One run; returns (steps, outcomes) or raises with the run's last error line.
    `extra`: further scene settings, key=value (--set)."""
    tag = "".join("_" + kv.split(".")[-1].replace("=", "") for kv in extra)
    out = os.path.join(workdir, f"{scene}_N{n}_s{stretch:g}{tag}_rtol{rtol!r}.h5")
    cmd = [exe, "run", os.path.join(REPO, "params", scene + ".toml"), "-o", out,
           "--overwrite", "--set", f"grid.n_cells={n}", "--set", f"grid.stretch={stretch:g}",
           "--set", f"solver.rtol={rtol!r}", "--set", "checkpoint.every_wall_s=0",
           "--set", "solver.max_steps=2000000"]
    for kv in extra:
        cmd += ["--set", kv]
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        return {"rtol": rtol, "error": wp.error_line(p.stderr)}
    r = load_run(out)
    return {"rtol": rtol, "steps": int(r.solver["nst"]), "wall_s": float(r.solver["wall_s"]),
            "outcomes": wp.outcomes(r)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--ref", required=True, help="reference output (.h5) of the same scene")
    ap.add_argument("--scene", default="fiducial")
    ap.add_argument("--n-cells", type=int, default=350)
    ap.add_argument("--stretch", type=float, default=0.5)
    ap.add_argument("--rtol", nargs="+", type=float, default=[1e-2, 1e-3, 1e-4, 1e-5, 1e-6])
    ap.add_argument("--draws", type=int, default=5)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a further scene setting for every run (repeatable)")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    exe = os.path.abspath(args.exe)
    sha = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip()
    ref = wp.outcomes(load_run(args.ref))
    half = (args.draws - 1) / 2.0
    todo = [(rt, rt * (1.0 + (k - half) * 1e-3)) for rt in args.rtol
            for k in range(args.draws)]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        done = list(pool.map(lambda t: (t[0], run(exe, args.workdir, args.scene,
                                                  args.n_cells, args.stretch, t[1],
                                                  args.set)), todo))
    names = wp.OUTCOMES + ["max"]
    rows, records = [], []
    for rt in args.rtol:
        recs = [r for base, r in done if base == rt]
        ok = [r for r in recs if "outcomes" in r]
        errs = [wp.errors(r["outcomes"], ref) for r in ok]
        for r, e in zip(ok, errs):
            records.append({"rtol": r["rtol"], "steps": r["steps"], "wall_s": r["wall_s"],
                            "err": e})
        for r in recs:
            if "error" in r:
                records.append(r)
        cells = []
        for name in names:
            v = np.array([e[name] for e in errs])
            cells.append(f"{np.median(v):.1e} / {v.max():.1e}" if len(v) else "-")
        steps = [r["steps"] for r in ok]
        wall = f"{np.median([r['wall_s'] for r in ok]):.2f}" if ok else "-"
        rows.append(f"| {rt:g} | {len(ok)}/{len(recs)} | "
                    + (f"{min(steps)}–{max(steps)}" if steps else "-") + f" | {wall} | "
                    + " | ".join(cells) + " |")
    sets = "".join(f", {kv}" for kv in args.set)
    head = (f"{args.scene}, N = {args.n_cells}, stretch {args.stretch:g}{sets}; {args.draws} draws "
            f"per rtol (rtol x (1 + k 1e-3)); {sha}\n\nError against the reference, "
            "median / largest over the draws:\n\n"
            "| rtol | finished | steps | wall [s], median | " + " | ".join(names) + " |\n|"
            + "---|" * (4 + len(names)) + "\n")
    text = head + "\n".join(rows) + "\n"
    tag = "".join("_" + kv.split(".")[-1].replace("=", "") for kv in args.set)
    base = os.path.join(args.workdir, f"roundoff_scatter_{args.scene}_N{args.n_cells}{tag}")
    with open(base + ".md", "w") as f:
        f.write(text)
    with open(base + ".json", "w") as f:
        json.dump(records, f, indent=1)
    print(text)


if __name__ == "__main__":
    main()
