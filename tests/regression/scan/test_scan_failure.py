"""A run that fails is isolated: in a scan of 4 runs, one fails with a solver error (its
step budget solver.max_steps is tiny), one crashes by SIGSEGV and one by SIGABRT (a
wrapper script stands in for panoptic with --run-exe and kills itself); the scan goes on,
the fourth run completes, and the summary records each failure with its error. A rerun
runs the failed ones again and skips the complete one. --task I runs one entry (job
arrays) and the command without --task then runs what is missing. A bad axis key or
value is refused before anything is written (exit 2, naming the key)."""
import csv
import os
import shutil
import stat

import h5py
import numpy as np

from common import Checks, parse_args, text
from scan_common import run_id, run_summary, run_summary_units, scan, summary, write_scan

WRAPPER = """#!/bin/sh
# a panoptic that crashes for two runs of the scan
case "$*" in
  *run_00002.h5*) kill -SEGV $$ ;;
  *run_00003.h5*) kill -ABRT $$ ;;
esac
exec "{exe}" "$@"
"""


def main():
    args = parse_args()
    c = Checks()
    out = f"{args.workdir}/scan"
    shutil.rmtree(out, ignore_errors=True)
    wrapper = f"{args.workdir}/crashing_panoptic.sh"
    with open(wrapper, "w") as f:
        f.write(WRAPPER.format(exe=os.path.abspath(args.exe)))
    os.chmod(wrapper, os.stat(wrapper).st_mode | stat.S_IXUSR)
    sf = write_scan(f"{args.workdir}/fail.toml", [
        'key = "star.mass_msun"\nvalues = [0.8, 1.0, 1.2, 1.4]\nzip = "a"',
        'key = "solver.max_steps"\nvalues = [2000000, 50, 2000000, 2000000]\nzip = "a"'])
    p = scan(args.exe, sf, out, "-j", "2", "--run-exe", wrapper, expect=3)
    print(p.stdout)
    s = summary(out)
    st, err, code = s["runs/status"], s["runs/error"], s["runs/exit_code"]
    c.check(list(st) == ["completed", "failed", "failed", "failed"],
            f"statuses {list(st)}; the scan exited 3 (some runs failed)")
    c.check(code[1] == 3 and "max_steps" in err[1], f"run 1: exit 3, error: {err[1][:100]}")
    c.check(code[2] == -11 and "signal 11" in err[2], f"run 2: SIGSEGV recorded: {err[2][:60]}")
    c.check(code[3] == -6 and "signal 6" in err[3], f"run 3: SIGABRT recorded: {err[3][:60]}")
    own = run_summary(f"{out}/runs/run_00000.h5")
    c.check(all(np.array_equal(s[f"outcome/{k}"][0], v, equal_nan=True) for k, v in own.items()),
            "the completed run's outcome is in the table")
    c.check(all(np.isnan(s["outcome/m_dust_final"][1:])), "no outcome for the failed runs")
    with h5py.File(f"{out}/summary.h5", "r") as f:
        units = {k: text(ds.attrs["units"]) for k, ds in f["outcome"].items()}
    own_units = {k: v for k, v in run_summary_units(f"{out}/runs/run_00000.h5").items()
                 if k in units}
    c.check(units["m_pl_coag"] == "M_earth" and units["t_first_pl_min"] == "yr" and
            units["r_max_pl_coag"] == "au" and
            all(units[k] == u for k, u in own_units.items()) and len(own_units) >= 9,
            f"/outcome/* carry the runs' /summary units ({len(own_units)} compared)")
    with open(f"{out}/summary.csv") as f:
        rows = f.read().splitlines()
    c.check(len(rows) == 5 and rows[2].split(",")[4] == "failed" and "max_steps" in rows[2],
            "summary.csv: a header and 4 rows; run 1 failed with its error")
    # every column of summary.csv under its own header: the numbers of the completed run
    # against summary.h5 (wall_s, steps and each outcome; the status and worker as text)
    with open(f"{out}/summary.csv", newline="") as f:
        recs = list(csv.DictReader(f))
    r0 = recs[0]
    same = (r0["status"] == "completed" and r0["exit_code"] == "0" and
            r0["worker"].startswith("local/") and
            float(r0["wall_s"]) == float(s["runs/wall_s"][0]) and
            float(r0["steps"]) == float(s["runs/steps"][0]) and s["runs/steps"][0] > 0 and
            s["runs/wall_s"][0] != s["runs/steps"][0])
    outs = [k for k in s if k.startswith("outcome/")]
    same = same and len(outs) >= 9 and all(
        np.isclose(float(r0[k[len("outcome/"):]]), s[k][0], rtol=1e-9, equal_nan=True)
        for k in outs)
    c.check(same, f"summary.csv run 0 = summary.h5 under every header ({len(outs)} outcomes, "
            f"wall_s {r0['wall_s']}, steps {r0['steps']})")
    # rerun: the complete run is skipped, the failed ones run again
    rid = run_id(f"{out}/runs/run_00000.h5")
    p = scan(args.exe, sf, out, "--run-exe", wrapper, expect=3)
    c.check("1 complete (checked), 3 to run" in p.stdout and
            run_id(f"{out}/runs/run_00000.h5") == rid, "rerun: the failed runs run again")
    # job arrays: --task I runs entry I alone; the command without --task collects
    arr = f"{args.workdir}/array"
    shutil.rmtree(arr, ignore_errors=True)
    p0 = scan(args.exe, sf, arr, "--task", "0", expect=0)
    p1 = scan(args.exe, sf, arr, "--task", "1", expect=3)
    p9 = scan(args.exe, sf, arr, "--task", "9", expect=2)
    ran = sorted(f for f in os.listdir(f"{arr}/runs") if f.endswith(".status"))
    c.check(ran == ["run_00000.status", "run_00001.status"] and "runs 0 to 3" in p9.stderr,
            f"--task 0 completed, --task 1 failed (exit 3), --task 9 refused; records: {ran}")
    p = scan(args.exe, sf, arr, expect=3)
    c.check("1 complete (checked), 3 to run" in p.stdout and
            list(summary(arr)["runs/status"]) == ["completed", "failed", "completed", "completed"],
            "collecting: the missing runs ran, the summary holds all four")
    # bad input: refused before anything is written
    for axis, what in [('key = "star.mass_msun"\nvalues = [1.0, -1.0]', "star.mass_msun = -1.0"),
                       ('key = "disk.alpah"\nvalues = [1e-3]', "did you mean disk.alpha")]:
        bad = f"{args.workdir}/bad_scan"
        shutil.rmtree(bad, ignore_errors=True)
        sfb = write_scan(f"{args.workdir}/bad.toml", [axis])
        p = scan(args.exe, sfb, bad, expect=2)
        c.check(what in p.stderr and not os.path.exists(bad),
                f"refused, nothing written: {p.stderr.strip().splitlines()[0][:150]}")
    c.finish()


main()
