#include "src/model/disk_tables.hpp"

#include <stdexcept>

#include "src/core/error.hpp"
#include "src/core/units.hpp"

namespace panoptic {

std::filesystem::path scene_relative_path(const Config& cfg, const std::string& key) {
  const std::filesystem::path p = cfg.str(key);
  if (p.is_absolute()) return p;
  const std::string& origin = cfg.where(key);
  if (origin == "--set") return p;  // a path on the command line: as the shell sees it
  // "file:line:col": relative to the file that set the key
  std::string file = origin;
  for (int k = 0; k < 2; ++k)
    if (const auto colon = file.rfind(':'); colon != std::string::npos) file.erase(colon);
  return std::filesystem::path(file).parent_path() / p;
}

std::vector<std::shared_ptr<const RadialTable>> read_disk_table(
    const Config& cfg, const std::string& key, const std::vector<std::string>& columns,
    const std::vector<double>& to_cgs) {
  if (cfg.str(key).empty())
    cfg.fail(
        key, "names no file; give the path of the CSV table (header " + [&] {
          std::string h;
          for (const auto& c : columns) h += (h.empty() ? "" : ",") + c;
          return h;
        }() + "), relative to the scene file that sets the key");
  const auto path = scene_relative_path(cfg, key);
  std::vector<std::shared_ptr<const RadialTable>> out;
  try {
    auto cols = read_csv_columns(path, columns);
    for (double& r : cols[0]) r *= units::kAu;
    for (std::size_t k = 1; k < cols.size(); ++k) {
      for (double& v : cols[k]) v *= to_cgs[k - 1];
      out.push_back(std::make_shared<const RadialTable>(cols[0], cols[k], columns[k]));
    }
  } catch (const std::invalid_argument& e) {
    cfg.fail(key, path.string() + ": " + e.what());
  }
  const double r_in = cfg.real("grid.r_in_au"), r_out = cfg.real("grid.r_out_au");
  const double lo = out[0]->r_min() / units::kAu, hi = out[0]->r_max() / units::kAu;
  if (lo > r_in * (1.0 + 1e-12) || hi < r_out * (1.0 - 1e-12))
    cfg.fail(key, path.string() + " covers r = " + num(lo) + " to " + num(hi) +
                      " au, but the grid spans grid.r_in_au = " + num(r_in) +
                      " to grid.r_out_au = " + num(r_out) +
                      " au (a table is not extrapolated); extend the table or narrow "
                      "the grid");
  return out;
}

}  // namespace panoptic
