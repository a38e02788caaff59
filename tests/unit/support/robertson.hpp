#pragma once
//! Test helper: the stiff Robertson kinetics (Robertson 1966; Hairer & Wanner, Solving
//! ODEs II, §IV.1) as a DiskModel of no cells and three global variables, with its exact
//! Jacobian, for the tests of the integrator and of restarts.
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "src/solver/disk_model.hpp"
#include "src/solver/physics_module.hpp"
#include "src/solver/state_layout.hpp"

namespace panoptic {

class Robertson : public PhysicsModule {
 public:
  explicit Robertson(StateLayout& layout) {
    for (const char* n : {"y1", "y2", "y3"})
      layout.add_global_var({n, "", "", 1.0, true});
  }
  std::string_view name() const override { return "robertson"; }
  void declare_pattern(PatternBuilder& p) const override {
    for (long i = 0; i < 3; ++i)
      for (long j = 0; j < 3; ++j) p.add(i, j);
  }
  void add_rhs(double, std::span<const double> y, std::span<double> f) const override {
    f[0] += -0.04 * y[0] + 1e4 * y[1] * y[2];
    f[2] += 3e7 * y[1] * y[1];
    f[1] += 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
  }
  void add_jacobian(double, std::span<const double> y, JacobianValues& J) const override {
    J.add(0, 0, -0.04);
    J.add(0, 1, 1e4 * y[2]);
    J.add(0, 2, 1e4 * y[1]);
    J.add(1, 0, 0.04);
    J.add(1, 1, -1e4 * y[2] - 6e7 * y[1]);
    J.add(1, 2, -1e4 * y[1]);
    J.add(2, 1, 6e7 * y[1]);
  }
};

//! The Robertson problem as a model CVODE can integrate.
inline std::unique_ptr<DiskModel> robertson_model() {
  auto layout = std::make_shared<StateLayout>(0);
  std::vector<std::unique_ptr<PhysicsModule>> modules;
  modules.push_back(std::make_unique<Robertson>(*layout));
  layout->freeze();
  return std::make_unique<DiskModel>(layout, std::move(modules));
}

}  // namespace panoptic
