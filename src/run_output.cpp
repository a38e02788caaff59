#include "src/run_output.hpp"

#include "src/cvode_integrator.hpp"
#include "src/error.hpp"

namespace panoptic {

RunOutput::RunOutput(const std::filesystem::path& path, bool overwrite,
                     const RunMetadata& meta)
    : path_(path) {
  h5::quiet_errors();
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !overwrite)
    throw IoError(
        path.string() +
        ": output file exists; pass --overwrite to replace it, or choose another "
        "file with -o");
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
      throw IoError(path.parent_path().string() + ": cannot create directory (" +
                    ec.message() + ")");
  }
  file_ = h5::create_file(path.string());
  h5::set_attr(file_.get(), "scene", meta.scene);
  h5::set_attr(file_.get(), "config_toml", meta.config_toml);
  h5::set_attr(file_.get(), "git_sha", meta.git_sha);
  h5::set_attr(file_.get(), "version", meta.version);
  ensure_group("snapshots");
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  h5::create_stack(g.get(), "time", 0, "yr", "simulated time of each snapshot");
  flush();
}

RunOutput::~RunOutput() {
  if (file_.valid()) H5Fflush(file_.get(), H5F_SCOPE_GLOBAL);
}

void RunOutput::ensure_group(const std::string& group) {
  if (!h5::exists(file_.get(), group)) h5::create_group(file_.get(), group);
}

void RunOutput::write_static(const std::string& group, const std::string& name,
                             std::span<const double> data, const std::string& units,
                             const std::string& description) {
  ensure_group(group);
  h5::Handle g = h5::open_group(file_.get(), group);
  h5::write_vector(g.get(), name, data, units, description);
}

void RunOutput::set_group_attr(const std::string& group, const std::string& name,
                               double value) {
  ensure_group(group);
  h5::Handle g = h5::open_group(file_.get(), group);
  h5::set_attr(g.get(), name, value);
}

void RunOutput::add_field(const std::string& name, std::size_t width,
                          const std::string& units, const std::string& description) {
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  h5::create_stack(g.get(), name, width, units, description);
  fields_[name] = width;
}

void RunOutput::write_snapshot(double t_yr,
                               const std::map<std::string, std::vector<double>>& fields) {
  h5::Handle g = h5::open_group(file_.get(), "snapshots");
  // Every field first, time last: a reader trusts only rows that have a time.
  for (const auto& [name, width] : fields_) {
    const auto it = fields.find(name);
    if (it == fields.end() || it->second.size() != (width == 0 ? 1 : width))
      throw IoError("snapshot field '" + name + "' missing or of the wrong length");
    h5::append_row(g.get(), name, it->second);
  }
  const double t[1] = {t_yr};
  h5::append_row(g.get(), "time", t);
  ++n_snapshots_;
  flush();
}

void RunOutput::write_solver(const SolverStats& s, double wall_s,
                             const std::string& status) {
  ensure_group("solver");
  h5::Handle g = h5::open_group(file_.get(), "solver");
  h5::set_attr(g.get(), "nst", s.nst);
  h5::set_attr(g.get(), "nfe", s.nfe);
  h5::set_attr(g.get(), "nje", s.nje);
  h5::set_attr(g.get(), "nsetups", s.nsetups);
  h5::set_attr(g.get(), "netf", s.netf);
  h5::set_attr(g.get(), "nni", s.nni);
  h5::set_attr(g.get(), "nncf", s.nncf);
  h5::set_attr(g.get(), "nreinit", s.nreinit);
  h5::set_attr(g.get(), "wall_s", wall_s);
  h5::set_attr(g.get(), "status", status);
  flush();
}

void RunOutput::flush() {
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0)
    throw IoError(path_.string() + ": flushing the HDF5 file failed");
}

}  // namespace panoptic
