"""`import panoptic` as a user gets it: the package installed with Debian's pip into a
virtual environment, from a clean copy of the repository, used from a directory outside
it (issue 36, "Must show").

Makes a venv with --system-site-packages (numpy, h5py, matplotlib, pandas from Debian),
`pip install --no-build-isolation --no-index` the postprocess/ folder of `git archive
HEAD` (nothing from PyPI), then, in a directory outside the repository and with the
venv's python: import panoptic (from the venv, not the checkout), panoptic.run of a tiny
scene, load_run, a 2-run scan with `panoptic scan` read by load_scan as a DataFrame, a
two-run overlay figure saved as PDF, and the console scripts panoptic-plot (PDF),
panoptic-plot-scan --log (SVG) and panoptic-model-error.

    PYTHONPATH=.:tests/regression /usr/bin/python3 tests/python/test_install.py \
        --exe build/panoptic --workdir DIR
"""
import os
import shutil
import subprocess
import sys
import textwrap
import time

from common import REPO, Checks, parse_args  # noqa: E402

PYTHON = "/usr/bin/python3"    # Debian's, with python3-venv and python3-pip

USER_SCRIPT = r'''
import os, sys
import panoptic
exe, scene, work = sys.argv[1:4]
print("panoptic from", panoptic.__file__)
assert os.path.realpath(panoptic.__file__).startswith(os.path.realpath(sys.prefix)), panoptic.__file__
tiny = {"grid.n_cells": 16, "output.t_end_yr": 300.0, "output.n_snapshots": 4}
a = panoptic.run(scene, set=tiny, out=os.path.join(work, "a.h5"), exe=exe)
b = panoptic.run(scene, set={**tiny, "disk.alpha": 1e-4}, out=os.path.join(work, "b.h5"), exe=exe)
a = panoptic.load_run(os.path.join(work, "a.h5"))
t, m = a.planetesimal_mass()
print(f"load_run: {a}; m_pl(t_end) = {m[-1]:.4g} M_earth")
assert a.finished and a.n_snapshots == 5 and b.config["disk"]["alpha"] == 1e-4
df = panoptic.load_scan(os.path.join(work, "scan"))
print(df[["name", "status", "star.mass_msun", "m_dust_final"]].to_string())
assert len(df) == 2 and list(df["status"]) == ["completed"] * 2, df
assert all(os.path.isfile(p) for p in df["path"]), df["path"]
assert df.attrs["units"]["m_dust_final"] == "M_earth" and df.attrs["units"]["star.mass_msun"] == "M_sun"
fig = panoptic.overlay_profiles([a, b], "sigma_d", labels=["alpha 1e-3", "alpha 1e-4"])
fig.savefig(os.path.join(work, "overlay.pdf"))
with open(os.path.join(work, "overlay.pdf"), "rb") as f:
    assert f.read(5) == b"%PDF-"
print("overlay.pdf written")
'''


def sh(cmd, cwd=None, env=None, timeout=120):
    """Run cmd; (returncode, stdout + stderr). Prints its wall time."""
    t0 = time.time()
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    print(f"  [{time.time() - t0:5.1f} s] {os.path.basename(cmd[0])} {' '.join(cmd[1:4])}")
    return p.returncode, p.stdout + p.stderr


