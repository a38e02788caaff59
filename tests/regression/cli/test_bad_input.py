"""Each class of bad input gives one clear message (file:line, key, value, constraint, fix),
exit code 2, and no output file; an unwritable output gives exit code 4; --help and
--version exit 0."""
import os
import subprocess

from common import REPO, Checks, parse_args

GOOD = open(os.path.join(REPO, "params/fiducial.toml")).read()


def edit(old, new):
    """The good scene with `old` replaced by `new`; `old` must be in it (else the case
    would run the good scene and test nothing)."""
    assert old in GOOD, f"{old!r} not in params/fiducial.toml: update this test"
    return GOOD.replace(old, new)


# (label, scene text or None for the good scene, extra CLI args, strings the message must hold)
CASES = [
    ("unknown key", edit("n_cells = 350", "n_cell = 350"),
     [], ["n_cell", ":", "grid.n_cells"]),
    ("wrong type", edit("n_cells = 350", 'n_cells = "many"'),
     [], ["grid.n_cells", "many"]),
    ("out of range", edit("r_in_au = 1.0 ", "r_in_au = -1.0 "),
     [], ["grid.r_in_au", "-1", "> 0"]),
    ("inconsistent r_in >= r_out", edit("r_in_au = 1.0 ", "r_in_au = 500.0 "),
     [], ["grid.r_in_au", "500", "r_out"]),
    ("unknown choice", edit('model = "powerlaw"', 'model = "mmsn2"'),
     [], ["disk.model", "mmsn2", "powerlaw", "lbp"]),
    ("malformed TOML", edit("[grid]", "[grid"),
     [], [":"]),
    ("binary garbage", "\x00\xff\xfe[[[\x01=\n", [], ["toml"]),
    ("bad --set key", None, ["--set", "grid.n_celz=10"], ["grid.n_celz", "--set"]),
    ("bad --set value", None, ["--set", "solver.rtol=-1"], ["solver.rtol", "-1"]),
    ("--set without =", None, ["--set", "solver.rtol"], ["solver.rtol"]),
    ("unknown CLI option", None, ["--frobnicate"], ["frobnicate"]),
    # material and gas constants beyond any real one (disk.mu = 1e308 passed check and
    # stopped the run with a Newton failure at t = 0, exit 3; a Young's modulus of 1e308
    # ran to exit 0 with E* = inf)
    ("gas heavier than any", None, ["--set", "disk.mu=1e308"],
     ["disk.mu", "1e308", "<= 100"]),
    ("a modulus beyond diamond's", None, ["--set", "material.ice_youngs_gpa=1e308"],
     ["material.ice_youngs_gpa", "1e308", "<= 10000", "GPa"]),
    # a star, a disk and a dust content no disk has (dust_to_gas = 1e30 and sigma_1au =
    # 1e30 stopped in CVODE with exit 3, star.mass_msun = 1e-30 ran to exit 0)
    ("a pebble radius twice", None, ["--set", "pebbles.radii_au=[3, 10, 3]"],
     ["pebbles.radii_au", "lists 3 [au] twice", "remove one"]),
    ("more dust than gas", None, ["--set", "dust.dust_to_gas=2"],
     ["dust.dust_to_gas", "2", "<= 1"]),
    ("a star lighter than a brown dwarf", None, ["--set", "star.mass_msun=1e-30"],
     ["star.mass_msun", "1e-30", ">= 0.01", "M_sun"]),
    ("a disk heavier than any", None, ["--set", "disk.sigma_1au=1e30"],
     ["disk.sigma_1au", "1e30", "<= 1e+06", "g cm^-2"]),
    ("a disk near absolute zero", None, ["--set", "disk.T_1au=1e-9"],
     ["disk.T_1au", "1e-9", ">= 1", "K"]),
    # keys inside their ranges that combine into a state that is not finite (CVODE said
    # only that its first right-hand side failed, exit 3)
    ("non-finite dust rates", None, ["--set", 'dust.init="gaussian_ring"', "--set",
                                     "dust.ring_sigma=1e308"],
     ["sigma_d", "nan", "dust.*",
      "far from their defaults (over 1e3 x): dust.ring_sigma = 1e+308 (default 1.0, --set)"]),
    ("no gas in a cell", None, ["--set", 'disk.model="lbp"', "--set", "disk.r_c_au=1e-6"],
     ["Sigma_g", "= 0", "disk.*", "disk.r_c_au = 1e-06 (default 60.0, --set)"]),
    # a temperature rising outward puts ice inside silicate (the snow line was NaN, and the
    # whole disk was taken as ice, with exit 0)
    ("temperature rising outward with a snow line", None, ["--set", "disk.q=-0.5"],
     ["disk.q", "-0.5", "rise outward", "snowline.enabled = false"]),
    # output times the integrator cannot tell apart (CV_TOO_CLOSE, exit 3, before)
    ("output times too close", None,
     ["--set", "output.times_yr=[1.0, 1.0000000000000002]", "--set", "output.t_end_yr=2"],
     ["output.times_yr", "apart", "merge"]),
]


