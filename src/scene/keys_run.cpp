// The key tables of the run itself: [meta], [grid], [solver], [checkpoint], [output].
#include "src/scene/key_builders.hpp"
#include "src/scene/key_tables.hpp"

namespace panoptic::scene_detail {

// [meta]: documentation only.
std::vector<KeySpec> meta_keys() {
  return {
      text("meta.description", "what this scene is for"),
      text("meta.reference", "the paper or test this scene reproduces"),
  };
}

// [grid] spec §10.2
std::vector<KeySpec> grid_keys() {
  return {
      // at most 1e5 cells: ~1 GB of memory, and ~150 times the finest grid of the
      // work-precision study
      integer("grid.n_cells", "250", "number of radial cells (spacing: grid.stretch)", 4,
              1e5),
      positive("grid.r_in_au", "1.0", "au", "inner edge (open: outflow, booked)"),
      positive("grid.r_out_au", "300.0", "au", "outer edge (closed: zero flux)"),
      real("grid.stretch", "0.0", "",
           "cell spacing d ln r ∝ r^stretch: 0 log-spaced, > 0 finer in the inner disk",
           -2.0, true, 2.0, true),
  };
}

// [solver] CVODE BDF + KLU, or DustPy's implicit Euler step; reinit_at_snapshots:
// restart, src/run/README.md "Restart"
std::vector<KeySpec> solver_keys() {
  const UsedWhen bdf = one_of("solver.method", {"bdf"});
  return {
      choice(
          "solver.method", "bdf", {"bdf", "implicit_euler"},
          "the time integrator: bdf = CVODE's BDF (variable order and step, error "
          "control by solver.rtol); implicit_euler = DustPy's step as a baseline "
          "(model.kind = \"distribution\" only): linearly implicit Euler on the "
          "model's Jacobian, solved by the block solver, the step solver.cfl times the "
          "least sigma/|dsigma/dt| over the shrinking bins and Sigma_g above DustPy's "
          "floors, no error control (src/solver/implicit_euler_integrator.hpp, "
          "tests/bench/results/implicit_euler.md)"),
      when({one_of("solver.method", {"implicit_euler"})},
           real("solver.cfl", "0.1", "",
                "implicit_euler: the step as a fraction of the shortest time in which a "
                "shrinking bin (or Sigma_g) would empty at its present rate; 0.1 is "
                "DustPy's (dustpy/simulation.py, t.cfl)",
                0.0, true, 10.0, false)),
      real("solver.rtol", "1e-6", "", "CVODE relative tolerance", 1e-14, false, 0.1,
           false),
      real("solver.atol_sigma", "0.0", "",
           "absolute tolerance of Sigma_d and Sigma_g, relative to the initial maximum "
           "of Sigma (so it scales with the scene); 10x it is also the Sigma_d below "
           "which a cell's m and phi are decoded towards a monomer's, and in a porous "
           "distribution the mass below which a bin's porosity is taken as unresolved; "
           "0 = by model: 1e-10 for a porous distribution, 1e-8 otherwise "
           "(tests/bench/results/porous_cost.md, \"The empty-bin scale\")",
           0.0, false, 1.0, false),
      integer("solver.max_steps", "2000000", "limit on the total number of CVODE steps",
              1, 1e12),
      real("solver.max_dt_yr", "0.0", "yr",
           "largest step of either integrator (0 = unlimited; else >= 1e-6 yr)", 0.0,
           false),
      when({bdf},
           real("solver.newton_coef", "0.0", "",
                "CVODE's nonlinear convergence coefficient (CVodeSetNonlinConvCoef): "
                "Newton stops when its correction is below this fraction of the local "
                "error tolerance; 0 = by model.kind: 0.03 for single_size (less Newton "
                "error in the local error estimate, fewer failed steps: "
                "tests/bench/results/performance_log.md), 0.05 for a compact "
                "distribution, 0.1 for a porous one "
                "(tests/bench/results/porous_newton.md)",
                0.0, false, 1.0, false)),
      when(
          {bdf},
          integer(
              "solver.steps_per_jacobian", "10",
              "k: a Newton-matrix factorisation at least every k steps and a fresh "
              "Jacobian at the first one k or more steps after the last "
              "(CVodeSetLSetupFrequency, CVodeSetJacEvalFrequency; CVODE's own are 20 "
              "and 51): a Jacobian of at most 2k - 1 steps keeps Newton converging where "
              "a cell crosses one of the model's smooth switches, fewer failed "
              "iterations and steps (tests/bench/README.md, Performance); 0: CVODE's own",
              0, 1e6)),
      when({bdf},
           choice("solver.linear", "auto", {"auto", "klu", "block", "gmres"},
                  "the solver of CVODE's Newton systems: auto = gmres for a size "
                  "distribution (model.kind = \"distribution\"), klu for the single "
                  "size; klu = KLU's sparse LU of the whole matrix, for "
                  "single-size runs (a few variables per cell); block = dense LU of each "
                  "cell's block and block-banded elimination over the cells "
                  "(src/solver/block_banded_lu.hpp): a size distribution in half KLU's "
                  "CPU time, its mass budget closing to round-off; refused (exit with the"
                  " reason) where a cell's equations read a global variable; gmres = "
                  "CVODE's SPGMR with products from the assembled Jacobian, "
                  "right-preconditioned by the LU of each cell's dense block "
                  "(src/solver/cell_block_preconditioner.hpp), each solution corrected "
                  "to keep the mass budget to round-off: 0.5-0.8x the block solver's "
                  "time on porous size distributions, 0.63-0.78x on compact ones, slow "
                  "on single-size runs (tests/bench/results/krylov_solver.md)")),
      flag("solver.reinit_at_snapshots", "true",
           "reinitialise CVODE at every snapshot time, so that a run restarted from a "
           "checkpoint is bit-for-bit identical to one never stopped; with gas.evolve "
           "the particle laws' eta and gas velocity are also set from the gas there "
           "(false: once, at the start)"),
  };
}

// [checkpoint] restart, src/run/README.md "Restart"
std::vector<KeySpec> checkpoint_keys() {
  return {
      real("checkpoint.every_wall_s", "1800.0", "s",
           "checkpoint at the first snapshot after this much wall time since the last "
           "one (0 = off); one is always written at the end and when stopped",
           0.0, false),
      integer("checkpoint.every_snapshots", "0",
              "checkpoint at every k-th snapshot (0 = off)", 0, 1e6),
  };
}

// [output]
std::vector<KeySpec> output_keys() {
  return {
      // 1e12 yr: far beyond any disk's life, and t_end in seconds stays finite (1e308 yr
      // would be inf s, on which CVODE fails)
      real("output.t_end_yr", "1e6", "yr", "end of the run", 1e-6, false, 1e12, false),
      when({is("output.times_yr", {"[]"})},
           real("output.t_first_yr", "100.0", "yr",
                "first snapshot after t = 0 (log-spaced snapshots from here to t_end)",
                1e-6)),
      when({is("output.times_yr", {"[]"})},
           integer("output.n_snapshots", "41",
                   "log-spaced snapshots after t = 0 (t_first..t_end)", 1, 1e6)),
      real_list("output.times_yr", "yr",
                "explicit snapshot times, each <= t_end_yr, strictly increasing, at "
                "least 1e-9 (relative) apart; replaces the log spacing when not empty",
                1e-6),
      text("output.file", "output file (default: out/<scene name>.h5; -o overrides)"),
  };
}

}  // namespace panoptic::scene_detail
