"""Where the CVODE steps of the fiducial scene go, and how many a scheme that stepped every
cell on its own would need (issues 3 and 7: why the run takes ~9 000 steps). Run on
demand, not in CI; uses build/tests/bench_fiducial.

Measured, each with the scene's snapshot schedule (CVODE restarts at every snapshot):

  coupled            the scene as it is: global steps, and cell-steps = steps x N
  local only         drift and diffusion off: the cells no longer exchange dust, so the
                     steps are those of N local growth histories sharing one step size
  cells on their own every K-th cell alone (a 4-cell grid of relative width 5e-4 at its
                     centre, transport off): the sum over cells of their own steps, the
                     least work any scheme that steps each cell with its own step size
                     (multirate, local time stepping) could do for the local physics
  restart cost       extra steps per CVODE restart of one cell (n_snapshots 41 -> 401),
                     what such a scheme pays each time transport hands a cell a new state

and the coupled run's steps by decade of time (--trace 1): how many, which variable limits
them, and how many are limited by a drained cell (Sigma_d below 1e-6 of the largest
Sigma_d met), whose dust no outcome can see.

    /usr/bin/python3 tests/bench/step_budget.py [--exe build/tests/bench_fiducial]
        [--every K] [--set key=value ...]
"""
import argparse
import collections
import math
import os
import re
import subprocess
import sys
import tomllib

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROW = re.compile(r"^\| ([0-9.]+) \| (\d+) \| (\d+) \| (\d+) \|")
TRACE = re.compile(r"^t = (\S+) yr  step \d+ .*limited by:\s+(\w+) in cell (\d+).*"
                   r"\|\| .*Sigma_d = (\S+) g")


def bench(exe, sets, trace=False):
    """(wall s, steps, RHS, Jac) of one bench_fiducial run; with trace, also the list of
    (t [yr], limiting variable) of every step."""
    cmd = [exe, "--runs", "1"] + (["--trace", "1"] if trace else [])
    for s in sets:
        cmd += ["--set", s]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    row = next(m for m in map(ROW.match, out.splitlines()) if m)
    steps = [(float(m.group(1)), m.group(2), float(m.group(4)))
             for m in map(TRACE.match, out.splitlines()) if m] if trace else None
    return float(row.group(1)), int(row.group(2)), int(row.group(3)), int(row.group(4)), \
        steps


def scene_grid(sets):
    """n_cells, r_in, r_out, stretch of the fiducial scene with the --set overrides."""
    with open(os.path.join(REPO, "params", "fiducial.toml"), "rb") as f:
        g = tomllib.load(f)["grid"]
    grid = {"n_cells": g["n_cells"], "r_in_au": g["r_in_au"], "r_out_au": g["r_out_au"],
            "stretch": g.get("stretch", 0.0)}
    for s in sets:
        key, _, val = s.partition("=")
        if key.startswith("grid.") and key[5:] in grid:
            grid[key[5:]] = float(val)
    return int(grid["n_cells"]), grid["r_in_au"], grid["r_out_au"], grid["stretch"]


def cell_centres(n, r_in, r_out, p):
    """Centres (geometric mean of the faces) of src/grid.cpp's grid: faces uniform in
    ln r (p = 0) or in r^-p."""
    if p == 0.0:
        faces = [r_in * (r_out / r_in) ** (i / n) for i in range(n + 1)]
    else:
        u0, u1 = r_in ** -p, r_out ** -p
        faces = [(u0 + (u1 - u0) * i / n) ** (-1.0 / p) for i in range(n + 1)]
    return [math.sqrt(a * b) for a, b in zip(faces[:-1], faces[1:])]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", default=os.path.join(REPO, "build", "tests", "bench_fiducial"))
    ap.add_argument("--every", type=int, default=10, help="sample every K-th cell")
    ap.add_argument("--set", action="append", default=[], dest="sets")
    a = ap.parse_args()
    n, r_in, r_out, p = scene_grid(a.sets)
    local = ["transport.drift=false", "transport.diffusion=false"]

    wall, steps, rhs, jac, trace = bench(a.exe, a.sets, trace=True)
    _, steps_local, _, _, _ = bench(a.exe, a.sets + local)
    rc = cell_centres(n, r_in, r_out, p)
    sampled = list(range(a.every // 2, n, a.every))
    own = []
    for i in sampled:
        one = a.sets + local + [f"grid.n_cells=4", f"grid.r_in_au={rc[i]:.9g}",
                                f"grid.r_out_au={rc[i] * 1.0005:.9g}", "grid.stretch=0"]
        own.append(bench(a.exe, one)[1])
        print(f"  cell {i:4d} (r = {rc[i]:8.3f} au): {own[-1]} steps on its own",
              file=sys.stderr)
    own_sum = sum(own) * n / len(sampled)
    mid = rc[n // 2]
    restart = []
    for ns in (41, 401):
        one = a.sets + local + ["grid.n_cells=4", f"grid.r_in_au={mid:.9g}",
                                f"grid.r_out_au={mid * 1.0005:.9g}", "grid.stretch=0",
                                f"output.n_snapshots={ns}"]
        restart.append(bench(a.exe, one)[1])
    per_restart = (restart[1] - restart[0]) / 360.0

    print(f"fiducial scene, {n} cells (stretch {p:g}), r = {r_in:g}..{r_out:g} au"
          + "".join(f", {s}" for s in a.sets))
    print("\n| scheme | steps | cell-steps | vs coupled |\n|---|---|---|---|")
    print(f"| coupled (the scene) | {steps} | {steps * n:.3g} | 1 |")
    print(f"| local only (transport off), one step size | {steps_local} | "
          f"{steps_local * n:.3g} | {steps_local / steps:.2f} |")
    print(f"| every cell on its own step size (sum; {len(sampled)} cells sampled) | "
          f"{sum(own) / len(sampled):.0f} per cell | {own_sum:.3g} | "
          f"{own_sum / (steps * n):.3f} |")
    print(f"\nrestart cost of one cell at r = {mid:.3g} au: {per_restart:.1f} steps per "
          f"CVODE restart ({restart[0]} steps with 41 snapshots, {restart[1]} with 401)")
    # a drained cell: Sigma_d below 1e-6 of the largest Sigma_d met in the trace
    drained = 1e-6 * max(sd for _, _, sd in trace)
    by_decade = collections.Counter()
    by_drained = collections.Counter()
    by_var = collections.defaultdict(collections.Counter)
    for t, var, sd in trace:
        d = math.floor(math.log10(max(t, 1e-3)))
        by_decade[d] += 1
        by_drained[d] += sd < drained
        by_var[d][var] += 1
    print("\n| t [yr] | steps | share | limited most by | limited by a drained cell |\n"
          "|---|---|---|---|---|")
    for d in sorted(by_decade):
        top = ", ".join(f"{v} {c}" for v, c in by_var[d].most_common(2))
        lo = "0" if d <= -3 else f"1e{d}"
        print(f"| {lo}..1e{d + 1} | {by_decade[d]} | "
              f"{100 * by_decade[d] / len(trace):.0f} % | {top} | {by_drained[d]} |")
    print(f"\n{sum(by_drained.values())} steps limited by a drained cell (Sigma_d < "
          f"{drained:.2g} g cm^-2, 1e-6 of the largest Sigma_d in the trace)")


if __name__ == "__main__":
    main()
