"""A scan killed with SIGKILL and run again completes: the runs complete before the kill
are skipped (the same file, run_id unchanged), the others run again, and no run of the
killed scan is left running (PR_SET_PDEATHSIG). "Complete" is checked, not assumed: a
truncated run file and one whose /solver status is not "completed" are run again. A
changed scan file is refused (exit 2) unless --force, which keeps the runs that still
match their manifest entry and reruns the others."""
import glob
import os
import shutil
import signal
import subprocess
import time

import h5py
import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args
from scan_common import run_id, scan, summary, write_scan

MASS = 'key = "star.mass_msun"\nvalues = [0.8, 1.2]'
ALPHA = 'key = "disk.alpha"\nlog = [1e-4, 1e-2]\nnum = 4'


def children_alive(out):
    """pids of processes whose command line names the scan directory."""
    pids = []
    for d in glob.glob("/proc/[0-9]*/cmdline"):
        try:
            with open(d, "rb") as f:
                if out.encode() in f.read():
                    pids.append(int(d.split("/")[2]))
        except OSError:
            pass
    return pids


def completed_status(out):
    n = 0
    for s in glob.glob(f"{out}/runs/*.status"):
        with open(s) as f:
            n += "outcome=completed" in f.read()
    return n


def complete_files(out):
    """Runs whose file is complete as `panoptic scan` checks it (/solver status
    "completed", a /summary): a run can end its file in the instant between its process's
    exit and its worker's .status line, so a kill there leaves a complete file that the
    .status files do not count, and the rerun (which checks the files) skips it."""
    names = []
    for p in glob.glob(f"{out}/runs/*.h5"):
        if p.endswith(".chk.h5"):
            continue
        try:
            with open_output(p) as f:
                st = f["solver"].attrs.get("status", b"")
                st = st.decode() if isinstance(st, bytes) else str(st)
                if st == "completed" and "summary" in f:
                    names.append(os.path.basename(p)[:-3])
        except (OSError, KeyError):
            pass
    return sorted(names)


