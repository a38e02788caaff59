"""Unused-key warnings of erosion.eps_eros (src/scene/keys_growth.cpp, KeySpec::used_when):
the single-size model reads it with erosion.model = "balance" only (spec §5.2), the
size-distribution mode with either erosion model (the pairs of bins, spec §15.2). A scene
of the single-size model with erosion.model = "halt" and eps_eros set is warned, by
`panoptic check` and `panoptic run`, in a line that names the key, where it was set, the
switches that leave it unread and what would make a run read it; the same scene in the
distribution mode, or with balance, is not."""
import os
import subprocess

from common import Checks, parse_args, write_file

SCENE = """[growth]
enabled = true
[erosion]
model = "halt"
v_eros_m_s = 20.0
eps_eros = 0.5
[grid]
n_cells = 4
r_in_au = 5.0
r_out_au = 10.0
[output]
t_end_yr = 10.0
t_first_yr = 1.0
n_snapshots = 2
"""
# a few bins for the distribution runs (1e-12 .. 1e-6 g, 3.5 per decade)
DISTRIBUTION = ["model.kind=distribution", "model.bins_per_decade=3.5", "model.m_min_g=1e-12",
                "model.m_max_g=1e-6"]
WARNING = ('panoptic: warning: erosion.eps_eros = 0.5 ({scene}:6:1) is not used: '
           'model.kind = "single_size", erosion.model = "halt"; set (model.kind = '
           '"distribution" or erosion.model = "balance") to use it, or remove the key')


def panoptic(exe, command, scene, sets, workdir, name):
    cmd = [exe, command, scene]
    if command == "run":
        cmd += ["-o", os.path.join(workdir, name + ".h5"), "--overwrite"]
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, capture_output=True, text=True)


def main():
    args = parse_args()
    c = Checks()
    scene = write_file(args.workdir, "halt_eps_eros.toml", SCENE)
    warning = WARNING.format(scene=scene)
    cases = (("single size, halt", [], True),
             ("single size, balance", ["erosion.model=balance"], False),
             ("distribution, halt", DISTRIBUTION, False),
             ("distribution, balance", DISTRIBUTION + ["erosion.model=balance"], False))
    for command in ("check", "run"):
        for label, sets, warned in cases:
            p = panoptic(args.exe, command, scene, sets, args.workdir,
                         label.replace(", ", "_").replace(" ", "_"))
            lines = [ln for ln in p.stderr.splitlines() if "eps_eros" in ln]
            if warned:
                ok = lines == [warning]
            else:
                ok = not lines
            c.check(p.returncode == 0 and ok,
                    f"{command}, {label}: exit {p.returncode}, eps_eros "
                    f"{'warned' if warned else 'not warned'} {lines if not ok else ''}"
                    f"{p.stderr.strip() if p.returncode else ''}")
    c.finish()


if __name__ == "__main__":
    main()
