#include "src/observe/observation_file.hpp"

#include <cstddef>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "build_info.hpp"  // PANOPTIC_GIT_SHA (generated at build time)
#include "src/core/error.hpp"
#include "src/io/durable_file.hpp"
#include "src/io/h5.hpp"

namespace fs = std::filesystem;

namespace panoptic {
namespace {

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

//! The root's attributes: where the observation comes from and how it was made.
void write_provenance(hid_t root, const Observation& o) {
  const ObserveArgs& a = o.args;
  const OpticalMaterials& mat = o.materials;
  h5::set_attr(root, "run_file", fs::absolute(a.run_file).string());
  h5::set_attr(root, "run_id", o.snapshot.run_id);
  h5::set_attr(root, "time_yr_requested", a.time_yr);
  h5::set_attr(root, "time_yr", o.snapshot.time_yr);
  h5::set_attr(root, "snapshot_index", o.snapshot.index);
  // how it is seen
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"distance_pc", a.distance_pc},
        {"incl_deg", a.incl_deg},
        {"pa_deg", a.pa_deg},
        {"beam_bmaj_arcsec", a.bmaj_arcsec},
        {"beam_bmin_arcsec", a.bmin_arcsec},
        {"beam_pa_deg", a.bpa_deg},
        {"beam_area_arcsec2", o.images.beam.area()}})
    h5::set_attr(root, name, value);
  const bool distribution = !o.particles.bins.empty();
  h5::set_attr(root, "particle_size",
               a.a_cm_given ? "--a-cm " + num(a.a_cm) + " in every cell (phi = 1)"
               : distribution
                   ? std::string("the run's size distribution: every bin of "
                                 "/snapshots/sigma holding dust, mass /grid/m_bins, "
                                 "filling factor /snapshots/phi_bins (1 when "
                                 "compact); /model/a, phi, rho_int: its "
                                 "mass-dominating bin")
                   : std::string("the run's /snapshots/a, phi, rho_int"));
  h5::set_attr(
      root, "emission",
      "absorption only (no scattering): I = B_nu(T) (1 - exp(-tau/cos i)), "
      "tau = Sigma_d kappa_abs of the " +
          std::string(distribution ? "size distribution (Sum_k sigma_k kappa_abs,k)"
                                   : "mass-dominating particle (one size per cell)") +
          ", T = /disk/T of the run; geometrically thin disk");
  h5::set_attr(
      root, "opacity",
      std::string(distribution ? "of the size distribution: kappa_abs = Sum_k sigma_k "
                                 "kappa_abs,k / Sigma_d over the bins, each bin's "
                                 "aggregate (radius a_k, filling factor phi_k) by "
                               : "") +
          "Mie (Bohren & Huffman 1983 BHMIE, Wiscombe 1980 terms) for x <= 1e4, "
          "geometric optics above; porosity by Maxwell-Garnett, solid in a "
          "vacuum matrix (Kataoka et al. 2014 eq. 3); "
          "inside the snow line silicate, outside observe.outer_species = " +
          mat.outer + " (" + mat.rule + ", silicate volume fraction " +
          num(mat.f_sil_volume) + ")");
  h5::set_attr(root, "config_toml", o.scene_toml);
  h5::set_attr(root, "git_sha", std::string(PANOPTIC_GIT_SHA));
  h5::set_attr(root, "version", std::string(PANOPTIC_VERSION));
}

