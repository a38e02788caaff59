"""Edge cases of `panoptic scan` met on clusters:

- --force after a change of output.t_end_yr: the runs start again from t = 0 and equal, bit
  for bit, the runs of a new scan of the changed file (they were continued from the
  final checkpoints of the old end time: other snapshot times, a restart on record);
- --task with an empty value (an unset $SLURM_ARRAY_TASK_ID) is refused, not taken as
  "every run" (each task of a job array would run the whole scan into the same files), and
  an id too large for a long is refused with the value as given;
- an axis over a key that scan.set also fixes is refused with spaces around the key too;
- --run-exe that is not an executable file is refused before anything is written, and a
  run that cannot be executed records the command and the reason;
- -j far above the number of runs costs no memory per slot;
- SIGTERM to every process of the scan (a batch system ending the job) stops the runs
  under way with their checkpoints: the scan's forwarded SIGTERM is not taken by a run
  as a second signal that ends it at once."""
import glob
import os
import resource
import shutil
import signal
import subprocess
import time

import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, parse_args
from scan_common import scan, summary, write_scan

SETS = ["grid.n_cells=16", "output.t_first_yr=10.0", "output.n_snapshots=3"]
MASS = 'key = "star.mass_msun"\nvalues = [0.6, 1.3]'


def snapshots(h5):
    with open_output(h5) as f:
        return {k: ds[()] for k, ds in f["snapshots"].items()}, "restarts" in f.attrs


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    for d in glob.glob(f"{w}/*"):
        shutil.rmtree(d) if os.path.isdir(d) else os.remove(d)

    # 1 --force with a later end time: rerun from the start, as a new scan runs them
    sf = write_scan(f"{w}/short.toml", [MASS], sets=SETS + ["output.t_end_yr=100.0"])
    scan(args.exe, sf, f"{w}/forced")
    sf = write_scan(f"{w}/short.toml", [MASS], sets=SETS + ["output.t_end_yr=300.0"])
    p = scan(args.exe, sf, f"{w}/forced", "--force")
    scan(args.exe, sf, f"{w}/fresh")
    c.check("0 complete (checked), 2 to run" in p.stdout and
            (summary(f"{w}/forced")["runs/status"] == "completed").all(),
            "--force with t_end_yr 100 -> 300: both runs run again and complete")
    for name in ("run_00000", "run_00001"):
        a, restarted = snapshots(f"{w}/forced/runs/{name}.h5")
        b, _ = snapshots(f"{w}/fresh/runs/{name}.h5")
        same = sorted(a) == sorted(b) and all(
            a[k].shape == b[k].shape and np.array_equal(a[k], b[k], equal_nan=True) for k in b)
        c.check(same and not restarted,
                f"{name}: snapshot times {a['time']} (a new scan: {b['time']}), "
                f"every /snapshots dataset equal: {same}, continued from a checkpoint: "
                f"{restarted}")

    # 2 --task: an empty value and an id beyond a long are refused
    for bad, shown in [("", '--task "":'), ("99999999999999999999", '"99999999999999999999"'),
                       ("1.5", '"1.5"'), ("-1", '"-1"')]:
        out = f"{w}/task"
        shutil.rmtree(out, ignore_errors=True)
        p = scan(args.exe, sf, out, "--task", bad, expect=2)
        c.check(shown in p.stderr and "integer >= 0" in p.stderr and not os.path.exists(out),
                f"--task {bad!r} refused, nothing written: {p.stderr.strip()[:110]}")

    # 3 an axis also fixed in scan.set, written with spaces (--set reads ' star.mass_msun ')
    sfs = write_scan(f"{w}/both.toml", [MASS],
                     sets=SETS + ["output.t_end_yr=100.0", " star.mass_msun = 3.0"])
    p = scan(args.exe, sfs, f"{w}/both", expect=2)
    c.check("also fixed in scan.set" in p.stderr and not os.path.exists(f"{w}/both"),
            "axis and scan.set on one key (with spaces) refused: " + p.stderr.strip()[:100])

    # 4 --run-exe that cannot run
    p = scan(args.exe, sf, f"{w}/noexe", "--run-exe", f"{w}/no_such_panoptic", expect=2)
    c.check("--run-exe" in p.stderr and "no_such_panoptic" in p.stderr and
            not os.path.exists(f"{w}/noexe"),
            "--run-exe of no file refused, nothing written: " + p.stderr.strip()[:100])
    # one that is a file but cannot be executed (its interpreter is missing): the run's
    # error names it and why
    bad_exe = f"{w}/bad_interpreter.sh"
    with open(bad_exe, "w") as f:
        f.write("#!/no/such/interpreter\n")
    os.chmod(bad_exe, 0o755)
    scan(args.exe, sf, f"{w}/badexe", "--run-exe", bad_exe, "--task", "0", expect=127)
    err = open(f"{w}/badexe/runs/run_00000.status").read()
    c.check(f"cannot execute {bad_exe}: No such file or directory" in err,
            "a run that cannot be executed records the command and why: " +
            [l for l in err.splitlines() if l.startswith("error=")][0][:120])

    # 5 -j far above the number of runs: each start allocated a flag per slot (250 MB for
    # -j 2e9, and seconds per start); the memory of the scan and its runs stays small
    scan(args.exe, sf, f"{w}/many", "-j", "2000000000")
    rss_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    c.check((summary(f"{w}/many")["runs/status"] == "completed").all() and rss_mb < 150,
            f"-j 2000000000 over 2 runs: complete, largest process {rss_mb:.0f} MB")

    # 6 SIGTERM to every process of the scan, as a batch system ending the job sends it:
    # each run gets it directly and once more from the scan, which must not be the
    # "second signal" that ends a run at once; the runs under way checkpoint (exit 75)
    sft = write_scan(f"{w}/term.toml", ['key = "disk.alpha"\nlog = [1e-4, 1e-3]\nnum = 4'],
                     sets=["grid.n_cells=32", "output.t_end_yr=1e5", "output.t_first_yr=10.0",
                           "output.n_snapshots=12"])
    out = f"{w}/term"
    proc = subprocess.Popen([args.exe, "scan", sft, "-o", out, "-j", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    deadline = time.time() + 60
    while time.time() < deadline and proc.poll() is None and len(
            glob.glob(f"{out}/runs/*.h5")) < 2:
        time.sleep(0.01)
    time.sleep(0.3)
    os.killpg(proc.pid, signal.SIGTERM)
    text = proc.communicate(timeout=60)[0]
    s = summary(out)
    started = [(n, st, code) for n, st, code in
               zip(s["runs/name"], s["runs/status"], s["runs/exit_code"]) if st != "not run"]
    c.check(proc.returncode == 75 and len(started) >= 2 and
            all(st == "interrupted" and code == 75 for _, st, code in started),
            f"SIGTERM to the process group: scan exit {proc.returncode}, the runs under way "
            f"checkpointed (exit 75): {started}")
    if proc.returncode != 75:
        print(text)
    c.finish()


main()
