"""Work-precision study (issue 7): cost against error of the outcomes users read off, for a
scene over a grid of cell counts N and relative tolerances rtol. Run on demand, not in CI.

For every (N, rtol) the scene is run with `--set grid.n_cells=N --set solver.rtol=RTOL`
(everything else as in the scene, the snapshot schedule included: CVODE restarts at every
snapshot, so the schedule is part of the method). Recorded: CPU time of the process (the
wall time on a shared machine is several times longer; both are kept),
CVODE steps, RHS and Jacobian evaluations, and the errors against a reference run of the
same scene (--ref-n, --ref-rtol) in

  sigma_d@1e4, @1e5, @1e6 yr  Sigma_d(r) at the snapshot nearest to those times (the
                              scene must have one within 1e-6 relative): relative L1 error
                              weighted by the annulus area, i.e. the dust mass misplaced,
                              sum_i |Sigma_i - Sigma_ref,i| A_i / sum_i Sigma_ref,i A_i,
                              where Sigma_ref,i is the reference averaged conservatively
                              onto the run's cells (its cell masses split by overlapping
                              annulus area; both grids span the same r_in..r_out)
  m_pl                        total planetesimal mass /summary m_pl_coag + m_pl_si:
                              relative error
  r_pl_out                    outer edge of the planetesimal zone, max(/summary
                              r_max_pl_coag, r_max_pl_si) (a cell centre, so it moves in
                              steps of one cell width): relative error
  m_peb_snow                  pebble mass through the snow line /summary m_peb_snowline:
                              relative error
  max                         the largest of these

A second reference (--ref2-n, --ref2-rtol) is compared with the first in the same way; its
error bounds how far the reference itself can be trusted.

    /usr/bin/python3 tests/bench/work_precision.py --exe build/panoptic --workdir DIR \
        [--scenes fiducial erosion_40] [--n-cells 32 64 ...] [--rtol 1e-2 1e-4 ...] \
        [--ref-n 2048 --ref-rtol 1e-8 --ref-atol 1e-12] [--ref2-n 1024 --ref2-rtol 1e-8] \
        [--stretch 0 0.5] [--timeout 1800] [--max-cost 1e9] [--jobs 1]

writes DIR/work_precision.json (every run: settings, costs, errors, command),
DIR/work_precision.csv, DIR/work_precision_<scene>.png (error against CPU time, one
panel per outcome), DIR/work_precision.md (a table per scene, Pareto-optimal runs in
bold) and DIR/work_precision_summary.md (per scene: every grid at --summary-rtol, every
rtol on --summary-grid N:stretch, and the Pareto front). Finished outputs in DIR are reused (delete DIR to measure afresh; --fresh ignores
them). A run still going after --timeout seconds or refused by the step budget is
recorded as not finished. --max-cost skips runs whose N * rtol^(-1/5) exceeds it (a
rough cost model of BDF: steps grow like rtol^(-1/order) and the work per step like N).
--stretch adds grid.stretch values (cell spacing d ln r ∝ r^stretch; the references stay
log-spaced). --existing-only tabulates the runs already in DIR out of the product of the
lists given, and runs nothing new."""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, REPO)
from postprocess.reader import load_run  # noqa: E402

import numpy as np  # noqa: E402

T_SIGMA = (1e4, 1e5, 1e6)  # yr: Sigma_d(r) compared at these times
OUTCOMES = [f"sigma_d@{t:.0e}".replace("+0", "") for t in T_SIGMA] + [
    "m_pl", "r_pl_out", "m_peb_snow"]


def tag(scene, n, rtol, stretch=0.0):
    return f"{scene}_N{n}_rtol{rtol:.0e}" + (f"_s{stretch:g}" if stretch else "")


def error_line(stderr):
    """The error message of a failed run: its "panoptic: error:" line (the failure
    report that follows lists cells), else the last line."""
    lines = stderr.strip().splitlines()
    err = [ln.removeprefix("panoptic: error: ") for ln in lines
           if ln.startswith("panoptic: error: ")]
    return (err[0] if err else (lines[-1] if lines else ""))[:200]


