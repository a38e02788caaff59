#include "src/model/scene_to_physics.hpp"

#include <stdexcept>

#include "physics/coagulation/porosity.hpp"
#include "src/core/units.hpp"
#include "src/model/disk_tables.hpp"

namespace panoptic {

namespace {

// disk.alpha_profile (spec §1.5 with a radial profile)
AlphaProfile alpha_profile_from_config(const Config& cfg) {
  AlphaProfile a;
  const std::string& kind = cfg.str("disk.alpha_profile");
  if (kind == "gaussian") {
    a.kind = AlphaProfile::Kind::kGaussian;
    a.amplitude = cfg.real("disk.alpha_bump_amplitude");
    a.r0 = cfg.real("disk.alpha_bump_r_au") * units::kAu;
    a.width = cfg.real("disk.alpha_bump_width_au") * units::kAu;
  } else if (kind == "table") {
    a.kind = AlphaProfile::Kind::kTable;
    a.table = read_disk_table(cfg, "disk.alpha_file", {"r_au", "alpha"}, {1.0})[0];
  }
  return a;
}

}  // namespace

DiskParams disk_params_from_config(const Config& cfg) {
  DiskParams d;
  d.star = {cfg.real("star.mass_msun") * units::kMsun,
            cfg.real("star.luminosity_lsun") * units::kLsun};
  ThermalParams& th = d.thermal;
  const std::string& model = cfg.str("disk.model");
  if (model != "table") {
    th.T_1au = cfg.real("disk.T_1au");
    th.q = cfg.real("disk.q");
    th.T_floor = cfg.real("disk.T_floor");
  }
  th.mu = cfg.real("disk.mu");
  if (cfg.str("disk.alpha_profile") != "table") th.alpha = cfg.real("disk.alpha");
  th.sigma_mol = cfg.real("disk.sigma_mol");
  th.T_sub = cfg.real("disk.T_sub");
  d.alpha = alpha_profile_from_config(cfg);
  GasProfile& g = d.profile;
  if (model == "lbp") {
    g.kind = GasProfile::Kind::kLbp74;
    g.m_disk = cfg.real("disk.m_disk_msun") * units::kMsun;
    g.r_c = cfg.real("disk.r_c_au") * units::kAu;
    g.gamma = cfg.real("disk.gamma");
  } else if (model == "table") {
    g.kind = GasProfile::Kind::kTable;
    const auto t = read_disk_table(cfg, "disk.table_file",
                                   {"r_au", "sigma_g_gcm2", "T_K"}, {1.0, 1.0});
    g.sigma_table = t[0];
    g.t_table = t[1];
  } else {
    g.kind = GasProfile::Kind::kPowerLaw;
    g.p = cfg.real("disk.p");
    g.sigma_1au =
        cfg.str("disk.sigma_norm") == "mass"
            ? PowerLawDisk::sigma_1au_for_mass(cfg.real("disk.m_gas_msun") * units::kMsun,
                                               g.p, cfg.real("grid.r_in_au") * units::kAu,
                                               cfg.real("grid.r_out_au") * units::kAu)
            : cfg.real("disk.sigma_1au");
  }
  if (model != "table" && cfg.str("disk.sigma_bump") == "gaussian") {
    g.bump_amplitude = cfg.real("disk.sigma_bump_amplitude");
    g.bump_r0 = cfg.real("disk.sigma_bump_r_au") * units::kAu;
    g.bump_width = cfg.real("disk.sigma_bump_width_au") * units::kAu;
  }
  return d;
}

physics::MonomerMaterial material_from_config(const Config& cfg, const std::string& sp) {
  physics::MonomerMaterial m;
  m.a0 = cfg.real("material.a0_um") * 1e-4;
  m.xi_crit = cfg.real("material.xi_crit_angstrom") * 1e-8;
  m.z0 = cfg.real("material.z0_nm") * 1e-7;
  m.rolling_radius_factor = cfg.real("material.rolling_radius_factor");
  m.rho0 = cfg.real("material." + sp + "_rho0");
  m.gamma_surf = cfg.real("material." + sp + "_gamma");
  m.youngs_modulus = cfg.real("material." + sp + "_youngs_gpa") * 1e10;  // GPa -> Ba
  m.poisson = cfg.real("material." + sp + "_poisson");
  return m;
}

physics::Species species_from_config(const Config& cfg, const std::string& sp) {
  const auto mat = material_from_config(cfg, sp);
  const auto contact = physics::contact_properties(mat);
  physics::Species s;
  s.a0 = mat.a0;
  s.rho0 = mat.rho0;
  s.m0 = contact.m0;
  s.e_roll = contact.e_roll;
  s.v_frag = 100.0 * cfg.real("fragmentation.v_frag_" + sp + "_m_s");
  // fragmentation.species: "both", or only "silicate" (sp = "sil") or "ice"
  const std::string& which = cfg.str("fragmentation.species");
  s.fragments = which == "both" || which.starts_with(sp);
  return s;
}

physics::OpticalTable optical_table_from_config(const Config& cfg,
                                                const std::string& sp) {
  const std::string key = "observe." + sp;
  try {
    return physics::OpticalTable(sp, cfg.reals(key + "_lambda_mm"), cfg.reals(key + "_n"),
                                 cfg.reals(key + "_k"));
  } catch (const std::invalid_argument& e) {
    // the one a --set changed (observe reads the run's resolved scene, where all three
    // are set), else the one the scene set, if only one
    std::string blamed = key + "_lambda_mm";
    for (const char* suffix : {"_n", "_k"})
      if (cfg.user_set(key + suffix) && !cfg.user_set(blamed)) blamed = key + suffix;
    for (const char* suffix : {"_lambda_mm", "_n", "_k"})
      if (cfg.where(key + suffix) == "--set" && cfg.where(blamed) != "--set")
        blamed = key + suffix;
    cfg.fail(blamed, std::string(e.what()) + "; fix " + key + "_lambda_mm, _n, _k");
  }
}

physics::GrowthOptions growth_options_from_config(const Config& cfg) {
  physics::GrowthOptions o;
  o.f_grow = cfg.real("growth.f_grow");
  o.eps = cfg.real("growth.eps");
  o.drag = cfg.str("growth.drag_law") == "epstein" ? physics::DragLaw::kEpstein
                                                   : physics::DragLaw::kStokesRe;
  o.st_max = cfg.real("growth.St_max");
  o.turbulence.vg2_factor = cfg.real("growth.vg2_factor");
  o.porosity = cfg.flag("porosity.enabled");
  o.s_hs = cfg.real("porosity.s_hs");
  o.b = cfg.real("porosity.b");
  o.phi_max = cfg.real("porosity.phi_max");
  o.gas_compaction = cfg.flag("porosity.gas_compaction");
  o.self_gravity = cfg.flag("porosity.self_gravity");
  const auto& e = cfg.str("erosion.model");
  o.erosion = e == "halt"      ? physics::ErosionModel::kHalt
              : e == "balance" ? physics::ErosionModel::kBalance
                               : physics::ErosionModel::kNone;
  o.v_eros = 100.0 * cfg.real("erosion.v_eros_m_s");
  o.w_eros = cfg.real("erosion.width");
  o.f_s = cfg.real("erosion.f_s");
  o.eps_eros = cfg.real("erosion.eps_eros");
  o.st_small = cfg.real("erosion.St_small");
  o.fragmentation = cfg.flag("fragmentation.enabled");
  o.bouncing = cfg.flag("bouncing.enabled");
  o.phi_bounce = cfg.real("bouncing.phi_bounce");
  return o;
}

DustTransportOptions transport_options_from_config(const Config& cfg) {
  return {cfg.flag("transport.drift"), cfg.flag("transport.diffusion"),
          cfg.str("transport.advection") == "van_leer",
          cfg.str("model.kind") == "single_size" &&
              cfg.str("transport.face_stokes") == "upwind"};
}

PlanetesimalOptions planetesimal_options_from_config(const Config& cfg) {
  PlanetesimalOptions po;
  po.coagulation = cfg.flag("planetesimals.coagulation");
  po.st_pl = cfg.real("planetesimals.St_pl");
  po.tau_pl_omega = cfg.real("planetesimals.tau_pl_omega");
  const auto& si = cfg.str("planetesimals.si");
  po.si = si == "d16"     ? StreamingInstability::kD16
          : si == "s18"   ? StreamingInstability::kS18
          : si == "zcrit" ? StreamingInstability::kZcrit
                          : StreamingInstability::kNone;
  po.zeta = si == "s18"     ? cfg.real("planetesimals.zeta_s18")
            : si == "zcrit" ? cfg.real("planetesimals.zeta_zcrit")
                            : cfg.real("planetesimals.zeta_d16");
  po.st_si_min = cfg.real("planetesimals.St_si_min");
  po.eps_crit = cfg.real("planetesimals.eps_crit");
  return po;
}

double atol_sigma_from_config(const Config& cfg) {
  const double set = cfg.real("solver.atol_sigma");
  if (set > 0.0) return set;
  // 0 = by model. A porous distribution resolves its bins' porosity down to this mass
  // (the empty-bin scale of physics/coagulation/porosity.hpp): at 1e-8 the porous
  // DustPy disk spent most of its steps on the volume of bins of unresolved mass, at
  // 1e-10 it takes 0.45x the CPU, and the porous MMSN 1.08x, both closer to a reference
  // at rtol 1e-5 (tests/bench/results/porous_cost.md, "The empty-bin scale"). The rest
  // keep 1e-8 (single size: performance_log.md, 45306ca; compact distributions: the
  // DustPy comparison, dustpy_anchor.md). Porosity on the track (porosity.bins =
  // "track") has no psi to resolve, but takes 1e-10 too: its runs were measured so
  // (tests/bench/results/porosity_track.md), 1e-8 was not.
  const bool porous_distribution =
      cfg.str("model.kind") == "distribution" && cfg.flag("porosity.enabled");
  return porous_distribution ? physics::coagulation::kPorousEmptyBinFraction : 1e-8;
}

}  // namespace panoptic
