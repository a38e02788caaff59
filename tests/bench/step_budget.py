"""Where the CVODE steps of the fiducial scene go, and how many a scheme that stepped every
cell on its own would need (issues 3 and 7: why the run takes ~5 700 steps). Run on
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
                   r"\|\| .*Sigma_d = (\S+) g.*St = ([-+.0-9e]+)\)")


def bench(exe, sets, trace=False):
    """(wall s, steps, RHS, Jac) of one bench_fiducial run; with trace, also the list of
    (t [yr], limiting variable, Sigma_d and St of its cell) of every step, and the table of
    bench_fiducial --lts (local time stepping, best case)."""
    cmd = [exe, "--runs", "1"] + (["--trace", "1", "--lts"] if trace else [])
    for s in sets:
        cmd += ["--set", s]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    row = next(m for m in map(ROW.match, out.splitlines()) if m)
    steps = [(float(m.group(1)), m.group(2), float(m.group(4)), float(m.group(5)))
             for m in map(TRACE.match, out.splitlines()) if m] if trace else None
    lines = out.splitlines()
    lts = None
    if trace:  # bench_fiducial prints the --lts table before its own
        k = next(i for i, line in enumerate(lines) if line.startswith("local time stepping"))
        lts = "\n".join(lines[k:next(i for i in range(k, len(lines))
                                     if lines[i].startswith("params/"))])
    return float(row.group(1)), int(row.group(2)), int(row.group(3)), int(row.group(4)), \
        steps, lts


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
    """Centres (geometric mean of the faces) of src/solver/grid.cpp's grid: faces uniform in
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

    wall, steps, rhs, jac, trace, lts = bench(a.exe, a.sets, trace=True)
    steps_local = bench(a.exe, a.sets + local)[1]
    rc = cell_centres(n, r_in, r_out, p)
    sampled = list(range(a.every // 2, n, a.every))
    own = []
    for i in sampled:
        one = a.sets + local + ["grid.n_cells=4", f"grid.r_in_au={rc[i]:.9g}",
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
    sd_max = max(sd for _, _, sd, _ in trace)
    drained = 1e-6 * sd_max
    by_decade = collections.Counter()
    by_drained = collections.Counter()
    by_var = collections.defaultdict(collections.Counter)
    past_barrier = collections.defaultdict(collections.Counter)
    for t, var, sd, st in trace:
        d = math.floor(math.log10(max(t, 1e-3)))
        by_decade[d] += 1
        by_drained[d] += sd < drained
        by_var[d][var] += 1
        if st > 1.0:  # past the drift barrier: running away, or what conversion left
            past_barrier[d]["left" if sd < 1e-3 * sd_max else "full"] += 1
    print("\n| t [yr] | steps | share | limited most by | limited by a drained cell | "
          "by a cell past St = 1 (of which nearly empty) |\n|---|---|---|---|---|---|")
    for d in sorted(by_decade):
        top = ", ".join(f"{v} {c}" for v, c in by_var[d].most_common(2))
        lo = "0" if d <= -3 else f"1e{d}"
        pb = past_barrier[d]
        print(f"| {lo}..1e{d + 1} | {by_decade[d]} | "
              f"{100 * by_decade[d] / len(trace):.0f} % | {top} | {by_drained[d]} | "
              f"{pb['full'] + pb['left']} ({pb['left']}) |")
    print(f"\n{sum(by_drained.values())} steps limited by a drained cell (Sigma_d < "
          f"{drained:.2g} g cm^-2, 1e-6 of the largest Sigma_d in the trace); "
          f"'nearly empty': Sigma_d < 1e-3 of it")
    print("\n" + lts)
    crossing_times(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(a.exe))),
                                "panoptic"), a.sets)


def crossing_times(panoptic, sets):
    """How fast transport is where the dust is: the shortest time in which drift crosses a
    cell holding at least 1e-3 of the largest Sigma_d, at each decade of snapshots of a
    `panoptic run` of the scene (the time scale a multirate scheme must resolve in the
    transport, against the local runaways' t_grow of 0.3-1 yr)."""
    import tempfile
    import h5py
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "fiducial.h5")
        cmd = [panoptic, "run", os.path.join(REPO, "params", "fiducial.toml"), "-o", out]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, capture_output=True, text=True, check=True)
        with h5py.File(out, "r") as f:
            t = f["snapshots/time"][:]  # yr
            dr = (f["grid/r_f"][1:] - f["grid/r_f"][:-1]) * 1.495978707e13  # cm
            rc = f["grid/r_c"][:]
            vr = abs(f["snapshots/v_r"][:])  # cm/s on the faces
            sd = f["snapshots/sigma_d"][:]
            st = f["snapshots/St"][:]
    best = {}
    for k in range(1, len(t)):
        d = math.floor(math.log10(t[k]))
        for i in range(len(dr)):
            v = max(vr[k, i], vr[k, i + 1])
            if sd[k, i] < 1e-3 * sd[k].max() or v <= 0.0:
                continue
            tc = dr[i] / v / 3.15576e7
            if d not in best or tc < best[d][0]:
                best[d] = (tc, rc[i], st[k, i], t[k])
    print("\n| snapshots in [yr] | shortest drift crossing of a cell with dust [yr] | at r "
          "[au] | St | t [yr] |\n|---|---|---|---|---|")
    for d in sorted(best):
        tc, r, s, tk = best[d]
        print(f"| 1e{d}..1e{d + 1} | {tc:.2g} | {r:.3g} | {s:.2g} | {tk:.3g} |")


if __name__ == "__main__":
    main()
