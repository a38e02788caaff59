"""`mpirun --oversubscribe -n 3 panoptic scan` over 8 runs gives the same summary table as
the serial scan: every axis value, status, CVODE step count and /summary outcome equal
bit for bit, and each equal to the run's own file; the runs were spread over more than
one rank. An I/O error on one rank (a run's status record cannot be written) ends the
whole job with the error, instead of leaving the other ranks waiting for it until the
batch system's time limit. Exits 77 (skipped) when panoptic is built without MPI or
mpirun is missing."""
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

from common import Checks, parse_args
from scan_common import run_summary, scan, summary, write_scan


def main():
    args = parse_args()
    version = subprocess.run([args.exe, "--version"], capture_output=True, text=True).stdout
    if "with MPI" not in version or shutil.which("mpirun") is None:
        print(f"SKIP: no MPI ({version.strip()}; mpirun: {shutil.which('mpirun')})")
        sys.exit(77)
    c = Checks()
    sf = write_scan(f"{args.workdir}/mpi.toml", [
        'key = "disk.alpha"\nlog = [1e-4, 1e-2]\nnum = 4',
        'key = "star.mass_msun"\nvalues = [0.7, 1.4]'])
    serial, par = f"{args.workdir}/serial", f"{args.workdir}/mpi"
    for d in (serial, par):
        shutil.rmtree(d, ignore_errors=True)
    scan(args.exe, sf, serial)
    p = scan(args.exe, sf, par, mpi=3)
    print(p.stdout)
    a, b = summary(serial), summary(par)
    c.check(len(a["runs/id"]) == 8 and (a["runs/status"] == "completed").all(),
            "serial: 8 runs, all completed")
    c.check((b["runs/status"] == "completed").all(), "mpi: all completed")
    c.check(sorted(a) == sorted(b), "the same columns")
    same = [k for k in a if not k.startswith(("runs/wall_s", "runs/worker"))]
    for k in same:
        equal = np.array_equal(a[k], b[k], equal_nan=a[k].dtype.kind == "f")
        c.check(equal, f"{k} equal (serial {a[k][:3]}..., mpi {b[k][:3]}...)")
    ranks = sorted(set(w.split("/")[0] for w in b["runs/worker"]))
    c.check(len(ranks) >= 2, f"runs were spread over ranks {ranks}")
    c.check(set(a["runs/worker"]) == {"local/0"}, "serial: one local worker")
    # the table holds what the run files hold
    for i, name in enumerate(b["runs/name"]):
        own = run_summary(f"{par}/runs/{name}.h5")
        ok = all(np.array_equal(b[f"outcome/{k}"][i], v, equal_nan=True) for k, v in own.items())
        c.check(ok and len(own) >= 10, f"{name}: table = its file's /summary ({len(own)} values)")
    c.check(np.count_nonzero(b["outcome/m_pl_coag"] > 1e-3) >= 4,
            "planetesimals formed in at least half of the runs (the outcome is not trivial)")
    # postprocess: a map for the two axes, lines for one
    from postprocess import plot_scan
    p = subprocess.run([sys.executable, "-m", "postprocess.plot_scan", par], capture_output=True,
                       text=True)
    maps = p.stdout.split()
    c.check(p.returncode == 0 and len(maps) == 6 and all(os.path.getsize(m) > 10000 for m in maps),
            f"plot_scan: {len(maps)} maps written")
    p = subprocess.run([sys.executable, "-m", "postprocess.plot_scan", par, "--axes", "disk.alpha"],
                       capture_output=True, text=True)
    c.check(p.returncode == 0 and p.stdout.strip().endswith("lines_disk.alpha.png"),
            "plot_scan --axes disk.alpha: line plot written")
    s = plot_scan.load_summary(par)
    x, y = s["axes"]["disk.alpha"][0], s["axes"]["star.mass_msun"][0]
    xs, ys, Z = plot_scan.grid_map(x, y, s["outcome"]["m_pl_coag"])
    ok = Z.shape == (2, 4) and all(Z[list(ys).index(y[i]), list(xs).index(x[i])] ==
                                   b["outcome/m_pl_coag"][i] for i in range(8))
    c.check(ok, "the map's cells hold each run's value at its (alpha, mass)")
    # an error on a rank ends the job: run_00001.status cannot be written (a directory
    # stands in its place), whichever rank runs it
    bad = f"{args.workdir}/io_error"
    shutil.rmtree(bad, ignore_errors=True)
    os.makedirs(f"{bad}/runs/run_00001.status/x")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.Popen(["mpirun", "--oversubscribe", "-n", "2", args.exe, "scan", sf,
                             "-o", bad], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, env=env, start_new_session=True)
    t0 = time.time()
    try:
        text = proc.communicate(timeout=60)[0]
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        text = proc.communicate()[0] + "\n(killed after 60 s: the job hung)"
    c.check(proc.returncode not in (0, -signal.SIGKILL) and "run_00001.status" in text,
            f"an I/O error on a rank ends the job in {time.time() - t0:.1f} s, exit "
            f"{proc.returncode}: {[l for l in text.splitlines() if 'panoptic: error' in l][:1]}")
    c.finish()


main()