def run_one(exe, workdir, scene, n, rtol, timeout, max_steps, fresh, stretch=0.0,
            atol_sigma=None):
    """Runs one (scene, N, rtol, grid stretch) unless a finished output is there; returns
    its record. `atol_sigma`, if given, overrides the scene's solver.atol_sigma."""
    out = os.path.join(workdir, tag(scene, n, rtol, stretch) + ".h5")
    meta = out + ".json"
    cmd = [exe, "run", os.path.join(REPO, "params", scene + ".toml"), "-o", out,
           "--overwrite", "--set", f"grid.n_cells={n}", "--set", f"solver.rtol={rtol:g}",
           "--set", f"grid.stretch={stretch:g}",
           "--set", "checkpoint.every_wall_s=0", "--set", f"solver.max_steps={max_steps}"]
    if atol_sigma is not None:
        cmd += ["--set", f"solver.atol_sigma={atol_sigma:g}"]
    rec = {"scene": scene, "n_cells": n, "rtol": rtol, "stretch": stretch,
           "cmd": " ".join(cmd), "out": out}
    if not fresh and os.path.exists(meta):
        with open(meta) as f:
            old = json.load(f)
        if old.get("cmd") == rec["cmd"] and (old.get("finished") or
                                             old.get("timeout", 0) >= timeout):
            if not old.get("finished") and "timeout" not in old and \
                    os.path.exists(out + ".stderr"):
                with open(out + ".stderr") as f:
                    old["error"] = error_line(f.read())
            return old
    t0 = time.monotonic()
    err_path = out + ".stderr"
    with open(err_path, "w") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
    # CPU time (wait4) is what the run costs on one free core; the wall time on a
    # shared machine is several times longer
    while True:
        pid, status, ru = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        if time.monotonic() - t0 > timeout:
            p.kill()
        time.sleep(0.1)
    with open(err_path) as f:
        stderr = f.read()
    rec.update(wall=time.monotonic() - t0, cpu=ru.ru_utime + ru.ru_stime,
               code=os.waitstatus_to_exitcode(status))
    rec["finished"] = rec["code"] == 0
    if rec["wall"] > timeout:
        rec.update(timeout=timeout, error=f"still running after {timeout:.0f} s")
    elif not rec["finished"]:
        rec["error"] = error_line(stderr)
    if rec["finished"]:
        run = load_run(out)
        rec.update(steps=int(run.solver["nst"]), rhs=int(run.solver["nfe"]),
                   jac=int(run.solver["nje"]), wall_solver=float(run.solver["wall_s"]))
    with open(meta, "w") as f:
        json.dump(rec, f)
    return rec


def conservative_average(r_f_src, sigma_src, r_f_dst):
    """Sigma of the source cells averaged onto the destination cells: the mass of each
    source annulus is split by overlapping area (uniform in r^2 within a cell)."""
    a_src = r_f_src**2
    a_dst = r_f_dst**2
    # cumulative mass (in units of pi au^2 g/cm^2) at each source face, then linear in r^2
    cum = np.concatenate([[0.0], np.cumsum(sigma_src * np.diff(a_src))])
    cum_dst = np.interp(a_dst, a_src, cum)
    return np.diff(cum_dst) / np.diff(a_dst)


def outcomes(run):
    """Numbers of one run: Sigma_d profiles at T_SIGMA and the summary outcomes."""
    res = {"r_f": run.r_f, "sigma": []}
    for t in T_SIGMA:
        k = int(np.argmin(np.abs(run.time - t)))
        if abs(run.time[k] / t - 1) > 1e-6:
            raise SystemExit(f"{run.path}: no snapshot at {t:g} yr (nearest {run.time[k]:g});"
                             " the scene's output times must include 1e4, 1e5 and 1e6 yr")
        res["sigma"].append(run.snapshots["sigma_d"][k])
    s = run.summary
    res["m_pl"] = s.get("m_pl_coag", 0.0) + s.get("m_pl_si", 0.0)
    edges = [s[k] for k in ("r_max_pl_coag", "r_max_pl_si") if k in s and np.isfinite(s[k])]
    res["r_pl_out"] = max(edges) if edges else float("nan")
    res["m_peb_snow"] = s.get("m_peb_snowline", float("nan"))
    return res


def errors(o, ref):
    """Errors of outcomes `o` against the reference outcomes `ref` (dict name -> float)."""
    e = {}
    area = np.diff(o["r_f"]**2)
    for name, sig, sig_ref in zip(OUTCOMES[:3], o["sigma"], ref["sigma"]):
        avg = conservative_average(ref["r_f"], sig_ref, o["r_f"])
        e[name] = float(np.sum(np.abs(sig - avg) * area) / np.sum(avg * area))
    for name in OUTCOMES[3:]:
        v, v_ref = o[name], ref[name]
        e[name] = (float(abs(v / v_ref - 1)) if v_ref != 0 and np.isfinite(v_ref)
                   else (0.0 if v == v_ref else float("nan")))
    # the largest defined error (the zone edge is undefined where no zone forms)
    e["max"] = max((e[k] for k in OUTCOMES if np.isfinite(e[k])), default=float("nan"))
    return e


