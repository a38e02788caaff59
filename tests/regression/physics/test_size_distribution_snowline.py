"""The size-distribution mode with the snow line (spec §1.7, §6.3, §15.4;
params/tests/distribution_small.toml with snowline.enabled, r_snow = 1.70 au): `panoptic
check` accepts the scene and the run completes; the dust budget, with the ice sublimated
at the snow line, closes to 1e-10 at every snapshot; with drift alone (transport.diffusion
= false, every flow through the snow face inward) the sublimated mass is f_ice of the mass
through the snow-line face (booked by the pebble monitor there, spec §8) at every
snapshot; the silicate cell inside starts with half the icy cells' dust-to-gas ratio.
The St of every bin (/snapshots/st_bins) is the mass-dominating bin's St where that bin
is, and grows as m^(1/3) over the small (Epstein) bins of every cell."""

import os

import numpy as np

from common import REPO, Checks, budget_error, load_run, parse_args, run, run_checked

SCENE = "params/tests/distribution_small.toml"


def main():
    args = parse_args()
    c = Checks()
    sets = ["snowline.enabled=true", "output.t_end_yr=1e3", "transport.diffusion=false"]
    p = run_checked([args.exe, "check", os.path.join(REPO, SCENE)]
                    + [a for s in sets for a in ("--set", s)], expect=None)
    c.check(p.returncode == 0, f"panoptic check accepts the scene (exit {p.returncode})")
    out = f"{args.workdir}/distribution_snowline.h5"
    run(args.exe, SCENE, out, sets)
    r = load_run(out)
    s = r.snapshots
    err = budget_error(s, r.budget_terms)
    print(f"max budget error {err:.1e}")
    c.check("m_sublimated" in (r.budget_terms or []), "m_sublimated is a budget term")
    c.check(err < 1e-10, f"dust budget closes to 1e-10 with the snow line ({err:.1e})")
    k = int(np.argmin(np.abs(r.monitor_r_au - r.r_snow_au)))
    f_ice = r.config["snowline"]["f_ice"]
    m_snow, m_sub = s["m_through"][:, k], s["m_sublimated"]
    c.check(m_snow[-1] > 0 and np.allclose(m_sub, f_ice * m_snow, rtol=1e-9,
                                           atol=1e-12 * m_snow[-1]),
            f"sublimated mass = f_ice x mass through the snow-line face "
            f"({r.monitor_r_au[k]:.4g} au) at every snapshot: {m_sub[-1]:.4e} = {f_ice} x "
            f"{m_snow[-1]:.4e} g")
    z = s["sigma_d"][0] / s["sigma_g"][0]
    inside = r.r_c < r.r_snow_au
    c.check(inside.any() and np.allclose(z[inside], (1 - f_ice) * z[~inside][0], rtol=1e-12),
            f"Z inside r_snow = (1 - f_ice) Z outside at the start ({z[inside][0]:.4g})")
    import h5py
    with h5py.File(out, "r") as f:
        m_bins = f["grid/m_bins"][:]
        sigma = f["snapshots/sigma"][-1].reshape(r.r_c.size, m_bins.size)
        st = f["snapshots/st_bins"][-1].reshape(r.r_c.size, m_bins.size)
    dominant = st[np.arange(r.r_c.size), np.argmax(sigma, axis=1)]
    c.check(np.array_equal(dominant, s["St"][-1]),
            "st_bins at the mass-dominating bin is St, bit for bit")
    slope = np.log(st[:, 1] / st[:, 0]) / np.log(m_bins[1] / m_bins[0])
    c.check(np.allclose(slope, 1 / 3, rtol=1e-9),
            f"St of the smallest bins grows as m^(1/3) (Epstein) in every cell "
            f"({slope.min():.12f} .. {slope.max():.12f})")
    c.finish()


if __name__ == "__main__":
    main()
