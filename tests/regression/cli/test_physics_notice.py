"""No silent physics choice (src/model/run_report.cpp, physics_choices): the process
switches default to off, so the header of `panoptic run` and the output of `panoptic
check` say in one line what the particles do. A scene with no [growth] (the minimal
scene of issue 37: two disk keys) says that growth is off and St is prescribed, with the
value and the key to change; a scene with growth but no porosity, no fragmentation and no
planetesimal channel names each switch; the fiducial scene says it is porous and sticks at
any speed."""
import os

from common import REPO, Checks, parse_args, run_checked, write_file


def growth_lines(text):
    return [ln.lstrip("# ") for ln in text.splitlines() if ln.lstrip("# ").startswith("growth:")]


def main():
    args = parse_args()
    c = Checks()
    minimal = write_file(args.workdir, "minimal.toml", "[disk]\nT_1au = 150.0\nalpha = 1e-4\n")
    out = os.path.join(args.workdir, "minimal.h5")
    for label, cmd in [
            ("run", [args.exe, "run", minimal, "-o", out, "--overwrite",
                     "--set", "output.t_end_yr=100", "--set", "output.n_snapshots=2"]),
            ("check", [args.exe, "check", minimal])]:
        lines = growth_lines(run_checked(cmd).stdout)
        c.check(len(lines) == 1 and "growth: off" in lines[0] and
                "St is prescribed: transport.St = 0.03 at 1 au" in lines[0] and
                "growth.enabled = true" in lines[0],
                f"{label}, no [growth]: one line, off, St = 0.03, the key: {lines}")
    lines = growth_lines(run_checked([args.exe, "check", minimal, "--set",
                                      "transport.St_slope=0.5", "--set", "transport.St=0.1"]
                                     ).stdout)
    c.check(len(lines) == 1 and "transport.St = 0.1 at 1 au times (r/au)^0.5" in lines[0],
            f"check, St with a slope: {lines}")
    lines = growth_lines(run_checked([args.exe, "check", minimal, "--set",
                                      "growth.enabled=true"]).stdout)
    c.check(len(lines) == 1 and "compact (phi = 1" in lines[0] and
            "porosity.enabled = true" in lines[0] and "fragmentation.enabled = false" in
            lines[0] and "no planetesimal channel" in lines[0],
            f"check, growth alone: compact, sticking, no planetesimals, each key: {lines}")
    lines = growth_lines(run_checked([args.exe, "check", os.path.join(
        REPO, "params", "fiducial.toml")]).stdout)
    c.check(len(lines) == 1 and lines[0].startswith("growth: on, porous; particles stick")
            and "planetesimal" not in lines[0], f"check, fiducial: {lines}")
    c.finish()


if __name__ == "__main__":
    main()
