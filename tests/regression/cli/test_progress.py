"""Progress in logs (src/run/README.md, Progress): with `--progress INTERVAL`, or
PANOPTIC_PROGRESS in the environment, a run whose stdout is not a terminal prints one line
per interval of wall time with the simulated time, its share of the run, the steps, the
wall time and the ETA; without either it prints none, as before. `panoptic scan
--progress` passes the option to its runs, whose logs then hold the lines. A malformed
interval is refused (exit 2) naming where it came from."""
import os
import re
import subprocess

from common import REPO, Checks, parse_args

FIDUCIAL = os.path.join(REPO, "params", "fiducial.toml")
SETS = ["--set", "grid.n_cells=48", "--set", "grid.stretch=0", "--set",
        "output.t_end_yr=3e4"]
LINE = re.compile(r"^progress: t = (\S+) yr \((\S+) %\), (\d+) steps, wall (\S+) s, "
                  r"ETA (\S+ s|unknown)$")


def progress_lines(text):
    return [LINE.match(ln) for ln in text.splitlines() if ln.startswith("progress:")]


def check_lines(c, label, text, interval):
    lines = progress_lines(text)
    ok = len(lines) >= 3 and all(lines)
    if ok:
        t = [float(m.group(1)) for m in lines]
        steps = [int(m.group(3)) for m in lines]
        wall = [float(m.group(4)) for m in lines]
        share = [float(m.group(2)) for m in lines]
        # the share is printed to 0.1 %: a line in the run's first 0.05 % (a loaded
        # machine reaches the first interval before that) truly reads 0.0 %
        ok = (t == sorted(t) and steps == sorted(steps) and share == sorted(share) and
              all(b - a >= interval - 0.011 for a, b in zip(wall, wall[1:])) and
              all(0 <= x <= 100 for x in share) and share[-1] > 0)
    c.check(ok, f"{label}: {len(lines)} lines, well formed, time, steps, share and wall rising "
            f"by >= {interval} s (to the printed digits): {[m.group(0) if m else None for m in lines[:2]]}")


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    run = [args.exe, "run", FIDUCIAL, *SETS, "-o", f"{w}/p.h5", "--overwrite"]
    env = {k: v for k, v in os.environ.items() if k != "PANOPTIC_PROGRESS"}

    p = subprocess.run(run + ["--progress", "0.05"], capture_output=True, text=True,
                       env=env)
    c.check(p.returncode == 0, f"--progress 0.05: exit {p.returncode}")
    check_lines(c, "--progress 0.05 (stdout a pipe)", p.stdout, 0.05)
    p = subprocess.run(run, capture_output=True, text=True,
                       env=dict(env, PANOPTIC_PROGRESS="0.05"))
    check_lines(c, "PANOPTIC_PROGRESS=0.05", p.stdout, 0.05)
    p = subprocess.run(run, capture_output=True, text=True, env=env)
    c.check(p.returncode == 0 and not progress_lines(p.stdout),
            "neither: no progress line in the log")
    for given, extra, e in [("--progress 1x", ["--progress", "1x"], env),
                            ("PANOPTIC_PROGRESS=soon", [],
                             dict(env, PANOPTIC_PROGRESS="soon"))]:
        p = subprocess.run(run + extra, capture_output=True, text=True, env=e)
        where = given.split("=")[0].split(" ")[0]
        c.check(p.returncode == 2 and where in p.stderr and "not a duration" in p.stderr,
                f"{given}: exit {p.returncode}, {p.stderr.strip()[:120]}")

    # a scan passes --progress to its runs' logs
    scan = os.path.join(w, "scan.toml")
    with open(scan, "w") as f:
        f.write(f'[scan]\nscene = "{FIDUCIAL}"\nset = ["grid.n_cells=48", '
                '"grid.stretch=0", "output.t_end_yr=3e4"]\n'
                '[[axis]]\nkey = "disk.alpha"\nvalues = [1e-3, 3e-4]\n')
    p = subprocess.run([args.exe, "scan", scan, "-o", f"{w}/scan", "--force",
                        "--progress", "0.05"], capture_output=True, text=True, env=env)
    logs = sorted(f for f in os.listdir(f"{w}/scan/runs") if f.endswith(".log"))
    c.check(p.returncode == 0 and len(logs) == 2, f"scan --progress: exit {p.returncode}, "
            f"logs {logs} {p.stderr.strip()[:200]}")
    for log in logs:
        with open(f"{w}/scan/runs/{log}") as f:
            check_lines(c, f"scan run log {log}", f.read(), 0.05)
    c.finish()


if __name__ == "__main__":
    main()
