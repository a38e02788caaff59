"""Planetesimal formation per mass bin in the size-distribution mode (spec §15.4,
physics/modules/bin_planetesimals.*), on params/tests/distribution_small.toml with both
channels and their thresholds lowered so that its grains (St ~1e-6 .. 1e-4 within
1 000 yr) convert: the run writes what a single-size run of the same scene writes about
planetesimals (the snapshot fields sigma_pl, sigma_pl_coag, sigma_pl_si, t_first_pl, the
budget terms m_pl_coag, m_pl_si, the /summary datasets), the budget closes to 1e-10 at
every snapshot with the planetesimal terms in it, and /summary agrees with the integrals
of the snapshot fields."""
import numpy as np

from postprocess.reader import open_output  # noqa: E402

from common import Checks, budget_error, load_run, parse_args, run

SCENE = "params/tests/distribution_small.toml"
CHANNELS = ["planetesimals.coagulation=true", "planetesimals.St_pl=1e-5",
            'planetesimals.si="d16"', "planetesimals.St_si_min=1e-5",
            "planetesimals.eps_crit=5e-3", "output.t_end_yr=1e3"]
ME = 5.972e27


def summary(path):
    with open_output(path) as f:
        return {k: np.ravel(f["summary"][k][()]) for k in f["summary"]}


def main():
    args = parse_args()
    c = Checks()
    dist = f"{args.workdir}/bins.h5"
    run(args.exe, SCENE, dist, CHANNELS)
    single = f"{args.workdir}/single.h5"
    run(args.exe, SCENE, single, CHANNELS + ['model.kind="single_size"'])
    r, rs = load_run(dist), load_run(single)
    s = r.snapshots
    for name in ("sigma_pl", "sigma_pl_coag", "sigma_pl_si", "t_first_pl", "m_pl_coag",
                 "m_pl_si"):
        c.check(name in s and name in rs.snapshots, f"/snapshots/{name} in both runs")
    c.check(list(r.budget_terms) == list(rs.budget_terms),
            f"the same budget terms as the single-size run ({list(r.budget_terms)})")
    keys, keys_single = set(summary(dist)), set(summary(single))
    pl_keys = {k for k in keys_single if "pl" in k}
    c.check(pl_keys <= keys, f"the single-size run's planetesimal /summary datasets "
            f"{sorted(pl_keys)} are there (missing: {sorted(pl_keys - keys)})")
    err = budget_error(s, r.budget_terms)
    m0 = s["m_dust"][0]
    frac = {ch: s[f"m_pl_{ch}"][-1] / m0 for ch in ("coag", "si")}
    print(f"budget error {err:.1e}; converted by 1 000 yr: coag {frac['coag']:.3f}, "
          f"SI {frac['si']:.3f} of the dust")
    c.check(err < 1e-10, f"dust budget closes to 1e-10 with the planetesimals ({err:.1e})")
    c.check(frac["coag"] > 1e-3 and frac["si"] > 1e-3, "both channels convert")
    total = np.sum(s["sigma_pl"][-1] * r.area)
    c.check(np.isclose(total, s["m_pl_coag"][-1] + s["m_pl_si"][-1], rtol=1e-12),
            "sigma_pl integrates to m_pl_coag + m_pl_si")
    summ = summary(dist)
    for ch in ("coag", "si"):
        m_int = np.sum(s[f"sigma_pl_{ch}"][-1] * r.area) / ME
        c.check(np.isclose(float(summ[f"m_pl_{ch}"][0]), m_int, rtol=1e-10, atol=1e-14),
                f"summary m_pl_{ch} = {float(summ[f'm_pl_{ch}'][0]):.6g} M_earth = integral "
                f"of sigma_pl_{ch} ({m_int:.6g})")
    formed = s["sigma_pl"][-1] > float(summ["formed_threshold"][0])
    c.check(formed.any() and np.array_equal(formed, np.isfinite(summ["t_first_pl"])),
            f"first-formation times exist exactly where planetesimals formed "
            f"({int(formed.sum())} cells)")
    c.finish()


if __name__ == "__main__":
    main()
