// /solver of a run file (src/io/README.md, "Output"; postprocess/reader.py reads it):
// every CVODE counter under its own name. Each counter gets a different value (the primes
// 2 ... 23, which no sum or swap of two of them reproduces), so an attribute written from
// another counter is told apart; H5RoundTrip.EverythingWrittenReadsBackExactly sets only
// nst and nje, leaving the other six at 0, where any two of them are equal.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "src/io/h5.hpp"
#include "src/io/run_output.hpp"
#include "src/solver/cvode_integrator.hpp"

namespace panoptic {
namespace {

namespace fs = std::filesystem;

TEST(H5RoundTrip, EverySolverCounterUnderItsOwnName) {
  const fs::path dir = fs::temp_directory_path() / "panoptic_solver_attrs";
  fs::create_directories(dir);
  const fs::path path = dir / "run.h5";
  fs::remove(path);
  SolverStats s;
  s.nst = 2;
  s.nfe = 3;
  s.nje = 5;
  s.nsetups = 7;
  s.netf = 11;
  s.nni = 13;
  s.nncf = 17;
  s.nreinit = 19;
  {
    RunOutput out(path, false, {"s", "", "", ""});
    out.start_appending();
    out.write_solver(s, 23.0, "stopped");
  }
  h5::quiet_errors();
  h5::Handle f = h5::open_file(path.string(), false);
  h5::Handle g = h5::open_group(f.get(), "solver");
  EXPECT_EQ(h5::get_attr_long(g.get(), "nst"), 2);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nfe"), 3);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nje"), 5);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nsetups"), 7);
  EXPECT_EQ(h5::get_attr_long(g.get(), "netf"), 11);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nni"), 13);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nncf"), 17);
  EXPECT_EQ(h5::get_attr_long(g.get(), "nreinit"), 19);
  EXPECT_EQ(h5::get_attr_double(g.get(), "wall_s"), 23.0);
  EXPECT_EQ(h5::get_attr_string(g.get(), "status"), "stopped");
}

}  // namespace
}  // namespace panoptic