def clean_copy(dest):
    """postprocess/ and params/ of the checkout's HEAD (git archive), else of the tree."""
    if os.path.isdir(os.path.join(REPO, ".git")) or os.path.isfile(os.path.join(REPO, ".git")):
        archive = subprocess.run(["git", "-C", REPO, "archive", "--format=tar", "HEAD",
                                  "postprocess", "params"], capture_output=True)
        if archive.returncode == 0:
            os.makedirs(dest)
            subprocess.run(["tar", "-x", "-C", dest], input=archive.stdout, check=True)
            return "git archive HEAD"
    for folder in ("postprocess", "params"):
        shutil.copytree(os.path.join(REPO, folder), os.path.join(dest, folder),
                        ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    return "a copy of the tree (no git)"


def main():
    args = parse_args()
    c = Checks()
    start = time.time()
    work = os.path.realpath(args.workdir)
    for name in ("src", "venv", "user"):
        shutil.rmtree(os.path.join(work, name), ignore_errors=True)
    src, venv, user = (os.path.join(work, n) for n in ("src", "venv", "user"))
    how = clean_copy(src)
    c.check(os.path.isfile(os.path.join(src, "postprocess", "pyproject.toml")),
            f"a clean copy of postprocess/ ({how})")

    # --without-pip: the venv sees Debian's pip through --system-site-packages, and
    # `venv/bin/python -m pip` installs into the venv (ensurepip would add ~3 s)
    rc, out = sh([PYTHON, "-m", "venv", "--system-site-packages", "--without-pip", venv])
    c.check(rc == 0, f"python3 -m venv --system-site-packages {out.strip()[-200:]}")
    pip = [os.path.join(venv, "bin", "python"), "-m", "pip"]
    # only what Debian installed: no index, no local wheel folders of this machine
    pip_env = {k: v for k, v in os.environ.items() if k != "PIP_FIND_LINKS"}
    rc, out = sh([*pip, "install", "--no-build-isolation", "--no-index",
                  os.path.join(src, "postprocess")], env=pip_env, timeout=300)
    c.check(rc == 0 and "Successfully installed panoptic" in out,
            "pip install --no-build-isolation --no-index ./postprocess (no PyPI): "
            + (out.strip().splitlines()[-1] if out.strip() else ""))
    if rc != 0:
        print(out)
        c.finish()

    # the scan first (with the build's executable), then everything else from the venv
    os.makedirs(user)
    scene = os.path.join(src, "params", "fiducial.toml")
    scan_file = os.path.join(user, "scan.toml")
    with open(scan_file, "w") as f:
        f.write(textwrap.dedent(f"""\
            [scan]
            scene = "{scene}"
            set = ["grid.n_cells=16", "output.t_end_yr=300.0", "output.n_snapshots=4"]
            sampling = "grid"
            [[axis]]
            key = "star.mass_msun"
            values = [0.8, 1.0]
            """))
    rc, out = sh([args.exe, "scan", scan_file, "-o", os.path.join(user, "scan"), "-j", "1"])
    c.check(rc == 0, "panoptic scan of 2 tiny runs")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PATH"] = os.path.join(venv, "bin") + os.pathsep + env.get("PATH", "")
    script = os.path.join(user, "user.py")
    with open(script, "w") as f:
        f.write(USER_SCRIPT)
    rc, out = sh([os.path.join(venv, "bin", "python"), script, args.exe, scene, user],
                 cwd=user, env=env)
    print(textwrap.indent(out.rstrip(), "    "))
    c.check(rc == 0 and "overlay.pdf written" in out and "site-packages" in out,
            "from outside the repository: import panoptic (the venv's), panoptic.run, "
            "load_run, load_scan -> DataFrame, a two-run overlay saved as PDF")

    plot_dir = os.path.join(user, "a_plots")
    rc, out = sh([os.path.join(venv, "bin", "panoptic-plot-profiles"),
                  os.path.join(user, "a.h5"), "-o", plot_dir, "--format", "pdf", "--no-footer"],
                 cwd=user, env=env)
    pdfs = sorted(n for n in os.listdir(plot_dir) if n.endswith(".pdf")) if rc == 0 else []
    c.check(rc == 0 and pdfs == ["dust_to_gas.pdf", "sigma_d.pdf"],
            f"panoptic-plot-profiles --format pdf: {pdfs}")
    rc, out = sh([os.path.join(venv, "bin", "panoptic-plot"), "--help"], cwd=user, env=env)
    c.check(rc == 0 and "--no-footer" in out, "panoptic-plot is installed")
    rc, out = sh([os.path.join(venv, "bin", "panoptic-plot-scan"), os.path.join(user, "scan"),
                  "--log", "star.mass_msun", "--format", "svg"], cwd=user, env=env)
    c.check(rc == 0 and out.strip().endswith(".svg"), f"panoptic-plot-scan --log --format svg: "
            f"{out.strip().splitlines()[-1] if out.strip() else ''}")
    c.check(os.access(os.path.join(venv, "bin", "panoptic-plot-observe"), os.X_OK),
            "panoptic-plot-observe is installed")
    rc, out = sh([os.path.join(venv, "bin", "panoptic-model-error"), os.path.join(user, "b.h5"),
                  os.path.join(user, "a.h5")], cwd=user, env=env)
    c.check(rc == 0 and "sigma_d_l1" in out and "disk.alpha" in out,
            "panoptic-model-error b.h5 a.h5: the tables, and the alpha difference warned about")
    wall = time.time() - start
    print(f"wall time {wall:.1f} s")
    c.check(wall < 120, f"the whole install test took {wall:.0f} s")
    c.finish()


if __name__ == "__main__":
    sys.exit(main())
