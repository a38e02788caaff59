"""The dust mass budget (spec §6.3): mass on the grid + mass that left through r_in equals
the initial mass to 1e-12 relative at every snapshot of a whole run, for the default scene
and with the gas evolving, at the default and at a loose tolerance (the budget is exact in
the discretisation, not a consequence of accuracy)."""
import numpy as np

from common import Checks, load_run, parse_args, run

CASES = [
    ("fiducial", []),
    ("fiducial, rtol 1e-3", ["solver.rtol=1e-3"]),
    ("fiducial, viscous gas", ["gas.evolve=true"]),
    ("fiducial, St ∝ r^-1, 64 cells", ["transport.St_slope=-1", "grid.n_cells=64"]),
]


def main():
    args = parse_args()
    c = Checks()
    for k, (label, sets) in enumerate(CASES):
        out = f"{args.workdir}/budget_{k}.h5"
        run(args.exe, "params/fiducial.toml", out, sets)
        r = load_run(out)
        m = r.snapshots["m_dust"] + r.snapshots["m_out_inner"]
        err = np.max(np.abs(m / m[0] - 1))
        left = r.snapshots["m_out_inner"][-1] / m[0]
        grid_mass = np.sum(r.snapshots["sigma_d"] * r.area, axis=1)
        consistent = np.max(np.abs(grid_mass / r.snapshots["m_dust"] - 1))
        print(f"{label}: {r.n_snapshots} snapshots, {left:.3f} of the dust left through r_in, "
              f"max budget error {err:.1e}")
        c.check(err < 1e-12, f"{label}: budget closes to 1e-12 ({err:.1e})")
        c.check(consistent < 1e-12, f"{label}: m_dust equals the sum of sigma_d * area")
        c.check(np.all(r.snapshots["sigma_d"] >= 0), f"{label}: no negative Sigma_d")
    c.finish()


if __name__ == "__main__":
    main()
