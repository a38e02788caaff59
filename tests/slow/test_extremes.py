"""Stability at the extremes (issue 5): every scene in params/*.toml run at the extremes of
its parameters, one axis at a time. Every run must either

  * complete, with no NaN or Inf in /snapshots (by design t_first_pl is NaN until a cell
    forms planetesimals and t_grow is +inf where growth has halted), no Sigma_d below -1e-12 of the snapshot's largest, and the mass
    budget m_dust + m_pl_coag + m_pl_si + m_out_inner + m_sublimated equal to the
    initial mass to 1e-8 at every snapshot; or
  * stop with a clear error: exit code 2 with a message naming a scene key (the scene is
    refused), or exit code 3 with a message naming the CVODE flag and the failing cell
    and variable (a solver failure).

Anything else (a failed check, another exit code, a crash, a run still going after the
wall-time limit) is a FAIL. Every run has a bounded step count (solver.max_steps) and a
CPU-time limit (--timeout, default 900 s; 6x for 4096 cells, 2x for rtol 1e-8 and
t_end 1e7), with a wall-time backstop of --wall-factor (5) times that. The table gives
CPU seconds: on a shared machine the wall time is several times the CPU time.

    /usr/bin/python3 tests/slow/test_extremes.py --exe build/panoptic --workdir DIR \
        [--table extremes.md] [--jobs 2] [--only REGEX] [--timeout 900] [--resume]

writes a markdown table (extreme x scene: pass / clear failure with its one-line reason /
FAIL, CPU time) to --table (default DIR/extremes.md), prints it, keeps one JSON line per
run in DIR/results.jsonl, and exits 1 when a run FAILs."""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import re
import subprocess
import sys
import threading
import time
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "regression"))
from common import REPO, budget_error, load_run  # noqa: E402

import numpy as np  # noqa: E402

AU = 1.496e13     # cm, src/core/units.hpp
MSUN = 1.989e33   # g
BUDGET_TOL = 1e-8
NEG_TOL = 1e-12
# solver.max_steps of every run: ~1.5 times the most any passing run needs (fiducial at
# alpha = 1e-5: 169 175 steps at 45306ca and every rerun since), and reached before the
# wall-time limit at ~2 ms per step
MAX_STEPS = 250000


# (row label, overrides or a function of the resolved scene returning them, timeout
# factor, solver.max_steps)
def disk_mass(frac):
    """Overrides giving a gas disk of frac * M_* (powerlaw: within the grid)."""
    def sets(cfg):
        m_star = cfg["star"]["mass_msun"]
        if cfg["disk"]["model"] == "lbp":
            return [f"disk.m_disk_msun={frac * m_star:.6g}"]
        p = cfg["disk"]["p"]
        x_in, x_out = cfg["grid"]["r_in_au"], cfg["grid"]["r_out_au"]
        # M = 2 pi Sigma_1 au^2 int_{x_in}^{x_out} x^(1-p) dx
        integral = (math.log(x_out / x_in) if abs(p - 2.0) < 1e-12
                    else (x_out ** (2 - p) - x_in ** (2 - p)) / (2 - p))
        sigma_1 = frac * m_star * MSUN / (2 * math.pi * AU**2 * integral)
        return [f"disk.sigma_1au={sigma_1:.6g}"]
    return sets


EXTREMES = [
    ("disk.alpha = 1e-5", ["disk.alpha=1e-5"], 1, MAX_STEPS),
    ("disk.alpha = 0.1", ["disk.alpha=0.1"], 1, MAX_STEPS),
    ("star.mass_msun = 0.1", ["star.mass_msun=0.1"], 1, MAX_STEPS),
    ("star.mass_msun = 3", ["star.mass_msun=3"], 1, MAX_STEPS),
    ("disk mass = 1e-4 M_*", disk_mass(1e-4), 1, MAX_STEPS),
    ("disk mass = 0.3 M_*", disk_mass(0.3), 1, MAX_STEPS),
    ("dust.dust_to_gas = 1e-5", ["dust.dust_to_gas=1e-5"], 1, MAX_STEPS),
    ("dust.dust_to_gas = 0.1", ["dust.dust_to_gas=0.1"], 1, MAX_STEPS),
    ("grid.n_cells = 16", ["grid.n_cells=16"], 1, MAX_STEPS),
    # ~16x the cost per step (~13 ms): a budget that binds (~4 CPU minutes) before the
    # CPU-time limit
    ("grid.n_cells = 4096", ["grid.n_cells=4096"], 6, 20000),
    ("grid 0.05-10 au", ["grid.r_in_au=0.05", "grid.r_out_au=10"], 1, MAX_STEPS),
    ("grid 10-3000 au", ["grid.r_in_au=10", "grid.r_out_au=3000"], 1, MAX_STEPS),
    ("solver.rtol = 1e-2", ["solver.rtol=1e-2"], 1, MAX_STEPS),
    ("solver.rtol = 1e-8", ["solver.rtol=1e-8"], 2, MAX_STEPS),
    ("output.t_end_yr = 1e7", ["output.t_end_yr=1e7"], 2, MAX_STEPS),
]


