"""`cmake --install` (README, The two commands): the executable and the shipped scenes are
installed under a prefix, and the installed `panoptic`, found on PATH from a folder
outside the repository, checks every installed scene and runs one of them. The build
folder is the one holding the executable under test (--exe)."""
import glob
import os
import shutil
import subprocess

from common import Checks, parse_args, run_checked
from postprocess.reader import load_run


def main():
    args = parse_args()
    c = Checks()
    build = os.path.dirname(os.path.abspath(args.exe))
    prefix = os.path.join(os.path.abspath(args.workdir), "prefix")
    shutil.rmtree(prefix, ignore_errors=True)
    run_checked(["cmake", "--install", build, "--prefix", prefix])

    exe = os.path.join(prefix, "bin", "panoptic")
    share = os.path.join(prefix, "share", "panoptic", "params")
    c.check(os.access(exe, os.X_OK), f"installed executable {exe}")
    scenes = sorted(glob.glob(os.path.join(share, "*.toml")))
    names = [os.path.basename(s) for s in scenes]
    c.check("fiducial.toml" in names and "reference.toml" in names,
            f"installed scenes: {', '.join(names)}")
    c.check(not os.path.exists(os.path.join(share, "tests")),
            "the test scenes are not installed")

    # From PATH, in a folder outside the repository and the build.
    env = dict(os.environ, PATH=os.path.join(prefix, "bin") + os.pathsep + os.environ["PATH"])
    outside = os.path.join(os.path.abspath(args.workdir), "elsewhere")
    os.makedirs(outside, exist_ok=True)
    for scene in scenes:
        p = subprocess.run(["panoptic", "check", scene], capture_output=True, text=True,
                           env=env, cwd=outside)
        c.check(p.returncode == 0 and "grid:" in p.stdout,
                f"installed panoptic check {os.path.basename(scene)}: exit {p.returncode} "
                f"{p.stderr.strip() if p.returncode else ''}")
    for scan in sorted(glob.glob(os.path.join(share, "scans", "*.toml"))):
        p = subprocess.run(["panoptic", "scan", "--dry-run", scan], capture_output=True,
                           text=True, env=env, cwd=outside)
        c.check(p.returncode == 0,
                f"installed panoptic scan --dry-run {os.path.basename(scan)}: exit "
                f"{p.returncode} {p.stderr.strip() if p.returncode else ''}")

    out = os.path.join(outside, "fiducial_short.h5")
    p = subprocess.run(["panoptic", "run", os.path.join(share, "fiducial.toml"),
                        "--set", "grid.n_cells=40", "--set", "output.t_end_yr=1000",
                        "-o", out, "--overwrite"],
                       capture_output=True, text=True, env=env, cwd=outside)
    c.check(p.returncode == 0, f"installed panoptic run fiducial.toml: exit {p.returncode} "
            f"{p.stderr.strip() if p.returncode else ''}")
    if p.returncode == 0:
        run = load_run(out)
        c.check(abs(run.time[-1] - 1000.0) < 1e-9, f"the run reached {run.time[-1]} yr")
    c.finish()


if __name__ == "__main__":
    main()
