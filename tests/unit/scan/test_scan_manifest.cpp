// Scan files expanded into manifests (src/scan/scan_manifest.hpp): product and zip order,
// exact lin/log points, Latin-hypercube reproducibility and stratification, and the
// errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "src/core/error.hpp"
#include "src/scan/scan_exec.hpp"
#include "src/scan/scan_manifest.hpp"
#include "tests/unit/support/expect_fields.hpp"

namespace panoptic {
namespace {

const std::filesystem::path kScans =
    std::filesystem::path(PANOPTIC_SOURCE_DIR) / "params";

Manifest expand(const std::string& body) {
  return expand_scan_text("[scan]\nscene = \"fiducial.toml\"\n" + body, "test.toml",
                          kScans);
}

std::string value(const Manifest& m, std::size_t run, std::size_t axis) {
  return m.entries.at(run).values.at(axis).second;
}

double number(const Manifest& m, std::size_t run, std::size_t axis) {
  return std::strtod(value(m, run, axis).c_str(), nullptr);
}

std::string error_of(const std::string& body) {
  try {
    expand(body);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ScanManifest, ProductFirstAxisSlowest) {
  const Manifest m = expand(
      "[[axis]]\nkey = \"star.mass_msun\"\nvalues = [0.5, 1, 2.0]\n"
      "[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-4, 1e-3]\n");
  ASSERT_EQ(m.entries.size(), 6u);
  const double mass[] = {0.5, 0.5, 1.0, 1.0, 2.0, 2.0};
  const double alpha[] = {1e-4, 1e-3, 1e-4, 1e-3, 1e-4, 1e-3};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(m.entries[i].id, static_cast<long>(i));
    EXPECT_EQ(number(m, i, 0), mass[i]);
    EXPECT_EQ(number(m, i, 1), alpha[i]);
  }
  EXPECT_EQ(m.entries[5].name, "run_00005");
  // an integer written for a real key becomes a real literal (1 -> 1.0)
  EXPECT_EQ(value(m, 2, 0), "1.0");
}

TEST(ScanManifest, LogRangeIsExactAtTheEndsAndDecades) {
  const Manifest m =
      expand("[[axis]]\nkey = \"disk.alpha\"\nlog = [1e-4, 1e-2]\nnum = 5\n");
  ASSERT_EQ(m.entries.size(), 5u);
  EXPECT_EQ(number(m, 0, 0), 1e-4);
  EXPECT_EQ(number(m, 2, 0), 1e-3);
  EXPECT_EQ(number(m, 4, 0), 1e-2);
  // equal ratios sqrt(10), independently of how the points are computed
  for (std::size_t i = 0; i + 1 < 5; ++i)
    EXPECT_NEAR(number(m, i + 1, 0) / number(m, i, 0), std::sqrt(10.0), 4e-15);
  // ends that are not powers of ten are kept as written
  const std::vector<double> x = log_points(3e-5, 7e-2, 7);
  EXPECT_EQ(x.front(), 3e-5);
  EXPECT_EQ(x.back(), 7e-2);
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    EXPECT_NEAR(std::log(x[i + 1] / x[i]), std::log(7e-2 / 3e-5) / 6, 1e-14);
}

TEST(ScanManifest, LinRangeAndIntegerKeys) {
  const Manifest m = expand(
      "[[axis]]\nkey = \"star.mass_msun\"\nlin = [0.5, 2.0]\nnum = 4\n"
      "[[axis]]\nkey = \"grid.n_cells\"\nlin = [10, 20]\nnum = 3\n");
  ASSERT_EQ(m.entries.size(), 12u);
  const double mass[] = {0.5, 1.0, 1.5, 2.0};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(number(m, 3 * i, 0), mass[i]);
  EXPECT_EQ(value(m, 0, 1), "10");
  EXPECT_EQ(value(m, 1, 1), "15");
  EXPECT_EQ(value(m, 2, 1), "20");
}

TEST(ScanManifest, GridRangeOfRepeatedPointsIsAnError) {
  // lin = [10, 11] with num = 5 over an integer key rounds to 10, 10, 11, 11, 11: three
  // runs would repeat others; lo = hi with num > 1 likewise
  const std::string e =
      error_of("[[axis]]\nkey = \"grid.n_cells\"\nlin = [10, 11]\nnum = 5\n");
  EXPECT_NE(e.find("axis grid.n_cells"), std::string::npos) << e;
  EXPECT_NE(e.find("repeated values (10, 10, 11, 11, 11), rounded to integers"),
            std::string::npos)
      << e;
  EXPECT_NE(error_of("[[axis]]\nkey = \"disk.alpha\"\nlog = [1e-3, 1e-3]\nnum = 2\n")
                .find("repeated values"),
            std::string::npos);
  // distinct points pass
  EXPECT_EQ(error_of("[[axis]]\nkey = \"grid.n_cells\"\nlin = [10, 12]\nnum = 3\n"), "");
  // one point of a range would drop its upper end ("both ends included"): refused, as a
  // value listed twice would run one scene twice
  EXPECT_NE(error_of("[[axis]]\nkey = \"disk.alpha\"\nlog = [1e-4, 1e-2]\nnum = 1\n")
                .find("num must be an integer >= 2 (a range includes both ends)"),
            std::string::npos);
  const std::string twice =
      error_of("[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3, 2e-3, 0.001]\n");
  EXPECT_NE(twice.find("disk.alpha = 0.001 appear twice (entries 1 and 3)"),
            std::string::npos)
      << twice;
  // zipped, a value may repeat where the tuple does not
  EXPECT_EQ(error_of("[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3, 2e-3, 1e-3]\n"
                     "zip = \"a\"\n[[axis]]\nkey = \"star.mass_msun\"\n"
                     "values = [1.0, 1.0, 2.0]\nzip = \"a\"\n"),
            "");
  EXPECT_NE(error_of("[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3, 2e-3, 1e-3]\n"
                     "zip = \"a\"\n[[axis]]\nkey = \"star.mass_msun\"\n"
                     "values = [1.0, 1.0, 1.0]\nzip = \"a\"\n")
                .find("appear twice (entries 1 and 3)"),
            std::string::npos);
  EXPECT_EQ(error_of("[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3, 2e-3]\n"), "");
}

TEST(ScanManifest, ZipAdvancesTogether) {
  const Manifest m = expand(
      "[[axis]]\nkey = \"star.mass_msun\"\nvalues = [0.5, 1.0, 2.0]\nzip = \"star\"\n"
      "[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-4, 1e-3]\n"
      "[[axis]]\nkey = \"star.luminosity_lsun\"\nlin = [0.1, 4.0]\nnum = 3\nzip = "
      "\"star\"\n");
  ASSERT_EQ(m.entries.size(), 6u);  // 3 zipped x 2
  const double lum[] = {0.1, 2.05, 4.0};
  for (std::size_t i = 0; i < 6; ++i) {
    const std::size_t k = i / 2;  // the zipped dimension comes first
    EXPECT_EQ(number(m, i, 0), (k == 0 ? 0.5 : k == 1 ? 1.0 : 2.0));
    EXPECT_EQ(number(m, i, 2), lum[k]);
    EXPECT_EQ(number(m, i, 1), i % 2 == 0 ? 1e-4 : 1e-3);
  }
}

TEST(ScanManifest, ZipLengthMismatchIsAnError) {
  const std::string e = error_of(
      "[[axis]]\nkey = \"star.mass_msun\"\nvalues = [0.5, 1.0, 2.0]\nzip = \"s\"\n"
      "[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-4, 1e-3]\nzip = \"s\"\n");
  EXPECT_NE(e.find("star.mass_msun (3 values)"), std::string::npos) << e;
  EXPECT_NE(e.find("disk.alpha (2 values)"), std::string::npos) << e;
  EXPECT_NE(e.find("same number"), std::string::npos) << e;
}

Manifest lhs(long n, long seed) {
  return expand("sampling = \"lhs\"\nsamples = " + std::to_string(n) +
                "\nseed = " + std::to_string(seed) +
                "\n[[axis]]\nkey = \"star.mass_msun\"\nlin = [0.3, 2.0]\n"
                "[[axis]]\nkey = \"disk.alpha\"\nlog = [1e-5, 1e-2]\n"
                "[[axis]]\nkey = \"disk.model\"\nvalues = [\"powerlaw\", \"lbp\"]\n");
}

TEST(ScanManifest, LatinHypercubeIsReproducibleAndStratified) {
  const long n = 50;
  const Manifest a = lhs(n, 7), b = lhs(n, 7), c = lhs(n, 8);
  ASSERT_EQ(a.entries.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(a.to_toml(), b.to_toml());
  EXPECT_NE(a.to_toml(), c.to_toml());
  // every stratum of every axis holds exactly one sample (in log10 for the log axis)
  std::set<long> lin_strata, log_strata;
  long powerlaw = 0;
  for (std::size_t i = 0; i < a.entries.size(); ++i) {
    const double mass = number(a, i, 0), alpha = number(a, i, 1);
    ASSERT_GE(mass, 0.3);
    ASSERT_LE(mass, 2.0);
    ASSERT_GE(alpha, 1e-5);
    ASSERT_LE(alpha, 1e-2);
    lin_strata.insert(static_cast<long>(std::floor((mass - 0.3) / 1.7 * n)));
    log_strata.insert(static_cast<long>(std::floor((std::log10(alpha) + 5.0) / 3.0 * n)));
    powerlaw += value(a, i, 2) == "\"powerlaw\"";
  }
  EXPECT_EQ(lin_strata.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(log_strata.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(powerlaw, n / 2);  // a list is stratified too: half the strata per value
  // the pairing across axes is not the identity (the axes are not sorted together)
  long same_order = 0;
  for (std::size_t i = 0; i + 1 < a.entries.size(); ++i)
    same_order += (number(a, i + 1, 0) > number(a, i, 0)) ==
                  (number(a, i + 1, 1) > number(a, i, 1));
  EXPECT_LT(same_order, n - 5);
}

TEST(ScanManifest, ErrorsNameTheKey) {
  std::string e = error_of("[[axis]]\nkey = \"star.mas_msun\"\nvalues = [1.0]\n");
  EXPECT_NE(e.find("test.toml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("star.mas_msun"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean star.mass_msun"), std::string::npos) << e;
  e = error_of("[[axis]]\nkey = \"disk.alpha\"\nlog = [0.0, 1e-2]\nnum = 3\n");
  EXPECT_NE(e.find("> 0"), std::string::npos) << e;
  e = error_of("[[axis]]\nkey = \"disk.alpha\"\nlin = [1e-4, 1e-2]\n");
  EXPECT_NE(e.find("needs num"), std::string::npos) << e;
  e = error_of(
      "sampling = \"lhs\"\n[[axis]]\nkey = \"disk.alpha\"\nlin = [1e-4, 1e-2]\n");
  EXPECT_NE(e.find("scan.samples"), std::string::npos) << e;
  e = error_of(
      "[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3]\n"
      "[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3]\n");
  EXPECT_NE(e.find("twice"), std::string::npos) << e;
  e = error_of("");
  EXPECT_NE(e.find("no [[axis]]"), std::string::npos) << e;
  EXPECT_NE(
      error_of("[[axis]]\nkey = \"disk.alpha\"\nvalues = [1e-3\n").find("test.toml:"),
      std::string::npos);
}

TEST(ScanManifest, BadValuesAreRefusedBeforeAnyRunNamingRunAndKey) {
  const Manifest m = expand("[[axis]]\nkey = \"star.mass_msun\"\nvalues = [1.0, -2.0]\n");
  try {
    validate_manifest(m);
    FAIL() << "a negative stellar mass was accepted";
  } catch (const ConfigError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("run_00001"), std::string::npos) << s;
    EXPECT_NE(s.find("star.mass_msun = -2.0"), std::string::npos) << s;
    EXPECT_NE(s.find("must be >= 0.01"), std::string::npos) << s;
  }
  const Manifest ok = expand("[[axis]]\nkey = \"star.mass_msun\"\nvalues = [0.5, 2.0]\n");
  const std::vector<ResolvedRun> r = validate_manifest(ok);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NE(r[1].config_toml.find("mass_msun = 2.0"), std::string::npos);
  EXPECT_EQ(r[1].t_end_yr, 1e6);  // params/fiducial.toml
}

TEST(ScanManifest, ResolvedSceneIsWhatTheRunRecords) {
  // The scan validates runs with apply_trusted_overrides on the base scene; a run loads
  // the scene with every --set (load_scene). Both must resolve to the same text: the scan
  // recognises a complete run by its config_toml.
  const Manifest m = expand(
      "set = [\"grid.n_cells=40\", \"output.t_end_yr=2e3\"]\n"
      "[[axis]]\nkey = \"disk.alpha\"\nlog = [1e-4, 1e-2]\nnum = 3\n"
      "[[axis]]\nkey = \"disk.model\"\nvalues = [\"powerlaw\", \"lbp\"]\n");
  const std::vector<ResolvedRun> r = validate_manifest(m);
  ASSERT_EQ(r.size(), 6u);
  for (std::size_t i = 0; i < m.entries.size(); ++i) {
    const std::vector<std::string> all = m.overrides(i);
    EXPECT_EQ(r[i].config_toml, load_scene(m.scene, all).resolved_toml()) << i;
  }
  EXPECT_NE(r[0].config_toml, r[1].config_toml);
  EXPECT_EQ(r[5].t_end_yr, 2e3);
}

TEST(ScanManifest, ManifestBodyIgnoresComments) {
  const Manifest m = expand("[[axis]]\nkey = \"star.mass_msun\"\nvalues = [1.0]\n");
  EXPECT_EQ(manifest_body(m.to_toml("# a header\n# more\n")), manifest_body(m.to_toml()));
  EXPECT_EQ(manifest_body(m.to_toml()), m.to_toml());
}

TEST(ScanManifest, TaskMessageCarriesTheRunsScene) {
  // An MPI worker decides from task.config_toml whether a checkpoint may be continued:
  // the message must carry it whole (multi-line, quotes), and the command line after it.
  ScanTask t;
  t.id = 17;
  t.name = "run_00017";
  t.h5 = "/d/runs/run_00017.h5";
  t.log = "/d/runs/run_00017.log";
  t.err = "/d/runs/run_00017.err";
  t.status = "/d/runs/run_00017.status";
  t.config_toml = "[star]\nmass_msun = 1.5\n[disk]\nmodel = \"lbp\"\n";
  t.argv = {"/bin/panoptic", "run", "s.toml", "--set",
            "a.b=1",         "-o",  t.h5,     "--overwrite"};
  const ScanTask u = ScanTask::deserialize(t.serialize());
  test_support::expect_fields_equal(u, t, &ScanTask::id, &ScanTask::name, &ScanTask::h5,
                                    &ScanTask::log, &ScanTask::err, &ScanTask::status,
                                    &ScanTask::config_toml, &ScanTask::argv);
}

TEST(ScanManifest, AxisAlsoFixedInSetIsAnErrorWithSpacesToo) {
  // --set reads " star.mass_msun = 3" as star.mass_msun; the axis would override it
  // silently
  for (const char* set :
       {"star.mass_msun=3", " star.mass_msun = 3", "star.mass_msun\t=3"})
    EXPECT_NE(error_of("set = [\"" + std::string(set) +
                       "\"]\n[[axis]]\nkey = \"star.mass_msun\"\nvalues = [1.0]\n")
                  .find("also fixed in scan.set"),
              std::string::npos)
        << set;
}

}  // namespace
}  // namespace panoptic