def scenes():
    return sorted(os.path.splitext(os.path.basename(p))[0]
                  for p in glob.glob(os.path.join(REPO, "params", "*.toml"))
                  if not p.endswith("reference.toml"))


def scene_keys():
    with open(os.path.join(REPO, "params", "reference.toml"), "rb") as f:
        ref = tomllib.load(f)
    return {f"{t}.{k}" for t, tab in ref.items() for k in tab}


def resolved(exe, scene):
    p = subprocess.run([exe, "check", os.path.join(REPO, "params", scene + ".toml")],
                       capture_output=True, text=True, check=True)
    return tomllib.loads(p.stdout)


def one_line(s, limit=160):
    s = " ".join(s.split())
    return s if len(s) <= limit else s[:limit - 3] + "..."


def judge_error(code, stderr, keys):
    """(verdict, reason) of a run that exited with `code`."""
    # without the warnings about keys the scene sets but does not use: a key named there
    # must not make an error that names none look clear
    msg = "\n".join(line for line in stderr.strip().splitlines()
                    if not line.startswith("panoptic: warning: "))
    # the error line (stderr may start with a note, e.g. where the last snapshot is kept)
    first = next((line.removeprefix("panoptic: error: ") for line in msg.splitlines()
                  if line.startswith("panoptic: error: ")), msg.splitlines()[0] if msg else "")
    if code == 2:
        named = sorted(k for k in keys if k in msg)
        if "error:" in msg and named:
            return "clear", "exit 2: " + one_line(first)
        return "FAIL", "exit 2 without a key named: " + one_line(first)
    if code == 3:
        flag = re.search(r"CVODE failed with (CV_[A-Z_]+)", msg)
        comp = re.search(r"^\s+(\S+ in cell \d+|\S+ \(global\))(.*)$", msg, re.M)
        if flag and comp:
            t = re.search(r"\(([^()]* yr)\)", first)
            return "clear", one_line(f"exit 3: {flag.group(1)}"
                                     f"{' at ' + t.group(1) if t else ''}; "
                                     f"{comp.group(1)}{comp.group(2)}")
        return "FAIL", "exit 3 without the flag and the failing cell: " + one_line(first)
    return "FAIL", f"exit code {code}: " + one_line(msg[-300:])


def check_output(path, t_end_yr):
    """Problems of a completed run ([] = pass) and its step count."""
    run = load_run(path)
    problems = []
    snaps = run.snapshots
    if run.solver.get("status") != "completed":
        problems.append(f"status {run.solver.get('status')!r}")
    if not np.isclose(run.time[-1], t_end_yr, rtol=1e-9):
        problems.append(f"ends at {run.time[-1]:.4g} yr")
    # t_first_pl is NaN until a cell forms planetesimals; t_grow is +inf where growth
    # has halted exactly (dm/dt = 0), never NaN
    bad = [k for k, v in snaps.items() if k != "t_first_pl" and not np.all(
        np.isfinite(v) | ((k == "t_grow") & (np.asarray(v) == np.inf)))]
    if bad:
        problems.append("non-finite " + ", ".join(sorted(bad)))
    sd = snaps["sigma_d"]
    neg = np.min(sd / np.maximum(np.max(np.abs(sd), axis=1, keepdims=True), 1e-300))
    if neg < -NEG_TOL:
        problems.append(f"Sigma_d down to {neg:.2g} of the max")
    err = budget_error(snaps)
    if not err <= BUDGET_TOL:
        problems.append(f"budget error {err:.2g}")
    return problems, err, int(run.solver.get("nst", -1))


