#include "src/observe/observe.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "physics/mie.hpp"
#include "physics/optical_constants.hpp"
#include "src/core/error.hpp"
#include "src/core/units.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"
#include "src/model/scene_to_physics.hpp"
#include "src/observe/observe_image.hpp"
#include "src/scene/config.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

using cplx = std::complex<double>;

//! What `observe` needs of one snapshot of a run file.
struct Snapshot {
  std::string config_toml, run_id;
  long index = 0;
  double time_yr = 0.0;
  std::vector<double> r_c_au, r_f_au, T, sigma_d, a, phi, rho_int;
  double r_snow_au = std::numeric_limits<double>::quiet_NaN();
};

std::vector<double> row(hid_t g, const std::string& name, long k, std::size_t width,
                        const std::string& file) {
  const std::vector<double> all = h5::read_doubles(g, name);
  if (all.size() < (static_cast<std::size_t>(k) + 1) * width)
    throw ConfigError(file + ": /snapshots/" + name +
                      " has fewer rows than /snapshots/time" +
                      ": the file is damaged or not a panoptic run");
  return {all.begin() + static_cast<std::ptrdiff_t>(k * width),
          all.begin() + static_cast<std::ptrdiff_t>((k + 1) * width)};
}

Snapshot read_snapshot(const std::string& file, double time_yr) {
  h5::quiet_errors();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw ConfigError(file +
                      (fs::exists(file, ec) ? ": not a regular file (a directory?)"
                                            : ": no such file") +
                      "; give the HDF5 output of `panoptic run`");
  h5::Handle f;
  try {
    f = h5::open_file(file, false);
  } catch (const IoError&) {
    throw ConfigError(file + ": not an HDF5 file; give the output of `panoptic run`");
  }
  for (const char* p :
       {"snapshots/time", "snapshots/sigma_d", "grid/r_c", "grid/r_f", "disk/T"})
    if (!h5::exists(f.get(), "snapshots") || !h5::exists(f.get(), "grid") ||
        !h5::exists(f.get(), "disk") || !h5::exists(f.get(), p) ||
        !h5::has_attr(f.get(), "config_toml"))
      throw ConfigError(
          file + ": not a panoptic run (no /" + p +
          " or no config_toml attribute); give the output of `panoptic run`");
  Snapshot s;
  s.config_toml = h5::get_attr_string(f.get(), "config_toml");
  if (h5::has_attr(f.get(), "run_id")) s.run_id = h5::get_attr_string(f.get(), "run_id");
  h5::Handle grid = h5::open_group(f.get(), "grid");
  s.r_c_au = h5::read_doubles(grid.get(), "r_c");
  s.r_f_au = h5::read_doubles(grid.get(), "r_f");
  h5::Handle disk = h5::open_group(f.get(), "disk");
  s.T = h5::read_doubles(disk.get(), "T");
  if (h5::has_attr(disk.get(), "r_snow_au"))
    s.r_snow_au = h5::get_attr_double(disk.get(), "r_snow_au");
  const std::size_t n = s.r_c_au.size();
  if (n == 0 || s.r_f_au.size() != n + 1 || s.T.size() != n)
    throw ConfigError(file + ": /grid and /disk/T disagree in size: damaged file");
  h5::Handle snap = h5::open_group(f.get(), "snapshots");
  const std::vector<double> times = h5::read_doubles(snap.get(), "time");
  if (times.empty()) throw ConfigError(file + ": holds no snapshot yet");
  // time must lie within the run (a hair of round-off allowed at the end)
  const double t_last = times.back();
  if (!(time_yr >= 0.0) || time_yr > t_last * (1.0 + 1e-9))
    throw ConfigError("--time-yr " + num(time_yr) + ": outside the run (snapshots from " +
                      num(times.front()) + " to " + num(t_last) + " yr in " + file +
                      "); choose a time in that range");
  long best = 0;
  for (std::size_t k = 1; k < times.size(); ++k)
    if (std::abs(times[k] - time_yr) < std::abs(times[best] - time_yr))
      best = static_cast<long>(k);
  s.index = best;
  s.time_yr = times[best];
  s.sigma_d = row(snap.get(), "sigma_d", best, n, file);
  if (h5::exists(snap.get(), "a")) {
    s.a = row(snap.get(), "a", best, n, file);
    s.phi = row(snap.get(), "phi", best, n, file);
    s.rho_int = row(snap.get(), "rho_int", best, n, file);
  }
  return s;
}