def main():
    args = parse_args()
    c = Checks()
    out = f"{args.workdir}/scan"
    shutil.rmtree(out, ignore_errors=True)
    sf = write_scan(f"{args.workdir}/resume.toml", [ALPHA, MASS])
    # 1 start the scan with 2 workers and SIGKILL it once 2 runs are complete
    proc = subprocess.Popen([args.exe, "scan", sf, "-o", out, "-j", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    deadline = time.time() + 60
    while time.time() < deadline and proc.poll() is None and completed_status(out) < 2:
        time.sleep(0.01)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    time.sleep(0.1)  # the runs take 0.2-0.5 s: without PDEATHSIG some would be alive
    c.check(proc.returncode == -signal.SIGKILL, "the scan was killed mid-way")
    c.check(children_alive(out) == [], "no run of the killed scan is left running")
    c.check(os.path.exists(f"{out}/manifest.toml"), "the manifest was written before the runs")
    s = summary(out) if os.path.exists(f"{out}/summary.h5") else None
    c.check(s is None, "the killed scan wrote no summary (it is rebuilt by the rerun)")
    marked = sorted(os.path.basename(p)[:-7] for p in glob.glob(f"{out}/runs/*.status")
                    if "outcome=completed" in open(p).read())
    done = complete_files(out)
    c.check(set(marked) <= set(done),
            f"every run its .status calls completed has a complete file: {marked}, {done}")
    c.check(2 <= len(done) < 8, f"{len(done)} of 8 runs were complete at the kill: {done}")
    ids = {n: run_id(f"{out}/runs/{n}.h5") for n in done}
    # 2 the same command again completes the scan, skipping the complete runs
    p = scan(args.exe, sf, out, "-j", "2")
    print(p.stdout)
    c.check(f"{len(done)} complete (checked), {8 - len(done)} to run" in p.stdout,
            "the rerun found the complete runs and runs the rest")
    s = summary(out)
    c.check((s["runs/status"] == "completed").all() and len(s["runs/status"]) == 8,
            "after the rerun every run is complete")
    c.check(all(run_id(f"{out}/runs/{n}.h5") == ids[n] for n in done),
            "the runs complete before the kill were not run again (same run_id)")
    # 3 complete is checked: a truncated file and a file not marked completed run again
    names = list(s["runs/name"])
    trunc, unmarked, kept = names[1], names[2], names[3]
    ids = {n: run_id(f"{out}/runs/{n}.h5") for n in names}
    before = {k: v[2] for k, v in s.items() if k.startswith("outcome/")}
    with open(f"{out}/runs/{trunc}.h5", "r+b") as f:
        f.truncate(os.path.getsize(f"{out}/runs/{trunc}.h5") // 2)
    with h5py.File(f"{out}/runs/{unmarked}.h5", "r+") as f:
        f["solver"].attrs["status"] = np.bytes_("stopped by SIGTERM")
    p = scan(args.exe, sf, out)
    c.check("6 complete (checked), 2 to run" in p.stdout, "a truncated and an unmarked file: 2 to run")
    s = summary(out)
    c.check((s["runs/status"] == "completed").all(), "complete again")
    # (the unmarked file's checkpoint is the final one, at t_end: panoptic run refuses to
    # continue from it (exit 2), so the scan runs it from the start)
    c.check(run_id(f"{out}/runs/{trunc}.h5") != ids[trunc]
            and run_id(f"{out}/runs/{unmarked}.h5") != ids[unmarked]
            and run_id(f"{out}/runs/{kept}.h5") == ids[kept], "exactly those two were rerun")
    c.check(all(np.array_equal(before[k], s[k][2], equal_nan=True) for k in before),
            "the rerun's outcome is the same bit for bit")
    # 3b SIGTERM stops the scan: the runs under way checkpoint, the summary says
    # interrupted, exit 75; the rerun continues them from their checkpoints. The runs last
    # 1.2-1.9 s (alpha 1e-4 .. 1e-3, to 1e5 yr), so the first two are surely mid-run 0.3 s
    # after their files appear (to 2e3 yr they took 0.3 s and could probably all finish
    # first once the code got faster: one failure of this test under ctest -j2, not
    # reproduced alone)
    out2 = f"{args.workdir}/scan_term"
    shutil.rmtree(out2, ignore_errors=True)
    sf2 = write_scan(f"{args.workdir}/term.toml", [ALPHA], sets=[
        "grid.n_cells=32", "output.t_end_yr=1e5", "output.t_first_yr=10.0",
        "output.n_snapshots=12"])
    proc = subprocess.Popen([args.exe, "scan", sf2, "-o", out2, "-j", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 60
    while time.time() < deadline and proc.poll() is None and len(
            glob.glob(f"{out2}/runs/*.h5")) < 2:
        time.sleep(0.01)
    time.sleep(0.3)
    proc.send_signal(signal.SIGTERM)
    text = proc.communicate(timeout=60)[0]
    s2 = summary(out2)
    stopped = [n for n, st in zip(s2["runs/name"], s2["runs/status"]) if st == "interrupted"]
    c.check(proc.returncode == 75 and len(stopped) >= 1,
            f"SIGTERM: exit {proc.returncode}, interrupted: {stopped}")
    c.check(all(os.path.exists(f"{out2}/runs/{n}.chk.h5") for n in stopped),
            "the interrupted runs are checkpointed")
    # 4 runs on 2 workers stopped early: those not started have no exit code (NaN in
    # summary.h5, an empty field in summary.csv), not 0, which means success
    not_run = s2["runs/status"] == "not run"
    with open(f"{out2}/summary.csv") as f:
        rows = [r.split(",") for r in f.read().splitlines()]
    col = rows[0].index("exit_code")
    c.check(not_run.any() and np.all(np.isnan(s2["runs/exit_code"][not_run])) and
            all(rows[1 + i][col] == "" for i in np.flatnonzero(not_run)) and
            all(s2["runs/exit_code"][s2["runs/status"] == "interrupted"] == 75),
            f"exit codes: not run NaN, interrupted 75: "
            f"{list(zip(s2['runs/status'], s2['runs/exit_code']))}")
    p = scan(args.exe, sf2, out2, "-j", "2")
    s2 = summary(out2)
    ok = (s2["runs/status"] == "completed").all()
    for n in stopped:
        with open_output(f"{out2}/runs/{n}.h5") as f:
            ok &= "restarts" in f.attrs
    c.check(ok, "rerun: complete, the interrupted runs continued from their checkpoints")
    if not ok:
        print(text, p.stdout)
    # 4 a changed scan file is refused; --force keeps the runs that still match
    write_scan(sf, [ALPHA, 'key = "star.mass_msun"\nvalues = [0.8, 1.3]'])
    p = scan(args.exe, sf, out, expect=2)
    c.check("another manifest" in p.stderr and "--force" in p.stderr and "star.mass_msun=1.3" in p.stderr,
            "changed scan refused: " + p.stderr.strip().splitlines()[0][:160])
    ids = {n: run_id(f"{out}/runs/{n}.h5") for n in names}
    p = scan(args.exe, sf, out, "--force")
    c.check("4 complete (checked), 4 to run" in p.stdout, "--force: the 4 runs of mass 0.8 kept")
    s = summary(out)
    c.check((s["runs/status"] == "completed").all(), "complete after --force")
    ok = True
    for i, n in enumerate(names):
        with open_output(f"{out}/runs/{n}.h5") as f:
            cfg = f.attrs["config_toml"]
            cfg = cfg.decode() if isinstance(cfg, bytes) else cfg
        m = s["axes/star.mass_msun"][i]
        ok &= f"mass_msun = {m}" in cfg
        ok &= (run_id(f"{out}/runs/{n}.h5") == ids[n]) == (m == 0.8)
    c.check(ok, "every run file holds its manifest entry's scene; only mass 1.3 was rerun")
    c.finish()


main()