void write_contents(hid_t root, const Observation& o) {
  const RunSnapshot& s = o.snapshot;
  const CellParticles& p = o.particles;
  const CellEmission& e = o.emission;
  const SkyImages& im = o.images;
  const SpectralIndex& alpha = o.alpha;
  const std::size_t nl = o.args.lambda_mm.size(), n = e.n_cells,
                    nb = im.r_mid_arcsec.size();
  const hsize_t hl = nl, hn = n, hb = nb, hp = im.grid.n, hnp = alpha.n_pairs;
  write_array(root, "wavelength_mm", {hl}, o.args.lambda_mm, "mm",
              "observed wavelengths");
  std::vector<double> nu_ghz(nl);
  for (std::size_t l = 0; l < nl; ++l) nu_ghz[l] = e.nu[l] * 1e-9;
  write_array(root, "frequency_GHz", {hl}, nu_ghz, "GHz", "c / wavelength");
  {
    h5::Handle g = h5::create_group(root, "model");
    write_array(g.get(), "r_au", {hn}, s.r_c_au, "au", "cell centres");
    write_array(g.get(), "r_f_au", {hn + 1}, s.r_f_au, "au", "cell faces");
    write_array(g.get(), "T", {hn}, s.T, "K", "dust temperature (= /disk/T of the run)");
    write_array(g.get(), "sigma_d", {hn}, s.sigma_d, "g cm^-2",
                "dust surface density of the snapshot");
    // a size distribution: the mass-dominating bin's (the opacity is all the bins')
    const std::string of = p.bins.empty() ? " used" : " of the mass-dominating bin";
    write_array(g.get(), "a", {hn}, p.a_cm, "cm", "particle radius" + of);
    write_array(g.get(), "phi", {hn}, p.phi, "",
                "filling factor" + of +
                    ": volume fraction of the optical solid, rho_int / its density (at "
                    "most 1)");
    write_array(g.get(), "rho_int", {hn}, p.rho, "g cm^-3", "internal density" + of);
    const std::vector<double> sp(p.inner.begin(), p.inner.end());
    write_array(g.get(), "inner_species", {hn}, sp, "",
                "1: silicate (inside the snow line), 0: observe.outer_species");
    write_array(g.get(), "kappa_abs", {hl, hn}, e.kappa_abs, "cm^2 g^-1",
                p.bins.empty() ? "absorption opacity per gram of dust"
                               : "absorption opacity per gram of dust of the size "
                                 "distribution, Sum_k sigma_k kappa_abs,k / Sigma_d");
    write_array(g.get(), "tau", {hl, hn}, e.tau, "",
                "vertical optical depth Sigma_d kappa_abs");
    write_array(g.get(), "intensity", {hl, hn}, e.intensity, "Jy arcsec^-2",
                "B_nu(T) (1 - exp(-tau / cos i)) at the cell centres");
    write_array(g.get(), "B_nu", {hl, hn}, e.b_nu, "Jy arcsec^-2",
                "Planck function B_nu(T)");
  }
  {
    h5::Handle g = h5::create_group(root, "image");
    std::vector<double> xs(im.grid.n);
    for (int j = 0; j < im.grid.n; ++j) xs[j] = im.grid.coord(j);
    write_array(g.get(), "x_arcsec", {hp}, xs, "arcsec",
                "offset to the east of pixel centres (axis 2; display east left)");
    write_array(g.get(), "y_arcsec", {hp}, xs, "arcsec",
                "offset to the north of pixel centres (axis 1)");
    write_array(g.get(), "model", {hl, hp, hp}, im.model, "Jy arcsec^-2",
                "model image before the beam, [wavelength][y][x]");
    write_array(g.get(), "convolved", {hl, hp, hp}, im.convolved, "Jy beam^-1",
                "image convolved with the beam, [wavelength][y][x]");
    h5::set_attr(g.get(), "pixel_arcsec", im.grid.pixel);
    h5::set_attr(g.get(), "padded_size", static_cast<long>(im.padded_size));
    h5::set_attr(g.get(), "kernel_half_width_px",
                 static_cast<long>(im.kernel_half_width));
  }
  {
    h5::Handle g = h5::create_group(root, "profile");
    std::vector<double> r_au(nb);
    for (std::size_t b = 0; b < nb; ++b)
      r_au[b] = im.r_mid_arcsec[b] * o.args.distance_pc;
    write_array(g.get(), "r_arcsec", {hb}, im.r_mid_arcsec, "arcsec",
                "deprojected radius of the bin centres");
    write_array(g.get(), "r_au", {hb}, r_au, "au",
                "deprojected radius of the bin centres");
    write_array(g.get(), "count", {hb}, im.count, "", "pixels in each bin");
    write_array(g.get(), "convolved", {hl, hb}, im.profile_convolved, "Jy beam^-1",
                "azimuthal mean of the convolved image over deprojected annuli (NaN: "
                "no pixel)");
    write_array(g.get(), "model", {hl, hb}, im.profile_model, "Jy arcsec^-2",
                "azimuthal mean of the model image over deprojected annuli");
  }
  {
    h5::Handle g = h5::create_group(root, "flux");
    write_array(g.get(), "model", {hl}, im.flux_model, "Jy",
                "total flux of the model image");
    write_array(g.get(), "convolved", {hl}, im.flux_convolved, "Jy",
                "total flux of the convolved image (sum x pixel area / beam area)");
    write_array(g.get(), "annuli", {hl}, im.flux_annuli, "Jy",
                "total flux summed over the cells' projected annuli (independent of "
                "the pixels: the check of model and convolved)");
  }
  {
    h5::Handle g = h5::create_group(root, "spectral_index");
    write_array(g.get(), "pairs_mm", {hnp, 2}, alpha.pairs_mm, "mm",
                "wavelength pairs (shorter, longer)");
    write_array(g.get(), "profile", {hnp, hb}, alpha.profile, "",
                "ln(I1/I2)/ln(nu1/nu2) of the convolved radial profiles");
    write_array(g.get(), "model", {hnp, hn}, alpha.model, "",
                "ln(I1/I2)/ln(nu1/nu2) of the model intensity at the cell centres");
    write_array(g.get(), "total", {hnp}, alpha.total, "", "of the total fluxes");
  }
}

}  // namespace

void write_observation_file(const fs::path& path, const Observation& o) {
  // written to <path>.tmp, closed, then put in place by the one atomic write
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  const fs::path tmp = path.string() + ".tmp";
  try {
    h5::Handle f = h5::create_file(tmp.string());
    write_provenance(f.get(), o);
    write_contents(f.get(), o);
    H5Fflush(f.get(), H5F_SCOPE_GLOBAL);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  commit_temporary(tmp, path);
}

}  // namespace panoptic