//! Optical constants of the three materials, from the scene's [observe] keys.
struct Materials {
  physics::OpticalTable ice, sil;
  std::string outer, rule;
  double f_sil_volume = 0.0;            //!< silicate volume fraction of the mix
  double rho_ice = 0.0, rho_sil = 0.0;  //!< densities of the optical solids [g cm^-3]
  //! Density of the solid whose optical constants the outer particles get [g cm^-3].
  double outer_density() const {
    if (outer == "ice") return rho_ice;
    if (outer == "sil") return rho_sil;
    return (1.0 - f_sil_volume) * rho_ice + f_sil_volume * rho_sil;
  }
  cplx outer_index(double lambda_mm) const {
    if (outer == "ice") return ice.at(lambda_mm);
    if (outer == "sil") return sil.at(lambda_mm);
    const cplx e_ice = ice.at(lambda_mm) * ice.at(lambda_mm);
    const cplx e_sil = sil.at(lambda_mm) * sil.at(lambda_mm);
    const cplx e = rule == "bruggeman"
                       ? physics::bruggeman(e_ice, e_sil, f_sil_volume)
                       : physics::maxwell_garnett(e_ice, e_sil, f_sil_volume);
    cplx m = std::sqrt(e);
    return m.imag() < 0.0 ? -m : m;
  }
};

void write_array(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims,
                 const std::vector<double>& data, const std::string& units,
                 const std::string& description) {
  h5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                   H5Sclose);
  h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (dims.size() == 3) {  // images: chunk per wavelength, compressed
    const hsize_t chunk[3] = {1, dims[1], dims[2]};
    H5Pset_chunk(dcpl.get(), 3, chunk);
    H5Pset_deflate(dcpl.get(), 4);
  }
  h5::Handle ds(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                           dcpl.get(), H5P_DEFAULT),
                H5Dclose);
  if (!space.valid() || !ds.valid() ||
      H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) <
          0)
    throw IoError("HDF5: writing dataset " + name + " failed");
  h5::set_attr(ds.get(), "units", units);
  h5::set_attr(ds.get(), "description", description);
}

}  // namespace

double planck_nu(double nu, double T) {
  using namespace units;
  const double x = kPlanck * nu / (kBoltzmann * T);
  return 2.0 * kPlanck * nu * nu * nu / (kLightSpeed * kLightSpeed) / std::expm1(x);
}

double slab_intensity_jy_arcsec2(double nu, double T, double tau, double mu) {
  using namespace units;
  const double b = planck_nu(nu, T) / kJansky / (kArcsecPerRad * kArcsecPerRad);
  return b * -std::expm1(-tau / mu);
}

