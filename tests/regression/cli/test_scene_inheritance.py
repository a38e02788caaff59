"""Scene inheritance and resolved scenes (params/README.md, Inheritance): a scene built on
another (`base = "..."`, two levels, a key overridden at each level) runs as the flat
scene with the same keys; `panoptic check` names the file that set each key; a cycle and a
missing base stop with exit 2 naming the chain or the path tried. A resolved scene, as
`panoptic check` prints it or as an output stores it (config_toml), re-runs without a
warning and reproduces the run bit for bit in every /snapshots dataset."""
import os
import subprocess

import h5py
import numpy as np

from common import REPO, Checks, parse_args, run_checked

FIDUCIAL = os.path.join(REPO, "params", "fiducial.toml")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


def run(exe, scene, out, *args, expect=0):
    return run_checked([exe, "run", scene, "-o", out, "--overwrite", *args], expect)


def snapshot_differences(a, b):
    """Names of the /snapshots datasets that differ in any bit between files a and b."""
    diffs = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        ga, gb = fa["snapshots"], fb["snapshots"]
        for name in sorted(set(ga) | set(gb)):
            if name not in ga or name not in gb:
                diffs.append(name)
                continue
            x, y = ga[name][()], gb[name][()]
            if x.shape != y.shape or x.tobytes() != y.tobytes():
                diffs.append(name)
    return diffs


def warnings_of(p):
    return [ln for ln in p.stderr.splitlines() if "warning" in ln]


def main():
    args = parse_args()
    c = Checks()
    w = args.workdir
    # fiducial <- cold (T_1au, alpha) <- variants/leaf (alpha again, a small fast grid)
    cold = write(f"{w}/cold.toml", f'base = "{FIDUCIAL}"\n[disk]\nT_1au = 150.0\n'
                 "alpha = 1e-4\n")
    leaf = write(f"{w}/variants/leaf.toml",
                 'base = "../cold.toml"   # relative to this file\n'
                 "[disk]\nalpha = 3e-4\n[grid]\nn_cells = 48\nstretch = 0.0\n"
                 "[output]\nt_end_yr = 3e4\nn_snapshots = 8\n")
    flat = write(f"{w}/flat.toml", open(FIDUCIAL).read().replace(
        "T_1au = 280.0", "T_1au = 150.0").replace("alpha = 1e-3", "alpha = 3e-4")
        .replace("n_cells = 350", "n_cells = 48").replace("stretch = 0.5", "stretch = 0.0")
        .replace("t_end_yr = 1e6", "t_end_yr = 3e4").replace("n_snapshots = 41",
                                                             "n_snapshots = 8"))
    p_leaf = run(args.exe, leaf, f"{w}/leaf.h5")
    run(args.exe, flat, f"{w}/flat.h5")
    d = snapshot_differences(f"{w}/leaf.h5", f"{w}/flat.h5")
    c.check(d == [], f"two levels of base: the run equals the flat scene's bit for bit "
            f"(differing: {d})")
    c.check(warnings_of(p_leaf) == [], f"no warning for the inherited scene "
            f"{warnings_of(p_leaf)}")

    p = run_checked([args.exe, "check", leaf])
    lines = {ln.split(" = ")[0]: ln for ln in p.stdout.splitlines() if " = " in ln}
    c.check(f"(from {FIDUCIAL})" in lines.get("sigma_1au", ""),
            f"check: sigma_1au from the grandparent: {lines.get('sigma_1au')!r}")
    c.check(f"(from {w}/cold.toml)" in lines.get("T_1au", ""),
            f"check: T_1au from the parent: {lines.get('T_1au')!r}")
    c.check("(from" not in lines.get("alpha", "(from") and
            lines.get("alpha", "").startswith("alpha = 3e-04"),
            f"check: alpha from the scene itself: {lines.get('alpha')!r}")

    # A resolved scene: printed by check (with --set), and stored in the output
    sets = ["--set", "disk.sigma_1au=2000", "--set", "disk.r_c_au=80"]
    p = run(args.exe, leaf, f"{w}/variant.h5", *sets)
    c.check(len(warnings_of(p)) == 1 and "disk.r_c_au" in warnings_of(p)[0],
            f"the --set of a key the run does not read is warned once: {warnings_of(p)}")
    resolved = write(f"{w}/resolved.toml",
                     run_checked([args.exe, "check", leaf, *sets]).stdout)
    with h5py.File(f"{w}/variant.h5", "r") as f:
        stored = write(f"{w}/stored.toml", f.attrs["config_toml"].decode()
                       if isinstance(f.attrs["config_toml"], bytes)
                       else f.attrs["config_toml"])
    for label, scene in [("panoptic check > x.toml", resolved),
                         ("config_toml of the output", stored)]:
        out = f"{w}/{os.path.basename(scene)}.h5"
        p = run(args.exe, scene, out)
        c.check(warnings_of(p) == [], f"{label}: re-runs without a warning "
                f"{warnings_of(p)[:2]}")
        d = snapshot_differences(f"{w}/variant.h5", out)
        c.check(d == [], f"{label}: the same run bit for bit (differing: {d})")

    # Refusals: a cycle, a missing base
    a = write(f"{w}/cycle/a.toml", 'base = "b.toml"\n')
    write(f"{w}/cycle/b.toml", 'base = "a.toml"\n[disk]\nalpha = 1e-4\n')
    p = subprocess.run([args.exe, "run", a], capture_output=True, text=True)
    chain = f"{w}/cycle/a.toml -> {w}/cycle/b.toml -> {w}/cycle/a.toml"
    c.check(p.returncode == 2 and chain in p.stderr,
            f"a cycle: exit {p.returncode}, the chain named: {p.stderr.strip()}")
    m = write(f"{w}/missing.toml", 'base = "nowhere/x.toml"\n')
    p = subprocess.run([args.exe, "check", m], capture_output=True, text=True)
    c.check(p.returncode == 2 and "base = \"nowhere/x.toml\"" in p.stderr and
            f"{w}/nowhere/x.toml" in p.stderr and "remove the base line" in p.stderr,
            f"a missing base: exit {p.returncode}, key, path tried and fix: "
            f"{p.stderr.strip()}")
    c.finish()


if __name__ == "__main__":
    main()
