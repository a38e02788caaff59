"""The mass budget of test_mass_budget.py for variants of the fiducial scene: a loose
tolerance (the budget is exact in the discretisation, not a consequence of accuracy),
evolving gas, and transport alone with a radially varying St."""
from common import Checks, parse_args
from test_mass_budget import check_budgets

VARIANTS = [
    ("fiducial, rtol 1e-3", "params/fiducial.toml", ["solver.rtol=1e-3"]),
    ("fiducial, viscous gas, 1e5 yr", "params/fiducial.toml",
     ["gas.evolve=true", "output.t_end_yr=1e5"]),
    ("transport alone, St ∝ r^-1, 64 cells", "params/fiducial.toml",
     ["growth.enabled=false", "porosity.enabled=false", "planetesimals.coagulation=false",
      'planetesimals.si="none"', "transport.St=0.03", "transport.St_slope=-1",
      "grid.n_cells=64"]),
]


def main():
    args = parse_args()
    c = Checks()
    check_budgets(VARIANTS, args, c)
    c.finish()


if __name__ == "__main__":
    main()
