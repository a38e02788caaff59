"""A short run of the size-distribution mode (spec §15, params/tests/distribution_small.toml:
12 cells, 50 mass bins, coagulation with fragmentation, drift, diffusion and the viscous
gas, 3 000 yr): the dust budget closes to 1e-10 at every snapshot, /snapshots/sigma holds
the bins of every cell (n_cells x /grid/m_bins) and sums to sigma_d, and the particles
grow: the mass-dominating bin (m, a, St) rises from the MRN start by orders of magnitude
in the inner disk while sigma_d stays near its initial profile. `panoptic observe` reads
the run (its opacities of the distribution: regression.test_observe_distribution); the
van Leer limiter runs it to the end with a closed budget; a
scan over two distribution runs (disk.alpha, each on the scan's --threads 2) completes
both with closed budgets, each output holding its own run's bins."""

import csv
import os
import shutil

import numpy as np

from common import REPO, Checks, budget_error, load_run, parse_args, run, run_checked


def main():
    args = parse_args()
    c = Checks()
    out = f"{args.workdir}/distribution_small.h5"
    run(args.exe, "params/tests/distribution_small.toml", out)
    r = load_run(out)
    s = r.snapshots
    err = budget_error(s, r.budget_terms)
    print(f"max budget error {err:.1e}")
    c.check(err < 1e-10, f"dust budget closes to 1e-10 ({err:.1e})")
    import h5py
    with h5py.File(out, "r") as f:
        m_bins = f["grid/m_bins"][:]
        sigma = f["snapshots/sigma"][:]
        n = f["grid/r_c"].shape[0]
    nb = m_bins.size
    c.check(nb == 50, f"50 mass bins 1e-12 .. 1e2 g at 3.5 per decade ({nb})")
    c.check(sigma.shape[1] == n * nb, f"sigma holds n_cells x bins ({sigma.shape})")
    bins = sigma.reshape(sigma.shape[0], n, nb)
    sums = bins.sum(axis=2)
    dev = float(np.max(np.abs(sums - s["sigma_d"]) / np.max(s["sigma_d"])))
    c.check(dev < 1e-14, f"the bins sum to sigma_d ({dev:.1e})")
    dominant = m_bins[np.argmax(bins[-1], axis=1)]
    c.check(np.allclose(dominant, s["m"][-1], rtol=0, atol=0),
            "m is the mass of the bin holding the most mass (argmax sigma_k)")
    grown = s["m"][-1][0] / s["m"][0][0]
    print(f"inner cell: m {s['m'][0][0]:.2e} -> {s['m'][-1][0]:.2e} g, "
          f"St {s['St'][0][0]:.2e} -> {s['St'][-1][0]:.2e}")
    c.check(grown > 1e6, f"the inner cell's mass-dominating bin grew ({grown:.1e} x)")
    change = float(np.max(np.abs(s["sigma_d"][-1] / s["sigma_d"][0] - 1)))
    c.check(change < 0.5, f"sigma_d changes by less than 50 % in 3 000 yr ({change:.2f})")
    # The van Leer limiter on nearly empty bins: their differences (~1e-162) once
    # underflowed to 0/0 in the limiter's derivative and stopped the run at 0.05 yr.
    out_vl = f"{args.workdir}/distribution_van_leer.h5"
    run(args.exe, "params/tests/distribution_small.toml", out_vl,
        ['transport.advection="van_leer"'])
    r_vl = load_run(out_vl)
    err_vl = budget_error(r_vl.snapshots, r_vl.budget_terms)
    c.check(r_vl.time[-1] == s["time"][-1] and err_vl < 1e-10,
            f"van Leer advection runs to {r_vl.time[-1]:g} yr, budget to 1e-10 ({err_vl:.1e})")
    p = run_checked([args.exe, "observe", out, "--time-yr", "3000", "--lambda-mm", "1.3",
                     "-o", f"{args.workdir}/distribution_obs.h5", "--overwrite"],
                    expect=None)
    c.check(p.returncode == 0, f"observe reads a distribution run, exit 0 ({p.returncode}: "
            f"{p.stderr.strip()[:120]})")
    scan = os.path.join(args.workdir, "distribution_scan.toml")
    with open(scan, "w") as f:
        f.write(f'[scan]\nscene = "{REPO}/params/tests/distribution_small.toml"\n'
                'set = ["output.t_end_yr=1e3"]\nsampling = "grid"\n\n'
                '[[axis]]\nkey = "disk.alpha"\nvalues = [1e-3, 3e-3]\n')
    scan_dir = os.path.join(args.workdir, "distribution_scan")
    shutil.rmtree(scan_dir, ignore_errors=True)  # runs of an earlier call would be resumed
    run_checked([args.exe, "scan", scan, "-o", scan_dir, "-j", "1", "--threads", "2",
                 "--force"])
    with open(os.path.join(scan_dir, "summary.csv")) as f:
        rows = list(csv.DictReader(f))
    c.check(len(rows) == 2 and all(r["status"] == "completed" for r in rows),
            f"the scan completes both distribution runs ({[r['status'] for r in rows]})")
    c.check(all(float(r["budget_error"]) < 1e-10 for r in rows),
            f"their budgets close ({[r['budget_error'] for r in rows]})")
    # each output is its own run's: its alpha, its bins summing to its sigma_d
    outputs = []
    for r in rows:
        alpha = float(r["disk.alpha"])
        path = os.path.join(scan_dir, "runs", r["name"] + ".h5")
        run_out = load_run(path)
        with h5py.File(path, "r") as f:
            bins = f["snapshots/sigma"][-1].reshape(n, nb)
        outputs.append(bins)
        with open(os.path.join(scan_dir, "runs", r["name"] + ".log")) as f:
            log = f.read()
        c.check("worker threads: 2 (--threads" in log,
                f"scan output {r['name']}: its run had the scan's --threads 2")
        c.check(run_out.config["disk"]["alpha"] == alpha and
                np.allclose(bins.sum(axis=1), run_out.snapshots["sigma_d"][-1], rtol=1e-14,
                            atol=0),
                f"scan output {r['name']}: alpha = {alpha:g}, its bins sum to its sigma_d")
    c.check(len(outputs) == 2 and not np.array_equal(outputs[0], outputs[1]),
            "the two scan outputs hold different distributions")
    c.finish()


if __name__ == "__main__":
    main()
