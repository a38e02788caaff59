// Accuracy presets of `panoptic run --fast / --accurate` (src/scene/presets.hpp): valid
// keys and values on the scenes, override the scene file, and lose to an explicit --set.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "src/scene/config.hpp"
#include "src/scene/presets.hpp"

namespace panoptic {
namespace {

const std::string kScenes[] = {"fiducial", "erosion_40", "compact_fragmentation"};

Config scene(const std::string& name, const std::vector<std::string>& sets) {
  return load_scene(std::string(PANOPTIC_SOURCE_DIR) + "/params/" + name + ".toml", sets);
}

TEST(Presets, ValidOnEveryPhysicsScene) {
  for (const std::string preset : {"fast", "accurate"})
    for (const auto& name : kScenes) {
      const auto sets = preset_overrides(preset);
      ASSERT_FALSE(sets.empty());
      EXPECT_NO_THROW(scene(name, with_preset(preset, {}))) << preset << " " << name;
    }
}

TEST(Presets, OverrideTheSceneFile) {
  // fiducial.toml sets grid.n_cells = 350 and solver.rtol = 1e-5 itself
  const Config fast = scene("fiducial", with_preset("fast", {}));
  const Config acc = scene("fiducial", with_preset("accurate", {}));
  const Config none = scene("fiducial", with_preset("", {}));
  EXPECT_EQ(none.integer("grid.n_cells"), 350);
  EXPECT_EQ(fast.integer("grid.n_cells"), 250);
  EXPECT_EQ(acc.integer("grid.n_cells"), 1000);
  EXPECT_DOUBLE_EQ(fast.real("solver.rtol"), 1e-4);
  EXPECT_DOUBLE_EQ(acc.real("solver.rtol"), 1e-6);
  // --accurate keeps CVODE's own Jacobian reuse; the others the scene's (default 10)
  EXPECT_EQ(acc.integer("solver.steps_per_jacobian"), 0);
  EXPECT_EQ(fast.integer("solver.steps_per_jacobian"), 10);
  EXPECT_EQ(none.integer("solver.steps_per_jacobian"), 10);
  // the scene's cell spacing is kept
  EXPECT_DOUBLE_EQ(fast.real("grid.stretch"), 0.5);
  EXPECT_DOUBLE_EQ(acc.real("grid.stretch"), 0.5);
}

TEST(Presets, ExplicitSetWins) {
  const Config c =
      scene("fiducial", with_preset("accurate", {"grid.n_cells=77", "solver.rtol=3e-5"}));
  EXPECT_EQ(c.integer("grid.n_cells"), 77);
  EXPECT_DOUBLE_EQ(c.real("solver.rtol"), 3e-5);
}

TEST(Presets, UnknownNameRefused) {
  EXPECT_THROW(preset_overrides("fastest"), std::invalid_argument);
}

}  // namespace
}  // namespace panoptic