def run_limited(cmd, log_path, cpu_limit, wall_factor):
    """Runs cmd with stdout and stderr into log_path (stderr after a '--- stderr' line);
    kills it past cpu_limit seconds of CPU time or wall_factor * cpu_limit of wall time.
    Returns (exit code, wall [s], CPU [s], None or the limit it was killed at). CPU time
    (user + system, from wait4) is what a run costs on one free core; on a shared machine
    the wall time is several times longer and says little about the run."""
    t0 = time.monotonic()
    with open(log_path + ".out", "w") as out, open(log_path + ".err", "w") as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err)
        limit = None
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            try:
                with open(f"/proc/{p.pid}/stat") as f:
                    fields = f.read().rpartition(")")[2].split()
                cpu = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
            except (OSError, IndexError, ValueError):
                cpu = 0.0
            wall = time.monotonic() - t0
            if limit is None and (cpu > cpu_limit or wall > wall_factor * cpu_limit):
                limit = (f"{cpu_limit:.0f} s of CPU time" if cpu > cpu_limit
                         else f"{wall_factor * cpu_limit:.0f} s of wall time")
                p.kill()
            time.sleep(0.2)
    wall = time.monotonic() - t0
    cpu = ru.ru_utime + ru.ru_stime
    code = os.waitstatus_to_exitcode(status)
    with open(log_path, "w") as f:
        f.write(" ".join(cmd) + "\n")
        for part, sep in ((".out", ""), (".err", "\n--- stderr\n")):
            with open(log_path + part) as g:
                f.write(sep + g.read())
            os.remove(log_path + part)
    return code, wall, cpu, limit


def run_case(exe, workdir, scene, label, sets, timeout, max_steps, keys, t_end_yr,
             wall_factor):
    tag = re.sub(r"[^A-Za-z0-9]+", "_", f"{scene}_{label}").strip("_")
    out = os.path.join(workdir, tag + ".h5")
    cmd = [exe, "run", os.path.join(REPO, "params", scene + ".toml"), "-o", out,
           "--overwrite", "--set", f"solver.max_steps={max_steps}",
           "--set", "checkpoint.every_wall_s=0"]
    for s in sets:
        cmd += ["--set", s]
    res = {"scene": scene, "extreme": label, "sets": sets, "cmd": " ".join(cmd)}
    log_path = os.path.join(workdir, tag + ".log")
    code, wall, cpu, limit = run_limited(cmd, log_path, timeout, wall_factor)
    res.update(wall=wall, cpu=cpu)
    if limit:
        res.update(verdict="FAIL", reason=f"timeout: still running after {limit}")
        return res
    res["code"] = code
    with open(log_path) as f:
        stderr = f.read().partition("\n--- stderr\n")[2]
    if code != 0:
        res["verdict"], res["reason"] = judge_error(code, stderr, keys)
        return res
    try:
        problems, err, nst = check_output(out, t_end_yr)
    except Exception as e:  # an unreadable output is a failure, not a crash of the test
        problems, err, nst = [f"output unreadable: {e}"], float("nan"), -1
    res.update(budget_error=err, steps=nst)
    res["verdict"] = "FAIL" if problems else "pass"
    res["reason"] = "; ".join(problems)
    for name in (out, os.path.splitext(out)[0] + ".chk.h5",
                 os.path.splitext(out)[0] + ".chk.prev.h5"):
        if res["verdict"] == "pass" and os.path.exists(name):
            os.remove(name)  # keep the disk clean; a failing run's file stays
    return res


def cell_text(r):
    t = f"{r.get('cpu', r['wall']):.0f} s"
    if r["verdict"] == "pass":
        return f"pass, {t}"
    if r["verdict"] == "clear":
        return f"clear failure ({r['reason']}), {t}"
    return f"**FAIL** ({r['reason']}), {t}"


