#include "src/model/track.hpp"

#include <cmath>
#include <memory>
#include <sstream>

#include "disk/disk_local_gas.hpp"
#include "disk/gas_disk.hpp"
#include "disk/local_gas.hpp"
#include "physics/growth_rates.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/solver/cvode_integrator.hpp"

namespace panoptic {
namespace {

//! The track as an ODE system: y = (r/r0, ln(m/m_ref), ln(1/phi)) as global variables.
class TrackModel : public PhysicsModule {
 public:
  TrackModel(StateLayout& layout, const Config& cfg, double r0)
      : disk_(make_disk(disk_params_from_config(cfg))),
        opt_(growth_options_from_config(cfg)),
        ice_(species_from_config(cfg, "ice")),
        sil_(species_from_config(cfg, "sil")),
        z_(cfg.real("dust.dust_to_gas")),
        r0_(r0),
        r_snow_(cfg.flag("snowline.enabled") ? disk_->r_snow() : 0.0) {
    for (const char* name : {"r", "ln_m", "ln_inv_phi"})
      layout.add_global_var({name, "", "track variable", 1.0, false});
  }
  std::string_view name() const override { return "track"; }
  void declare_pattern(PatternBuilder& p) const override {
    for (long i = 0; i < 3; ++i)
      for (long j = 0; j < 3; ++j) p.add(i, j);
  }
  void add_rhs(double, std::span<const double> y, std::span<double> f) const override {
    double d[3];
    rates(y.data(), d);
    for (int i = 0; i < 3; ++i) f[i] += d[i];
  }
  //! One-sided differences: three state variables, a cheap and near-exact Jacobian.
  void add_jacobian(double, std::span<const double> y,
                    JacobianValues& jac) const override {
    double f0[3], f1[3], yp[3] = {y[0], y[1], y[2]};
    rates(yp, f0);
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-7 * std::max(std::abs(y[j]), 1.0);
      yp[j] = y[j] + h;
      rates(yp, f1);
      yp[j] = y[j];
      for (int i = 0; i < 3; ++i) jac.add(i, j, (f1[i] - f0[i]) / h);
    }
  }

  //! The particle described by state y.
  TrackPoint point(double t, const double* y) const {
    TrackPoint p;
    p.t = t;
    p.r = y[0] * r0_;
    const auto& sp = species(p.r);
    p.m = mass(y, sp);
    p.phi = opt_.porosity ? std::exp(-physics::softplus(y[2], 100.0)) : 1.0;
    p.a = physics::radius(p.m, p.phi, sp.rho0);
    p.St = physics::stokes_number(p.m, p.phi, sp.rho0, gas(p.r), opt_.drag);
    return p;
  }

 private:
  const physics::Species& species(double r) const { return r < r_snow_ ? sil_ : ice_; }
  double mass(const double* y, const physics::Species& sp) const {
    // m >= m0 of the species, softly (as on the grid)
    const double x_lo = std::log(sp.m0 / ice_.m0);
    return ice_.m0 * std::exp(x_lo + physics::softplus(y[1] - x_lo, 100.0));
  }
  physics::LocalGas gas(double r) const {
    // dlnP/dlnr of the profile at r, by a centred difference (spec §1.4)
    const double h = 1e-4;
    auto lnp = [&](double x) { return std::log(disk_->pressure(disk_->sigma_g(x), x)); };
    const double dlnp =
        (lnp(r * (1 + h)) - lnp(r * (1 - h))) / (std::log1p(h) - std::log1p(-h));
    return local_gas_at(*disk_, r, disk_->sigma_g(r), dlnp);
  }
  void rates(const double* y, double* d) const {
    const TrackPoint p = point(0.0, y);
    const auto g = gas(p.r);
    const auto r =
        physics::particle_rates(z_ * g.sigma_g, p.m, p.phi, p.St, g, species(p.r), opt_);
    d[0] = physics::v_radial_drift(p.St, g) / r0_;  // spec §3.2, §6.1 (static gas)
    d[1] = r.dlnm_dt;
    d[2] = opt_.porosity ? -r.dlnphi_dt : 0.0;
  }

  std::unique_ptr<GasDisk> disk_;
  physics::GrowthOptions opt_;
  physics::Species ice_, sil_;
  double z_, r0_, r_snow_;
};

struct Stop {};

}  // namespace

TrackResult track_particle(const Config& cfg, double r0, double a_stop, double t_max) {
  auto layout = std::make_shared<StateLayout>(0);
  auto module = std::make_unique<TrackModel>(*layout, cfg, r0);
  const TrackModel& track = *module;
  layout->freeze();
  std::vector<std::unique_ptr<PhysicsModule>> modules;
  modules.push_back(std::move(module));
  DiskModel model(layout, std::move(modules));

  const double y0[3] = {1.0, 0.0, 0.0};  // a monomer at r0 (ice m0 outside the snow line)
  IntegratorOptions opt;
  opt.rtol = cfg.real("solver.rtol");
  opt.atol = {1e-10, 1e-8, 1e-8};
  opt.max_steps = cfg.integer("solver.max_steps");
  CvodeIntegrator cvode(model, 0.0, y0, opt);

  TrackResult out;
  out.points.push_back(track.point(0.0, y0));
  if (!(out.points.front().a < a_stop)) {  // it ended at once, at a negative time
    std::ostringstream m;
    m << "--a-stop-cm " << a_stop
      << ": the released monomer is already a = " << out.points.front().a
      << " cm; give a larger stop size";
    throw ConfigError(m.str());
  }
  const double r_in = cfg.real("grid.r_in_au") * units::kAu;
  try {
    cvode.advance_to(t_max, [&](double t, long) {
      const TrackPoint p = track.point(t, cvode.state().data());
      out.points.push_back(p);
      if (p.a >= a_stop || p.r <= r_in) throw Stop{};
    });
  } catch (const Stop&) {
  }
  out.steps = cvode.stats().nst;
  const TrackPoint& last = out.points.back();
  if (last.a >= a_stop && out.points.size() >= 2) {
    // interpolate in ln a between the last two steps
    const TrackPoint& prev = out.points[out.points.size() - 2];
    const double w = std::log(a_stop / prev.a) / std::log(last.a / prev.a);
    out.reached = true;
    out.at_stop = last;
    out.at_stop.t = prev.t + w * (last.t - prev.t);
    out.at_stop.r = prev.r + w * (last.r - prev.r);
    out.at_stop.a = a_stop;
    const auto log_interp = [w](double x0, double x1) {
      return x0 > 0.0 && x1 > 0.0 ? x0 * std::exp(w * std::log(x1 / x0)) : x1;
    };
    out.at_stop.m = log_interp(prev.m, last.m);
    out.at_stop.phi = log_interp(prev.phi, last.phi);
    out.at_stop.St = log_interp(prev.St, last.St);
  }
  return out;
}

}  // namespace panoptic
