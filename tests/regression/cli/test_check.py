"""`panoptic check SCENE` (params/README.md, "Scenes"): every shipped scene passes and prints the run
it would make (grid, gas disk, state layout); the gas between r_in and r_out against the
closed forms of the MMSN and LBP profiles; the snow line is reported where it falls,
and said to be off the grid when T = T_sub lies beyond the outer or inside the inner edge
(a warm disk printed "snow line at 13840.8 au" as if the run had one)."""
import glob
import math
import os
import subprocess

from common import REPO, Checks, parse_args


def check(exe, scene, *sets):
    cmd = [exe, "check", scene]
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, capture_output=True, text=True)


def gas_line(p):
    return next((ln for ln in p.stdout.splitlines() if "gas disk:" in ln), "")


def main():
    args = parse_args()
    c = Checks()

    scenes = sorted(glob.glob(os.path.join(REPO, "params", "*.toml")) +
                    glob.glob(os.path.join(REPO, "params", "tests", "*.toml")))
    c.check(len(scenes) >= 10, f"{len(scenes)} scenes found in params/ and params/tests/")
    for scene in scenes:
        p = check(args.exe, scene)
        name = os.path.relpath(scene, REPO)
        c.check(p.returncode == 0 and "grid:" in p.stdout and "state:" in p.stdout and
                gas_line(p) != "",
                f"check {name}: exit {p.returncode}, prints grid, gas disk and state "
                f"{p.stderr.strip()}")

    fiducial = os.path.join(REPO, "params", "fiducial.toml")
    # spec §1.7: T = T_1au r^-q = T_sub at r = (T_1au / T_sub)^(1/q)
    cases = [
        ("on the grid", [], (280.0 / 170.0) ** 2, ""),
        ("beyond the outer edge (300 au)", ["disk.T_1au=5000"], (5000.0 / 170.0) ** 2,
         "(beyond the outer edge: all silicate on the grid)"),
        ("inside the inner edge (5 au)", ["grid.r_in_au=5"], (280.0 / 170.0) ** 2,
         "(inside the inner edge: all ice on the grid)"),
    ]
    for label, sets, r_snow, note in cases:
        line = gas_line(check(args.exe, fiducial, *sets))
        shown = line.split("snow line at ")[-1].split(" au")[0] if "snow line at" in line \
            else "nan"
        ok = abs(float(shown) / r_snow - 1) < 5e-6
        c.check(ok and (note in line if note else "(" not in line.split("snow line")[-1]),
                f"snow line {label}: {line.strip()!r} (expected {r_snow:.6g} au "
                f"{note or 'with no note'})")
    # the profile's gas between r_in and r_out, in closed form (spec §1.2): MMSN
    # 2 pi Sigma_1 au^2 2 (sqrt(r_out) - sqrt(r_in)) with r in au; LBP (gamma = 1)
    # M_disk (e^(-r_in/r_c) - e^(-r_out/r_c)), its share of M_disk in %
    msun, au = 1.989e33, 1.496e13
    lbp_share = math.exp(-1.0 / 60.0) - math.exp(-1000.0 / 60.0)
    for scene, mass, share in [
            ("fiducial.toml", 2 * math.pi * 1700 * au**2 * 2 * (math.sqrt(300) - 1) / msun,
             None),
            ("compact_fragmentation.toml", 0.05 * lbp_share, 100 * lbp_share)]:
        line = gas_line(check(args.exe, os.path.join(REPO, "params", scene)))
        shown = float(line.split(" M_sun between")[0].split(", ")[-1])
        ok = abs(shown / mass - 1) < 1e-5
        if share is not None:
            pct = float(line.split("(")[1].split(" %")[0])
            ok = ok and abs(pct / share - 1) < 1e-5
        c.check(ok, f"{scene}: gas between r_in and r_out {line.strip()!r} "
                f"(closed form {mass:.6g} M_sun{f', {share:.6g} %' if share else ''})")
    for label, sets, text in [
            ("off", ["snowline.enabled=false"], "snow line off"),
            ("q = 0, colder than T_sub", ["disk.q=0", "disk.T_1au=100"],
             "no snow line: colder than disk.T_sub everywhere (all ice)"),
            ("q = 0, warmer than T_sub", ["disk.q=0", "disk.T_1au=200"],
             "no snow line: warmer than disk.T_sub everywhere (all silicate)")]:
        line = gas_line(check(args.exe, fiducial, *sets))
        c.check(text in line, f"snow line {label}: {line.strip()!r}")
    # log-spaced snapshots between equal ends: one snapshot, said in the header
    for sets, warned in ((["output.t_end_yr=100"], True),
                         (["output.t_end_yr=100", "output.n_snapshots=1"], False),
                         (["output.t_end_yr=200"], False)):
        p = check(args.exe, fiducial, *sets)
        said = "WARNING: output.n_snapshots" in p.stdout
        c.check(p.returncode == 0 and said == warned,
                f"{' '.join(sets)} (t_first_yr = 100): exit {p.returncode}, "
                f"one-snapshot warning {'printed' if said else 'not printed'}")
    c.finish()


if __name__ == "__main__":
    main()