def table(results, scene_list):
    by = {(r["extreme"], r["scene"]): r for r in results}
    rows = ["| extreme | " + " | ".join(scene_list) + " |",
            "|---|" + "---|" * len(scene_list)]
    for label, *_ in EXTREMES:
        if not any((label, s) in by for s in scene_list):
            continue
        rows.append(f"| {label} | " + " | ".join(
            cell_text(by[(label, s)]) if (label, s) in by else "–" for s in scene_list) + " |")
    return "\n".join(rows) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", required=True, help="the panoptic executable")
    ap.add_argument("--workdir", required=True, help="where run outputs and logs go")
    ap.add_argument("--table", help="markdown table file (default WORKDIR/extremes.md)")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel")
    ap.add_argument("--timeout", type=float, default=900.0,
                    help="CPU-time limit per run [s] (times a factor for the costly extremes)")
    ap.add_argument("--wall-factor", type=float, default=5.0,
                    help="wall-time limit per run as a multiple of its CPU-time limit")
    ap.add_argument("--resume", action="store_true",
                    help="keep the results already in WORKDIR/results.jsonl and run only "
                         "the other cases (and the selected ones that timed out)")
    ap.add_argument("--only", help="run only cases whose 'scene extreme' matches this regex")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    exe = os.path.abspath(args.exe)
    keys = scene_keys()
    scene_list = scenes()
    cases = []
    for label, sets, factor, max_steps in EXTREMES:
        for scene in scene_list:
            if args.only and not re.search(args.only, f"{scene} {label}"):
                continue
            cfg = resolved(exe, scene)
            s = sets(cfg) if callable(sets) else list(sets)
            t_end = next((float(x.split("=")[1]) for x in s
                          if x.startswith("output.t_end_yr=")), cfg["output"]["t_end_yr"])
            cases.append((scene, label, s, factor * args.timeout, max_steps, t_end))
    # the longest first, so that the two workers finish together
    cases.sort(key=lambda c: -c[3])
    results, lock = [], threading.Lock()
    jsonl = os.path.join(args.workdir, "results.jsonl")
    if args.resume and os.path.exists(jsonl):
        with open(jsonl) as f:
            kept = [json.loads(line) for line in f if line.strip()]
        # a timeout of a selected case is run again; every other result is kept
        done = {(r["scene"], r["extreme"]) for r in kept
                if not r["reason"].startswith("timeout")}
        cases = [c for c in cases if (c[0], c[1]) not in done]
        rerun = {(c[0], c[1]) for c in cases}
        results = [r for r in kept if (r["scene"], r["extreme"]) not in rerun]
    n_kept = len(results)
    print(f"{len(cases)} runs, {args.jobs} at a time ({n_kept} kept)", flush=True)
    t0 = time.monotonic()
    with open(jsonl, "w") as log, \
            concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for r in results:
            log.write(json.dumps(r) + "\n")
        futures = [pool.submit(run_case, exe, args.workdir, scene, label, s, timeout,
                               max_steps, keys, t_end, args.wall_factor)
                   for scene, label, s, timeout, max_steps, t_end in cases]
        for fut in concurrent.futures.as_completed(futures):
            r = fut.result()
            with lock:
                results.append(r)
                log.write(json.dumps(r) + "\n")
                log.flush()
            print(f"[{len(results) - n_kept}/{len(cases)}] {r['scene']:22s} {r['extreme']:24s} "
                  f"{r['verdict']:5s} {r.get('cpu', 0):7.1f} s cpu {r['wall']:7.1f} s wall  "
                  f"{r.get('reason', '')}", flush=True)
    total = time.monotonic() - t0
    text = table(results, scene_list)
    n_fail = sum(r["verdict"] == "FAIL" for r in results)
    n_clear = sum(r["verdict"] == "clear" for r in results)
    summary = (f"{len(results)} runs: {len(results) - n_fail - n_clear} pass, "
               f"{n_clear} clear failures, {n_fail} FAIL; times are CPU seconds of each "
               f"run; this session {total:.0f} s wall ({args.jobs} at a time)\n")
    path = args.table or os.path.join(args.workdir, "extremes.md")
    with open(path, "w") as f:
        f.write(text + "\n" + summary)
    print("\n" + text + "\n" + summary, end="")
    sys.exit(1 if n_fail else 0)


if __name__ == "__main__":
    main()