int observe(const ObserveArgs& a) {
  // 1 arguments (before the file is read: a bad argument costs nothing)
  if (a.lambda_mm.empty())
    throw ConfigError("--lambda-mm: no wavelength given; e.g. --lambda-mm 0.87,1.3,3.0");
  for (const double l : a.lambda_mm)
    if (!(l > 0.0) || !std::isfinite(l))
      throw ConfigError("--lambda-mm " + num(l) + ": wavelengths must be > 0 [mm]");
  for (std::size_t i = 0; i < a.lambda_mm.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (a.lambda_mm[i] == a.lambda_mm[j])
        throw ConfigError("--lambda-mm: " + num(a.lambda_mm[i]) +
                          " mm given twice; give each wavelength once");
  if (!(a.distance_pc > 0.0) || !std::isfinite(a.distance_pc))
    throw ConfigError("--distance-pc " + num(a.distance_pc) + ": must be > 0 [pc]");
  if (!(a.incl_deg >= 0.0 && a.incl_deg < 90.0))
    throw ConfigError("--incl-deg " + num(a.incl_deg) +
                      ": must be in [0, 90) [deg] (a thin disk seen edge-on has no "
                      "projected area); 0 = face-on");
  if (!std::isfinite(a.pa_deg))
    throw ConfigError("--pa-deg " + num(a.pa_deg) + ": must be a finite angle [deg]");
  if (!(a.bmin_arcsec > 0.0) || !(a.bmaj_arcsec >= a.bmin_arcsec) ||
      !std::isfinite(a.bmaj_arcsec) || !std::isfinite(a.bpa_deg))
    throw ConfigError("--beam-arcsec " + num(a.bmaj_arcsec) + "," + num(a.bmin_arcsec) +
                      "," + num(a.bpa_deg) +
                      ": needs bmaj >= bmin > 0 [arcsec] and a finite PA [deg]");
  // 1 nm to 100 km: below, the Rayleigh-limit opacity overflows (1e-308 gave NaN)
  if (a.a_cm_given && !(a.a_cm >= 1e-7 && a.a_cm <= 1e7))
    throw ConfigError("--a-cm " + num(a.a_cm) +
                      ": must be >= 1e-7 and <= 1e7 [cm] (1 nm to 100 km)");
  for (const std::string& o : a.overrides)
    if (o.rfind("observe.", 0) != 0)
      throw ConfigError("--set " + o +
                        ": observe may change only observe.* keys (the run is done); "
                        "rerun the scene to change anything else");
  const fs::path out_path =
      a.output.empty()
          ? fs::path(fs::path(a.run_file).replace_extension("").string() + "_obs.h5")
          : fs::path(a.output);
  refuse_output_is_input(out_path, a.run_file, "the run file observe reads");
  const fs::path chk = checkpoint_path(a.run_file);  // nor the run's checkpoints
  for (const fs::path& c : {chk, previous_checkpoint_path(chk)})
    refuse_output_is_input(out_path, c, "a checkpoint of the run");
  refuse_to_replace(out_path, a.overwrite);
  std::error_code ec;

  // 2 the snapshot, and the scene of the run (with --set observe.* overrides)
  const Snapshot s = read_snapshot(a.run_file, a.time_yr);
  const Config cfg =
      load_scene_text(s.config_toml, a.run_file + ":config_toml", a.overrides);
  const std::size_t n = s.r_c_au.size();
  const double f_ice = cfg.real("snowline.f_ice");
  const double rho_ice = cfg.real("observe.water_ice_rho");
  const double rho_sil = cfg.real("material.sil_rho0");
  Materials mat{optical_table_from_config(cfg, "ice"),
                optical_table_from_config(cfg, "sil"),
                cfg.str("observe.outer_species"),
                cfg.str("observe.mix_rule"),
                (1.0 - f_ice) / rho_sil / (f_ice / rho_ice + (1.0 - f_ice) / rho_sil),
                rho_ice,
                rho_sil};
  for (const double l : a.lambda_mm) {
    const bool outer_ice = mat.outer != "sil";
    if (!mat.sil.covers(l) || (outer_ice && !mat.ice.covers(l)))
      throw ConfigError(
          "--lambda-mm " + num(l) + ": outside the optical-constant tables (" +
          "silicate " + num(mat.sil.lambda_min_mm()) + " - " +
          num(mat.sil.lambda_max_mm()) + " mm, ice " + num(mat.ice.lambda_min_mm()) +
          " - " + num(mat.ice.lambda_max_mm()) +
          " mm); extend observe.*_lambda_mm/_n/_k with --set");
  }
  // a snapshot of a run that failed can hold NaN (its last rows): say so, rather than
  // write an observation of NaN with exit 0
  for (const auto& [name, v] : {std::pair{"sigma_d", &s.sigma_d},
                                {"a", &s.a},
                                {"phi", &s.phi},
                                {"rho_int", &s.rho_int},
                                {"T", &s.T}})
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!std::isfinite((*v)[i]))
        throw ConfigError(a.run_file + ": snapshot " + std::to_string(s.index) +
                          " (t = " + num(s.time_yr) + " yr) has " + name + " = " +
                          num((*v)[i]) + " at r = " + num(s.r_c_au[i]) +
                          " au: not a state to observe (did the run fail? its exit code "
                          "and /solver status say); choose another --time-yr");
  const bool has_size = !s.a.empty();
  if (!has_size && !(a.a_cm_given))
    throw ConfigError(a.run_file +
                      ": the run has no particle sizes (/snapshots/a: growth was off); "
                      "give one with --a-cm");
  // r_snow_au is +inf for a disk warmer than T_sub everywhere (all silicate), 0 for one
  // colder everywhere; NaN (a run without a snow line) compares false
  const bool snowline = cfg.flag("snowline.enabled");
  std::vector<int> inner(n);
  for (std::size_t i = 0; i < n; ++i) inner[i] = snowline && s.r_c_au[i] < s.r_snow_au;

  // 3 opacity, optical depth and intensity per cell and wavelength
  const std::size_t nl = a.lambda_mm.size();
  const double mu = std::cos(a.incl_deg * units::kPi / 180.0);
  // The particle's mass and size are the run's (rho_int = phi rho0 of its monomers); its
  // optical solid has the density of the material whose constants it gets (silicate,
  // water ice of observe.water_ice_rho, or their mix), so the volume fraction of that
  // solid, the filling factor of the mixing rule, is rho_int / rho_solid: the run's phi
  // when the densities agree (the default mix: 1.408 against material.ice_rho0 = 1.4).
  // A compact grain (--a-cm, or a run without sizes) is of the optical solid itself.
  std::vector<double> a_cm(n), phi(n), rho(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double rho_solid = inner[i] ? mat.rho_sil : mat.outer_density();
    const bool compact = a.a_cm_given || !has_size;
    a_cm[i] = a.a_cm_given ? a.a_cm : s.a[i];
    rho[i] = compact ? rho_solid : s.rho_int[i];
    phi[i] = compact ? 1.0 : std::min(1.0, s.rho_int[i] / rho_solid);
  }
  std::vector<double> kappa(nl * n), tau(nl * n), inten(nl * n), bnu(nl * n), nu(nl);
  for (std::size_t l = 0; l < nl; ++l) {
    const double lambda_cm = a.lambda_mm[l] * 0.1;
    nu[l] = units::kLightSpeed / lambda_cm;
    const cplx m_sil = mat.sil.at(a.lambda_mm[l]),
               m_out = mat.outer_index(a.lambda_mm[l]);
    for (std::size_t i = 0; i < n; ++i) {
      const cplx m = physics::porous_index(inner[i] ? m_sil : m_out, phi[i]);
      const std::size_t k = l * n + i;
      kappa[k] = physics::kappa_abs(m, a_cm[i], rho[i], lambda_cm);
      tau[k] = s.sigma_d[i] * kappa[k];
      inten[k] = slab_intensity_jy_arcsec2(nu[l], s.T[i], tau[k], mu);
      bnu[k] = slab_intensity_jy_arcsec2(nu[l], s.T[i], 1e300, 1.0);
    }
  }

  // 4 images: pixel from the beam, field = disk + margin; projection; convolution
  // angles reduced to one turn first: sin and cos of a huge angle lose all precision
  const DiskOrientation orient{a.incl_deg * units::kPi / 180.0,
                               std::fmod(a.pa_deg, 360.0) * units::kPi / 180.0};
  const Beam beam{a.bmaj_arcsec, a.bmin_arcsec,
                  std::fmod(a.bpa_deg, 360.0) * units::kPi / 180.0};
  const double r_out_arcsec = s.r_f_au.back() / a.distance_pc;
  SkyGrid grid;
  grid.pixel = a.bmin_arcsec / kPixelsPerBeamMinor;
  const double half = r_out_arcsec + kFieldMarginBeams * a.bmaj_arcsec;
  const double n_side = 2.0 * std::ceil(half / grid.pixel) + 1.0;
  if (n_side > kMaxImageSide)
    throw ConfigError("--beam-arcsec " + num(a.bmaj_arcsec) + "," + num(a.bmin_arcsec) +
                      ": the image would need " + num(n_side) + " x " + num(n_side) +
                      " pixels (" + std::to_string(kPixelsPerBeamMinor) +
                      " per bmin over the disk, " + num(2.0 * half) +
                      " arcsec); the limit is " + std::to_string(kMaxImageSide) +
                      ": use a larger beam or a larger --distance-pc");
  grid.n = static_cast<int>(n_side);
  // Nearly edge-on the projected disk is thinner than a pixel: its flux is still exact
  // (DiskProjector), but neither the image nor the deprojected profile then resolves
  // anything across the minor axis (with point samples the image missed the disk
  // altogether, flux 0 at i = 89.999999 deg, PA 30). Require the projected minor axis
  // to span a few pixels. (Only where the inclination thins it: a disk smaller than the
  // beam's pixels is observed face-on or inclined alike, as a point source.)
  const double major_px = 2.0 * r_out_arcsec / grid.pixel, minor_px = major_px * mu;
  if (minor_px < std::min(kMinMinorAxisPixels, 0.5 * major_px))
    throw ConfigError("--incl-deg " + num(a.incl_deg) +
                      ": the disk's projected minor "
                      "axis would be " +
                      num(minor_px) + " pixels (" + num(grid.pixel) +
                      " arcsec each, from the beam), fewer than " +
                      num(kMinMinorAxisPixels) +
                      " to sample it; use a smaller inclination or a smaller beam");
  std::vector<double> edges_arcsec(n + 1);
  for (std::size_t i = 0; i <= n; ++i) edges_arcsec[i] = s.r_f_au[i] / a.distance_pc;
  const DiskProjector projector(grid, orient, edges_arcsec);
  BeamConvolver convolver(grid.n, grid.pixel, beam);  // plans made once, reused below
  const std::size_t npix = static_cast<std::size_t>(grid.n) * grid.n;
  const double dr = grid.pixel;
  const RadialProfile geometry =
      radial_profile(std::vector<double>(npix, 0.0), grid, orient, dr, r_out_arcsec);
  const std::size_t nb = geometry.r_mid.size();
  std::vector<double> img_model(nl * npix), img_conv(nl * npix);
  // The flux summed over the cells' projected annuli, I_i mu pi (r_o^2 - r_i^2) / d^2
  // [arcsec^2]: independent of the pixels, the check of the image-summed fluxes.
  std::vector<double> flux_annuli(nl, 0.0);
  for (std::size_t l = 0; l < nl; ++l)
    for (std::size_t i = 0; i < n; ++i)
      flux_annuli[l] +=
          inten[l * n + i] * mu * units::kPi *
          (edges_arcsec[i + 1] * edges_arcsec[i + 1] - edges_arcsec[i] * edges_arcsec[i]);
  std::vector<double> prof_conv(nl * nb), prof_model(nl * nb), flux_model(nl),
      flux_conv(nl);
  const double pix2 = grid.pixel * grid.pixel;
  for (std::size_t l = 0; l < nl; ++l) {
    const std::vector<double> model =
        projector.image(std::span<const double>(inten).subspan(l * n, n));
    std::vector<double> conv = convolver.convolve(model);
    double fm = 0.0, fc = 0.0;
    for (std::size_t p = 0; p < npix; ++p) {
      fm += model[p] * pix2;
      fc += conv[p] * pix2;
      conv[p] *= beam.area();  // Jy/arcsec^2 -> Jy/beam
    }
    flux_model[l] = fm;
    flux_conv[l] = fc;
    const RadialProfile pc = radial_profile(conv, grid, orient, dr, r_out_arcsec);
    const RadialProfile pm = radial_profile(model, grid, orient, dr, r_out_arcsec);
    std::copy(pc.value.begin(), pc.value.end(), prof_conv.begin() + l * nb);
    std::copy(pm.value.begin(), pm.value.end(), prof_model.begin() + l * nb);
    std::copy(model.begin(), model.end(), img_model.begin() + l * npix);
    std::copy(conv.begin(), conv.end(), img_conv.begin() + l * npix);
  }

  // 5 spectral index between every pair (shorter first): alpha = ln(I1/I2) / ln(nu1/nu2)
  std::vector<double> pairs, alpha_prof, alpha_model, alpha_total;
  std::vector<std::size_t> order(nl);
  for (std::size_t l = 0; l < nl; ++l) order[l] = l;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return a.lambda_mm[x] < a.lambda_mm[y];
  });
  std::size_t np = 0;
  const auto alpha = [](double i1, double i2, double nu1, double nu2) {
    return i1 > 0.0 && i2 > 0.0 ? std::log(i1 / i2) / std::log(nu1 / nu2)
                                : std::numeric_limits<double>::quiet_NaN();
  };
  for (std::size_t p = 0; p < nl; ++p)
    for (std::size_t q = p + 1; q < nl; ++q) {
      const std::size_t l1 = order[p], l2 = order[q];
      pairs.push_back(a.lambda_mm[l1]);
      pairs.push_back(a.lambda_mm[l2]);
      for (std::size_t b = 0; b < nb; ++b)
        alpha_prof.push_back(
            alpha(prof_conv[l1 * nb + b], prof_conv[l2 * nb + b], nu[l1], nu[l2]));
      for (std::size_t i = 0; i < n; ++i)
        alpha_model.push_back(
            alpha(inten[l1 * n + i], inten[l2 * n + i], nu[l1], nu[l2]));
      alpha_total.push_back(alpha(flux_model[l1], flux_model[l2], nu[l1], nu[l2]));
      ++np;
    }

  // Every number an option can make non-finite (a beam or a particle far outside the
  // disk's scales), checked before anything is written.
  for (const auto& [name, v] : {std::pair{"kappa_abs", &kappa},
                                {"tau", &tau},
                                {"intensity", &inten},
                                {"model image", &img_model},
                                {"convolved image", &img_conv},
                                {"model flux", &flux_model},
                                {"annuli flux", &flux_annuli},
                                {"convolved flux", &flux_conv}})
    for (const double x : *v)
      if (!std::isfinite(x))
        throw ConfigError("the observation is not finite (" + std::string(name) + " = " +
                          num(x) +
                          "): the options are outside what the model can image; bring "
                          "--beam-arcsec, --a-cm and --distance-pc nearer to the disk's "
                          "scales");

  // The projection conserves each annulus's flux (DiskProjector): the image's flux is
  // the annuli's to round-off at any pixel size. Checked before anything is written.
  for (std::size_t l = 0; l < nl; ++l)
    if (!(std::abs(flux_model[l] - flux_annuli[l]) <=
          kFluxRoundOff * std::abs(flux_annuli[l])))
      throw std::logic_error("observe: at " + num(a.lambda_mm[l]) +
                             " mm the image's flux " + num(flux_model[l]) +
                             " Jy differs from the annuli's " + num(flux_annuli[l]) +
                             " Jy beyond round-off");

  // 6 output: written to <out>.tmp, renamed when whole
  if (out_path.has_parent_path()) fs::create_directories(out_path.parent_path(), ec);
  const fs::path tmp = out_path.string() + ".tmp";
  try {
    h5::Handle f = h5::create_file(tmp.string());
    const hid_t root = f.get();
    h5::set_attr(root, "run_file", fs::absolute(a.run_file).string());
    h5::set_attr(root, "run_id", s.run_id);
    h5::set_attr(root, "time_yr_requested", a.time_yr);
    h5::set_attr(root, "time_yr", s.time_yr);
    h5::set_attr(root, "snapshot_index", s.index);
    h5::set_attr(root, "distance_pc", a.distance_pc);
    h5::set_attr(root, "incl_deg", a.incl_deg);
    h5::set_attr(root, "pa_deg", a.pa_deg);
    h5::set_attr(root, "beam_bmaj_arcsec", a.bmaj_arcsec);
    h5::set_attr(root, "beam_bmin_arcsec", a.bmin_arcsec);
    h5::set_attr(root, "beam_pa_deg", a.bpa_deg);
    h5::set_attr(root, "beam_area_arcsec2", beam.area());
    h5::set_attr(root, "particle_size",
                 a.a_cm_given ? "--a-cm " + num(a.a_cm) + " in every cell (phi = 1)"
                              : std::string("the run's /snapshots/a, phi, rho_int"));
    h5::set_attr(root, "emission",
                 "absorption only (no scattering): I = B_nu(T) (1 - exp(-tau/cos i)), "
                 "tau = Sigma_d kappa_abs of the mass-dominating particle (one size per "
                 "cell), T = /disk/T of the run; geometrically thin disk");
    h5::set_attr(root, "opacity",
                 "Mie (Bohren & Huffman 1983 BHMIE, Wiscombe 1980 terms) for x <= 1e4, "
                 "geometric optics above; porosity by Maxwell-Garnett, solid in a vacuum "
                 "matrix (Kataoka et al. 2014 eq. 3); "
                 "inside the snow line silicate, outside observe.outer_species = " +
                     mat.outer + " (" + mat.rule + ", silicate volume fraction " +
                     num(mat.f_sil_volume) + ")");
    h5::set_attr(root, "config_toml", cfg.resolved_toml());
    h5::set_attr(root, "git_sha", std::string(PANOPTIC_GIT_SHA));
    h5::set_attr(root, "version", std::string(PANOPTIC_VERSION));
    const hsize_t hl = nl, hn = n, hb = nb, hp = grid.n, hnp = np;
    write_array(root, "wavelength_mm", {hl}, a.lambda_mm, "mm", "observed wavelengths");
    std::vector<double> nu_ghz(nl);
    for (std::size_t l = 0; l < nl; ++l) nu_ghz[l] = nu[l] * 1e-9;
    write_array(root, "frequency_GHz", {hl}, nu_ghz, "GHz", "c / wavelength");
    {
      h5::Handle g = h5::create_group(root, "model");
      write_array(g.get(), "r_au", {hn}, s.r_c_au, "au", "cell centres");
      write_array(g.get(), "r_f_au", {hn + 1}, s.r_f_au, "au", "cell faces");
      write_array(g.get(), "T", {hn}, s.T, "K",
                  "dust temperature (= /disk/T of the run)");
      write_array(g.get(), "sigma_d", {hn}, s.sigma_d, "g cm^-2",
                  "dust surface density of the snapshot");
      write_array(g.get(), "a", {hn}, a_cm, "cm", "particle radius used");
      write_array(g.get(), "phi", {hn}, phi, "",
                  "filling factor used: volume fraction of the optical solid, rho_int / "
                  "its density (at most 1)");
      write_array(g.get(), "rho_int", {hn}, rho, "g cm^-3", "internal density used");
      std::vector<double> sp(n);
      for (std::size_t i = 0; i < n; ++i) sp[i] = inner[i];
      write_array(g.get(), "inner_species", {hn}, sp, "",
                  "1: silicate (inside the snow line), 0: observe.outer_species");
      write_array(g.get(), "kappa_abs", {hl, hn}, kappa, "cm^2 g^-1",
                  "absorption opacity per gram of dust");
      write_array(g.get(), "tau", {hl, hn}, tau, "",
                  "vertical optical depth Sigma_d kappa_abs");
      write_array(g.get(), "intensity", {hl, hn}, inten, "Jy arcsec^-2",
                  "B_nu(T) (1 - exp(-tau / cos i)) at the cell centres");
      write_array(g.get(), "B_nu", {hl, hn}, bnu, "Jy arcsec^-2",
                  "Planck function B_nu(T)");
    }
    {
      h5::Handle g = h5::create_group(root, "image");
      std::vector<double> xs(grid.n);
      for (int j = 0; j < grid.n; ++j) xs[j] = grid.coord(j);
      write_array(g.get(), "x_arcsec", {hp}, xs, "arcsec",
                  "offset to the east of pixel centres (axis 2; display east left)");
      write_array(g.get(), "y_arcsec", {hp}, xs, "arcsec",
                  "offset to the north of pixel centres (axis 1)");
      write_array(g.get(), "model", {hl, hp, hp}, img_model, "Jy arcsec^-2",
                  "model image before the beam, [wavelength][y][x]");
      write_array(g.get(), "convolved", {hl, hp, hp}, img_conv, "Jy beam^-1",
                  "image convolved with the beam, [wavelength][y][x]");
      h5::set_attr(g.get(), "pixel_arcsec", grid.pixel);
      h5::set_attr(g.get(), "padded_size", static_cast<long>(convolver.padded_size()));
      h5::set_attr(g.get(), "kernel_half_width_px",
                   static_cast<long>(convolver.kernel_half_width()));
    }
    {
      h5::Handle g = h5::create_group(root, "profile");
      std::vector<double> r_au(nb);
      for (std::size_t b = 0; b < nb; ++b) r_au[b] = geometry.r_mid[b] * a.distance_pc;
      write_array(g.get(), "r_arcsec", {hb}, geometry.r_mid, "arcsec",
                  "deprojected radius of the bin centres");
      write_array(g.get(), "r_au", {hb}, r_au, "au",
                  "deprojected radius of the bin centres");
      write_array(g.get(), "count", {hb}, geometry.count, "", "pixels in each bin");
      write_array(g.get(), "convolved", {hl, hb}, prof_conv, "Jy beam^-1",
                  "azimuthal mean of the convolved image over deprojected annuli (NaN: "
                  "no pixel)");
      write_array(g.get(), "model", {hl, hb}, prof_model, "Jy arcsec^-2",
                  "azimuthal mean of the model image over deprojected annuli");
    }
    {
      h5::Handle g = h5::create_group(root, "flux");
      write_array(g.get(), "model", {hl}, flux_model, "Jy",
                  "total flux of the model image");
      write_array(g.get(), "convolved", {hl}, flux_conv, "Jy",
                  "total flux of the convolved image (sum x pixel area / beam area)");
      write_array(g.get(), "annuli", {hl}, flux_annuli, "Jy",
                  "total flux summed over the cells' projected annuli (independent of "
                  "the pixels: the check of model and convolved)");
    }
    {
      h5::Handle g = h5::create_group(root, "spectral_index");
      write_array(g.get(), "pairs_mm", {hnp, 2}, pairs, "mm",
                  "wavelength pairs (shorter, longer)");
      write_array(g.get(), "profile", {hnp, hb}, alpha_prof, "",
                  "ln(I1/I2)/ln(nu1/nu2) of the convolved radial profiles");
      write_array(g.get(), "model", {hnp, hn}, alpha_model, "",
                  "ln(I1/I2)/ln(nu1/nu2) of the model intensity at the cell centres");
      write_array(g.get(), "total", {hnp}, alpha_total, "", "of the total fluxes");
    }
    H5Fflush(root, H5F_SCOPE_GLOBAL);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, out_path, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() sets ec again
    fs::remove(tmp, ec);
    throw IoError(out_path.string() + ": cannot rename the finished file into place (" +
                  why + ")");
  }

  // 7 report
  std::printf("panoptic observe: %s, snapshot %ld at t = %.6g yr (asked %.6g yr)\n",
              a.run_file.c_str(), s.index, s.time_yr, a.time_yr);
  std::printf(
      "  d = %g pc, i = %g deg, PA = %g deg; beam %g x %g arcsec at %g deg; "
      "%d x %d pixels of %.4g arcsec (FFT %d^2)\n",
      a.distance_pc, a.incl_deg, a.pa_deg, a.bmaj_arcsec, a.bmin_arcsec, a.bpa_deg,
      grid.n, grid.n, grid.pixel, convolver.padded_size());
  for (std::size_t l = 0; l < nl; ++l) {
    std::printf(
        "  %6.3g mm: flux %.6g Jy (after the beam %.6g Jy; over the annuli %.6g Jy), max "
        "tau %.3g\n",
        a.lambda_mm[l], flux_model[l], flux_conv[l], flux_annuli[l],
        *std::max_element(tau.begin() + l * n, tau.begin() + (l + 1) * n));
  }
  for (std::size_t p = 0; p < np; ++p)
    std::printf("  alpha(%g-%g mm) of the total flux: %.4g\n", pairs[2 * p],
                pairs[2 * p + 1], alpha_total[p]);
  std::printf("  -> %s\n", out_path.c_str());
  return 0;
}

}  // namespace panoptic