def main():
    args = parse_args()
    c = Checks()
    for k, (label, text, extra, needles) in enumerate(CASES):
        scene = os.path.join(args.workdir, f"bad_{k}.toml")
        data = GOOD if text is None else text
        with open(scene, "wb") as f:  # the garbage case is not UTF-8 on purpose
            f.write(data.encode("latin-1") if label == "binary garbage" else data.encode())
        out = os.path.join(args.workdir, f"bad_{k}.h5")
        if os.path.exists(out):
            os.remove(out)
        p = subprocess.run([args.exe, "run", scene, "-o", out] + extra,
                           capture_output=True, text=True, errors="replace")
        msg = (p.stderr + p.stdout).strip()
        lower = msg.lower()
        missing = [n for n in needles if n.lower() not in lower]
        print(f"[{label}] exit {p.returncode}: {msg.splitlines()[0] if msg else '(no message)'}")
        c.check(p.returncode == 2, f"{label}: exit code 2")
        c.check(not missing, f"{label}: message names {needles}" + (f" (missing {missing})" if missing else ""))
        c.check(not os.path.exists(out), f"{label}: no output file left behind")

    # the output is the scene: --overwrite must not replace what the run reads
    scene = os.path.join(args.workdir, "same.toml")
    with open(scene, "w") as f:
        f.write(GOOD)
    link = os.path.join(args.workdir, "same_link.toml")
    if os.path.lexists(link):
        os.remove(link)
    os.symlink(scene, link)
    for label, out in (("output is the scene", scene), ("output is a link to it", link)):
        p = subprocess.run([args.exe, "run", scene, "-o", out, "--overwrite",
                            "--set", "output.t_end_yr=10", "--set", "output.t_first_yr=1"],
                           capture_output=True, text=True)
        print(f"[{label}] exit {p.returncode}: {p.stderr.strip()}")
        c.check(p.returncode == 2 and "the scene" in p.stderr and "-o" in p.stderr,
                f"{label}: exit code 2, message names it")
        c.check(open(scene).read() == GOOD, f"{label}: the scene is untouched")

    # track: a time or size that ends the track at once (exit 0 with no track, before)
    for flag, value in (("--t-max-yr", "0"), ("--t-max-yr", "nan"), ("--a-stop-cm", "-1")):
        p = subprocess.run([args.exe, "track", os.path.join(REPO, "params/fiducial.toml"),
                            "--r0-au", "10", flag, value], capture_output=True, text=True)
        c.check(p.returncode == 2 and flag in p.stderr,
                f"track {flag} {value}: exit {p.returncode}: {p.stderr.strip()}")

    # a release radius inside the grid's inner edge: the message gives the edge
    p = subprocess.run([args.exe, "track", os.path.join(REPO, "params/fiducial.toml"),
                        "--r0-au", "0.5"], capture_output=True, text=True)
    c.check(p.returncode == 2 and "grid.r_in_au = 1 " in p.stderr,
            f"track --r0-au 0.5: exit {p.returncode}, names r_in: {p.stderr.strip()}")
    # observe given a directory: it was "no such file"
    p = subprocess.run([args.exe, "observe", args.workdir, "--time-yr", "1", "--lambda-mm",
                        "1.3"], capture_output=True, text=True)
    c.check(p.returncode == 2 and "not a regular file" in p.stderr,
            f"observe DIR: exit {p.returncode}: {p.stderr.strip()}")

    # the wrong file given to --restart, or to -o with --restart, is bad input (exit 2)
    # naming the file to give: it was a "truncated or damaged" checkpoint (exit 4) with
    # the advice to start the run again without --restart
    fiducial = os.path.join(REPO, "params/fiducial.toml")
    short = ["--set", "output.t_end_yr=10", "--set", "output.t_first_yr=1"]
    run_out = os.path.join(args.workdir, "short.h5")
    chk = run_out[:-3] + ".chk.h5"
    for f in (run_out, chk):
        if os.path.exists(f):
            os.remove(f)
    p = subprocess.run([args.exe, "run", fiducial, "-o", run_out] + short,
                       capture_output=True, text=True)
    c.check(p.returncode == 0 and os.path.exists(chk), f"short run: exit {p.returncode}")
    missing = os.path.join(args.workdir, "missing.h5")
    for label, extra, needles in (
            ("--restart the scene", ["--restart", fiducial], ["not an HDF5 file", ".chk.h5"]),
            ("--restart a directory", ["--restart", args.workdir], ["is a directory"]),
            ("--restart the output", ["--restart", run_out, "-o", run_out],
             ["the output of a run, not its checkpoint", "restart from " + chk]),
            ("--restart with -o a missing file",
             ["--restart", chk, "-o", missing, "--set", "output.t_end_yr=100"],
             ["-o " + missing, "no such file", run_out])):
        before = open(run_out, "rb").read()
        p = subprocess.run([args.exe, "run", fiducial] + short + extra,
                           capture_output=True, text=True)
        print(f"[{label}] exit {p.returncode}: {p.stderr.strip()}")
        c.check(p.returncode == 2 and all(n in p.stderr for n in needles)
                and "without --restart" not in p.stderr,
                f"{label}: exit code 2, message names {needles}")
        c.check(open(run_out, "rb").read() == before and not os.path.exists(missing),
                f"{label}: the run's output untouched, no file made")

    # -o "" (an unset variable) wrote to the default output, out/<scene>.h5
    cwd = os.path.join(args.workdir, "empty_o")
    os.makedirs(cwd, exist_ok=True)
    for cmd in (["run", fiducial] + short,
                ["observe", run_out, "--time-yr", "10", "--lambda-mm", "1.3"]):
        p = subprocess.run([os.path.abspath(args.exe)] + cmd + ["-o", ""],
                           capture_output=True, text=True,
                           cwd=cwd)
        print(f"[{cmd[0]} -o ''] exit {p.returncode}: {p.stderr.strip()}")
        c.check(p.returncode == 2 and "empty output path" in p.stderr,
                f"{cmd[0]} -o '': exit code 2, says the path is empty")
        c.check(not os.listdir(cwd) and not os.path.exists(run_out[:-3] + "_obs.h5"),
                f"{cmd[0]} -o '': no output written")

    # unwritable output location -> I/O error, exit 4
    p = subprocess.run([args.exe, "run", os.path.join(REPO, "params/fiducial.toml"),
                        "-o", "/proc/panoptic/x.h5"], capture_output=True, text=True)
    print(f"[unwritable output] exit {p.returncode}: {p.stderr.strip()}")
    c.check(p.returncode == 4, "unwritable output: exit code 4")
    # a key set but not read under the scene's switches (an LBP radius on a power-law
    # disk was silently ignored): one warning naming the key, where it was set, the
    # switch and the fix; check and run still exit 0
    fid = os.path.join(REPO, "params/fiducial.toml")
    for cmd in (["check", fid], ["run", fid, "-o", os.path.join(args.workdir, "warn.h5"),
                                 "--overwrite", "--set", "output.t_end_yr=1e-3",
                                 "--set", "output.t_first_yr=1e-4",
                                 "--set", "grid.n_cells=16"]):
        p = subprocess.run([args.exe] + cmd + ["--set", "disk.r_c_au=30"],
                           capture_output=True, text=True)
        warnings = [l for l in p.stderr.splitlines() if "warning" in l]
        print(f"[unused key, {cmd[0]}] exit {p.returncode}: {warnings}")
        c.check(p.returncode == 0 and len(warnings) == 1 and warnings[0].startswith(
            "panoptic: warning: disk.r_c_au = 30") and all(n in warnings[0] for n in [
                "(--set)", 'disk.model = "powerlaw"', 'set disk.model = "lbp"']),
                f"{cmd[0]}: one warning for the unused disk.r_c_au, exit 0")
    p = subprocess.run([args.exe, "check", fid], capture_output=True, text=True)
    c.check(p.returncode == 0 and "warning" not in p.stderr,
            f"check of the fiducial scene: no warning ({p.stderr.strip()!r})")
    for flag in ["--help", "--version"]:
        p = subprocess.run([args.exe, flag], capture_output=True, text=True)
        c.check(p.returncode == 0 and p.stdout.strip() != "", f"{flag}: exit 0 with text")
    c.finish()


if __name__ == "__main__":
    main()