def pareto(recs):
    """Marks each finished record on the front of (CPU time, max error)."""
    done = [r for r in recs if r.get("finished") and np.isfinite(r["err"]["max"])]
    for r in done:
        r["pareto"] = not any(q is not r and q["cpu"] <= r["cpu"] and
                              q["err"]["max"] <= r["err"]["max"] and
                              (q["cpu"] < r["cpu"] or q["err"]["max"] < r["err"]["max"])
                              for q in done)


def plot(recs, scene, ref_label, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    done = [r for r in recs if r.get("finished")]
    ns = sorted({r["n_cells"] for r in done})
    series = sorted({(r.get("stretch", 0.0), r["n_cells"]) for r in done})
    rtols = sorted({r["rtol"] for r in done})
    cmap = plt.get_cmap("viridis")
    markers = "os^Dv<>ph*"
    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5), constrained_layout=True)
    for ax, name in zip(axes.flat, OUTCOMES + ["max"]):
        if not any(np.isfinite(r["err"][name]) for r in done):
            # e.g. the zone edge of a scene that forms no planetesimals
            ax.text(0.5, 0.5, "undefined in this scene", transform=ax.transAxes,
                    ha="center", va="center")
            ax.set_title(name, fontsize=10)
            continue
        for st, n in series:
            i = ns.index(n)
            rs = sorted((r for r in done if r["n_cells"] == n and
                         r.get("stretch", 0.0) == st and np.isfinite(r["err"][name])),
                        key=lambda r: r["rtol"])
            x = [r["cpu"] for r in rs]
            y = [max(r["err"][name], 1e-12) for r in rs]
            label = f"N = {n}" + (f", stretch {st:g}" if st else "")
            ax.plot(x, y, "--" if st else "-", color=cmap(i / max(1, len(ns) - 1)), lw=0.8,
                    label=label if name == OUTCOMES[0] else None)
            for r in rs:
                ax.plot(r["cpu"], max(r["err"][name], 1e-12),
                        markers[rtols.index(r["rtol"]) % len(markers)],
                        color=cmap(i / max(1, len(ns) - 1)), ms=5,
                        mec="k" if r.get("pareto") else "none")
        ax.axhline(0.01, color="0.6", ls=":", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time [s]")
        ax.set_title(name + (" (all outcomes)" if name == "max" else ""), fontsize=10)
    axes.flat[7].axis("off")
    axes.flat[0].set_ylabel("relative error")
    axes.flat[4].set_ylabel("relative error")
    for j, rt in enumerate(rtols):
        axes.flat[1].plot([], [], markers[j % len(markers)], color="0.4",
                          label=f"rtol = {rt:.0e}")
    axes.flat[0].legend(fontsize=7)
    axes.flat[1].legend(fontsize=7)
    fig.suptitle(f"{scene}: work-precision against {ref_label} (black edge: Pareto front "
                 f"of the max error; dotted: 1 %)")
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt(x):
    return "–" if x is None or not np.isfinite(x) else f"{x:.1e}"


def table(recs):
    """Markdown rows of `recs` (sorted by stretch, N, falling rtol); Pareto runs in bold."""
    lines = ["| N | stretch | rtol | CPU [s] | steps | RHS | Jac | " + " | ".join(OUTCOMES) +
             " | max |", "|---|---|---|---|---|---|---|" + "---|" * (len(OUTCOMES) + 1)]
    for r in sorted(recs, key=lambda r: (r.get("stretch", 0.0), r["n_cells"], -r["rtol"])):
        st = f"{r.get('stretch', 0.0):g}"
        if not r.get("finished"):
            lines.append(f"| {r['n_cells']} | {st} | {r['rtol']:.0e} | > {r['wall']:.0f} | "
                         f"not finished: {r.get('error', '')} |" + " |" * (len(OUTCOMES) + 3))
            continue
        b = "**" if r.get("pareto") else ""
        lines.append(f"| {b}{r['n_cells']}{b} | {b}{st}{b} | {b}{r['rtol']:.0e}{b} | "
                     f"{r['cpu']:.1f} | {r['steps']} | {r['rhs']} | {r['jac']} | " +
                     " | ".join(fmt(r["err"][k]) for k in OUTCOMES) +
                     f" | {b}{fmt(r['err']['max'])}{b} |")
    return lines


def ref_line(scene, ref):
    return (f"**{scene}** (reference: N = {ref['n_cells']}, rtol = {ref['rtol']:.0e}, "
            f"{ref['cpu']:.0f} s, {ref['steps']} steps"
            + (f"; its own error against N = {ref['ref2']['n_cells']}, rtol = "
               f"{ref['ref2']['rtol']:.0e}: max {fmt(ref['ref2']['err']['max'])}"
               f" ({', '.join(f'{k} {fmt(v)}' for k, v in ref['ref2']['err'].items() if k != 'max')})"
               if ref.get("ref2") else "") + ")\n")


def markdown(by_scene, refs, sha):
    lines = [f"Measured at commit {sha}. Errors relative to the reference; "
             "Costs are CPU seconds (one core). Pareto-optimal (CPU time, max error) runs in bold.\n"]
    for scene, recs in by_scene.items():
        lines += [ref_line(scene, refs[scene])] + table(recs) + [""]
    return "\n".join(lines)


def summary_markdown(by_scene, refs, sha, rtol, grid):
    """The condensed view: every grid at one rtol, every rtol on one grid (N, stretch),
    and the Pareto front, per scene."""
    n, st = grid
    lines = [f"Measured at commit {sha}. Errors relative to the reference; costs are CPU "
             "seconds (one core); bold: on the Pareto front of (CPU time, max error) among "
             "all runs of the scene.\n"]
    for scene, recs in by_scene.items():
        lines += [ref_line(scene, refs[scene]), f"Every grid at rtol = {rtol:.0e}:\n"]
        lines += table([r for r in recs if r["rtol"] == rtol]) + [""]
        lines += [f"Every rtol at N = {n}, stretch {st:g}:\n"]
        lines += table([r for r in recs if r["n_cells"] == n and
                        r.get("stretch", 0.0) == st]) + [""]
        lines += ["The Pareto front:\n"] + table([r for r in recs if r.get("pareto")]) + [""]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--scenes", nargs="+", default=["fiducial", "erosion_40"])
    ap.add_argument("--n-cells", nargs="+", type=int,
                    default=[32, 64, 128, 256, 512, 1024, 2048])
    ap.add_argument("--rtol", nargs="+", type=float,
                    default=[1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8])
    ap.add_argument("--stretch", nargs="+", type=float, default=[0.0],
                    help="grid.stretch values (0: log-spaced)")
    ap.add_argument("--ref-n", type=int, default=4096)
    ap.add_argument("--ref-rtol", type=float, default=1e-10)
    # The scene's absolute tolerance (solver.atol_sigma = 1e-8 of the initial maximum of
    # Sigma) would dominate rtol = 1e-10 wherever Sigma_d is below 100 times that maximum,
    # i.e. everywhere: the references tighten it too (1e-12, as the references of tests/bench/README.md).
    ap.add_argument("--ref-atol", type=float, default=1e-12,
                    help="solver.atol_sigma of the reference runs")
    ap.add_argument("--ref2-n", type=int, help="second reference, to bound the first's error")
    ap.add_argument("--ref2-rtol", type=float)
    ap.add_argument("--timeout", type=float, default=1800.0, help="wall-time limit per run [s]")
    ap.add_argument("--ref-timeout", type=float, default=14400.0)
    ap.add_argument("--max-steps", type=int, default=2000000)
    ap.add_argument("--max-cost", type=float, default=float("inf"),
                    help="skip runs with N * rtol^(-1/5) above this")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--fresh", action="store_true", help="rerun even if outputs exist")
    ap.add_argument("--existing-only", action="store_true",
                    help="tabulate only the runs already in --workdir (run nothing new)")
    ap.add_argument("--summary-rtol", type=float, default=1e-5,
                    help="work_precision_summary.md: every grid at this rtol")
    ap.add_argument("--summary-grid", default="350:0.5",
                    help="work_precision_summary.md: every rtol on this grid, N:stretch")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    exe = os.path.abspath(args.exe)
    sha = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip()

    jobs = []  # (scene, n, rtol, timeout, role, stretch); the references log-spaced
    for scene in args.scenes:
        jobs.append((scene, args.ref_n, args.ref_rtol, args.ref_timeout, "ref", 0.0))
        if args.ref2_n:
            jobs.append((scene, args.ref2_n, args.ref2_rtol, args.ref_timeout, "ref2", 0.0))
        for st in args.stretch:
            for n in args.n_cells:
                for rt in args.rtol:
                    if st == 0.0 and (n, rt) in ((args.ref_n, args.ref_rtol),
                                                 (args.ref2_n, args.ref2_rtol)):
                        continue
                    if n * rt ** -0.2 > args.max_cost:
                        continue
                    if args.existing_only and not os.path.exists(os.path.join(
                            args.workdir, tag(scene, n, rt, st) + ".h5.json")):
                        continue
                    jobs.append((scene, n, rt, args.timeout, "run", st))
    print(f"{len(jobs)} runs, {args.jobs} at a time ({sha})", flush=True)
    recs = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futs = {pool.submit(run_one, exe, args.workdir, s, n, rt, to, args.max_steps,
                            args.fresh, st, args.ref_atol if role != "run" else None): role
                for s, n, rt, to, role, st in jobs}
        for fut in concurrent.futures.as_completed(futs):
            r = fut.result()
            r["role"] = futs[fut]
            recs.append(r)
            print(f"[{len(recs)}/{len(jobs)}] {r['scene']:12s} N={r['n_cells']:5d} "
                  f"stretch={r.get('stretch', 0.0):g} "
                  f"rtol={r['rtol']:.0e} {'ok ' if r.get('finished') else 'NOT'} "
                  f"{r['cpu']:8.1f} s cpu {r['wall']:8.1f} s wall {r.get('steps', '')} {r.get('error', '')}", flush=True)

    by_scene, refs = {}, {}
    for scene in args.scenes:
        ref = next(r for r in recs if r["scene"] == scene and r["role"] == "ref")
        if not ref.get("finished"):
            raise SystemExit(f"the reference of {scene} did not finish: {ref.get('error')}")
        ref_o = outcomes(load_run(ref["out"]))
        ref2 = next((r for r in recs if r["scene"] == scene and r["role"] == "ref2"), None)
        if ref2 and ref2.get("finished"):
            ref2["err"] = errors(outcomes(load_run(ref2["out"])), ref_o)
            ref["ref2"] = ref2
        runs = [r for r in recs if r["scene"] == scene and r["role"] == "run"]
        if ref2:
            runs.append(dict(ref2, role="run"))
        for r in runs:
            if r.get("finished"):
                r["err"] = errors(outcomes(load_run(r["out"])), ref_o)
                r["outcomes"] = {k: v for k, v in outcomes(load_run(r["out"])).items()
                                 if k in OUTCOMES}
        ref["outcomes"] = {k: v for k, v in ref_o.items() if k in OUTCOMES}
        pareto(runs)
        by_scene[scene], refs[scene] = runs, ref
        plot(runs, scene, f"N = {ref['n_cells']}, rtol = {ref['rtol']:.0e}",
             os.path.join(args.workdir, f"work_precision_{scene}.png"))

    allrecs = [r for s in args.scenes for r in by_scene[s]] + list(refs.values())
    with open(os.path.join(args.workdir, "work_precision.json"), "w") as f:
        json.dump({"version": sha, "records": allrecs}, f, indent=1, default=str)
    with open(os.path.join(args.workdir, "work_precision.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scene", "role", "n_cells", "stretch", "rtol", "finished", "cpu_s", "wall_s", "steps", "rhs",
                    "jac"] + [f"err_{k}" for k in OUTCOMES + ["max"]] + ["pareto"])
        for r in allrecs:
            e = r.get("err", {})
            w.writerow([r["scene"], r["role"], r["n_cells"], r.get("stretch", 0.0), r["rtol"],
                        r.get("finished"),
                        f"{r['cpu']:.3f}", f"{r['wall']:.3f}", r.get("steps"), r.get("rhs"), r.get("jac")] +
                       [e.get(k, "") for k in OUTCOMES + ["max"]] + [r.get("pareto", "")])
    text = markdown(by_scene, refs, sha)
    with open(os.path.join(args.workdir, "work_precision.md"), "w") as f:
        f.write(text)
    n, _, st = args.summary_grid.partition(":")
    with open(os.path.join(args.workdir, "work_precision_summary.md"), "w") as f:
        f.write(summary_markdown(by_scene, refs, sha, args.summary_rtol,
                                 (int(n), float(st or 0.0))))
    print(text)


if __name__ == "__main__":
    main()
