"""A table disk (disk.model = "table") that tabulates the fiducial power law (Sigma_g =
1700 r^-1.5, T = 280 r^-1/2, 40 rows from 1 to 300 au) reproduces the power-law run: the
log-log interpolation is exact for a power law, so the two differ by the round-off of
exp(log) against pow. Compared: /disk (T, c_s, h_g, omega_k, alpha, eta), sigma_g, and a
1 Myr run of params/fiducial.toml with the dust transported (drift, diffusion, the snow
line) and growth off: the same step count, v_r, St, the booked masses and sigma_d, each
the largest relative difference over all snapshots and cells (sigma_d relative to each
snapshot's largest value: in the drained tail far below it the relative digits are
those of an exponentially small number). Thresholds: 1e-12 for the gas (eta, a difference
of logarithms over d ln r, is the least precise, measured 1.6e-13), 1e-9 for the dust.
With growth on, the particle laws' thresholds (fragmentation, St_pl) make CVODE take
different steps, and the runs then agree only to the solver's tolerance (README,
params/README.md: what this test does not claim)."""
import os
import re

import numpy as np

from common import REPO, Checks, load_run, parse_args, run, run_checked, write_file

GROWTH_OFF = ["growth.enabled=false", "porosity.enabled=false",
              "planetesimals.coagulation=false"]


def main():
    args = parse_args()
    c = Checks()
    rows = "".join(f"{r!r},{1700.0 * r ** -1.5!r},{280.0 * r ** -0.5!r}\n"
                   for r in np.geomspace(1.0, 300.0, 40))
    table = write_file(args.workdir, "mmsn.csv",
                       "# the fiducial power law, tabulated\nr_au,sigma_g_gcm2,T_K\n" + rows)
    outs, steps = {}, {}
    for model in ("powerlaw", "table"):
        outs[model] = os.path.join(args.workdir, f"{model}.h5")
        p = run(args.exe, "params/fiducial.toml", outs[model],
                GROWTH_OFF + [f"disk.model=\"{model}\"", f"disk.table_file=\"{table}\""])
        steps[model] = re.search(r"solver: (\d+) steps", p.stdout).group(1)
    a, b = load_run(outs["powerlaw"]), load_run(outs["table"])
    c.check(steps["powerlaw"] == steps["table"],
            f"the same steps ({steps['powerlaw']}, {steps['table']})")

    def rel(x, y, scale=None):
        x, y = np.asarray(x, float), np.asarray(y, float)
        s = np.abs(x) if scale is None else scale
        m = s > 0
        return float(np.max(np.abs(x - y)[m] / s[m])) if m.any() else 0.0

    for k in ("T", "c_s", "h_g", "omega_k", "alpha", "eta"):
        d = rel(a.disk[k], b.disk[k])
        c.check(d < 1e-12, f"/disk/{k}: largest relative difference {d:.1e} < 1e-12")
    d = rel(a.snapshots["sigma_g"], b.snapshots["sigma_g"])
    c.check(d < 1e-12, f"sigma_g: largest relative difference {d:.1e} < 1e-12")
    for k in ("v_r", "St", "m_out_inner", "m_sublimated", "m_through"):
        d = rel(a.snapshots[k], b.snapshots[k])
        c.check(d < 1e-9, f"{k}: largest relative difference {d:.1e} < 1e-9")
    sa, sb = np.asarray(a.snapshots["sigma_d"]), np.asarray(b.snapshots["sigma_d"])
    d = rel(sa, sb, np.max(np.abs(sa), axis=1, keepdims=True) * np.ones_like(sa))
    c.check(d < 1e-9, f"sigma_d: largest difference {d:.1e} of the snapshot's peak < 1e-9")
    # a table that does not cover the grid is refused by name
    p = run_checked([args.exe, "check", os.path.join(REPO, "params/fiducial.toml"),
                     "--set", 'disk.model="table"', "--set", f'disk.table_file="{table}"',
                     "--set", "grid.r_out_au=400"], expect=2)
    c.check("disk.table_file" in p.stderr and "extend the table" in p.stderr,
            "a table short of the grid is refused naming the key and the fix")
    c.finish()


if __name__ == "__main__":
    main()
