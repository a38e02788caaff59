// Scene inheritance (`base = "other.toml"`, params/README.md, Inheritance): keys of the
// deepest base first, each file's keys over its bases', --set over all; where each key
// came from; a cycle or a missing base refused with the chain or the path tried. And the
// resolved scene, which lists every key: it re-loads to the same values without a
// warning about the keys its run does not read (their lines carry the "not read" mark).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "src/scene/config.hpp"
#include "tests/unit/support/config_error.hpp"

namespace panoptic {
namespace {

namespace fs = std::filesystem;

class SceneBase : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("panoptic_test_inheritance_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "variants");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string error_of(const fs::path& scene) {
    return config_error_message([&] { load_scene(scene); }, scene.string());
  }
  // The line of `key`'s leaf in a resolved scene ("" if none).
  static std::string line_of(const std::string& resolved, const std::string& leaf) {
    for (std::size_t a = 0, b; a < resolved.size(); a = b + 1) {
      b = resolved.find('\n', a);
      if (b == std::string::npos) b = resolved.size();
      const std::string line = resolved.substr(a, b - a);
      if (line.rfind(leaf + " = ", 0) == 0) return line;
    }
    return "";
  }
  fs::path dir_;
};

// fiducial-like grandparent, a colder parent, a less turbulent child: a key set at each
// level, one overridden at each level, and --set over all of them.
TEST_F(SceneBase, TwoLevelsEachFileOverridesItsBases) {
  const fs::path root = write("root.toml",
                              "[disk]\nT_1au = 280.0\nalpha = 1e-3\nsigma_1au = 1700.0\n"
                              "[grid]\nn_cells = 100\n");
  const fs::path mid = write("mid.toml",
                             "base = \"root.toml\"\n[disk]\nT_1au = 150.0\n"
                             "alpha = 3e-4\n");
  const fs::path leaf = write("variants/leaf.toml",
                              "# the base is relative to this file's folder\n"
                              "base = \"../mid.toml\"\n[disk]\nalpha = 1e-4\n");
  const Config c = load_scene(leaf, std::vector<std::string>{"grid.n_cells=64"});
  EXPECT_EQ(c.real("disk.sigma_1au"), 1700.0);  // only the grandparent sets it
  EXPECT_EQ(c.real("disk.T_1au"), 150.0);       // the parent overrides the grandparent
  EXPECT_EQ(c.real("disk.alpha"), 1e-4);        // the child overrides both
  EXPECT_EQ(c.integer("grid.n_cells"), 64);     // --set overrides every file
  EXPECT_EQ(c.file(), leaf);
  const std::string root_name = (dir_ / "root.toml").string();
  const std::string mid_name = (dir_ / "mid.toml").string();
  EXPECT_EQ(c.where("disk.sigma_1au"), root_name + ":4:1");
  EXPECT_EQ(c.where("disk.T_1au"), mid_name + ":3:1");
  EXPECT_EQ(c.where("disk.alpha"), leaf.string() + ":4:1");
  EXPECT_EQ(c.where("grid.n_cells"), "--set");
  EXPECT_TRUE(c.user_set("disk.sigma_1au"));
  // `panoptic check` shows which file set each key
  const std::string resolved = c.resolved_toml();
  EXPECT_NE(line_of(resolved, "sigma_1au").find("(from " + root_name + ")"),
            std::string::npos)
      << resolved;
  EXPECT_NE(line_of(resolved, "T_1au").find("(from " + mid_name + ")"),
            std::string::npos);
  EXPECT_EQ(line_of(resolved, "alpha").find("(from"), std::string::npos);
  EXPECT_NE(line_of(resolved, "n_cells").find("(--set)"), std::string::npos);
  EXPECT_NE(line_of(resolved, "p").find("(default)"), std::string::npos);
  // the resolved scene is flat: it loads alone to the same values
  const Config back = load_scene_text(resolved, "resolved.toml");
  EXPECT_TRUE(back.values_ == c.values_);
  EXPECT_EQ(scene_files(leaf),
            (std::vector<fs::path>{leaf, dir_ / "mid.toml", dir_ / "root.toml"}));
}

TEST_F(SceneBase, ACycleIsRefusedWithTheChain) {
  write("a.toml", "base = \"b.toml\"\n[disk]\nalpha = 1e-4\n");
  write("b.toml", "base = \"./a.toml\"\n");
  const std::string a = (dir_ / "a.toml").string(), b = (dir_ / "b.toml").string();
  const std::string message = error_of(dir_ / "a.toml");
  EXPECT_NE(message.find(a + " -> " + b + " -> " + a), std::string::npos) << message;
  EXPECT_NE(message.find(b + ":1:8: base = \"./a.toml\""), std::string::npos) << message;
  EXPECT_NE(message.find("remove the base line"), std::string::npos) << message;
  // a scene that names itself
  const fs::path self = write("self.toml", "base = \"self.toml\"\n");
  EXPECT_NE(error_of(self).find(self.string() + " -> " + self.string()),
            std::string::npos)
      << error_of(self);
}

TEST_F(SceneBase, AMissingBaseNamesTheKeyThePathAndTheFix) {
  const fs::path scene = write("variants/x.toml", "base = \"nope.toml\"\n");
  const std::string message = error_of(scene);
  for (const std::string& part : std::vector<std::string>{
           scene.string() + ":1:8: base = \"nope.toml\"",
           (dir_ / "variants" / "nope.toml").string() + ": cannot read scene file",
           "relative to the folder of " + scene.string(), "remove the base line"})
    EXPECT_NE(message.find(part), std::string::npos) << part << " in\n" << message;
}

TEST_F(SceneBase, ABaseMustBeAStringAtTheTop) {
  EXPECT_NE(error_of(write("n.toml", "base = 3\n")).find("base = 3: must be the path"),
            std::string::npos);
  EXPECT_NE(error_of(write("t.toml", "[disk]\nbase = \"a.toml\"\n"))
                .find("goes at the top of the scene"),
            std::string::npos);
}

TEST_F(SceneBase, ErrorsInABaseNameTheBase) {
  write("bad.toml", "[disk]\nalpha = -1.0\n");
  const std::string message = error_of(write("x.toml", "base = \"bad.toml\"\n"));
  EXPECT_EQ(message.rfind((dir_ / "bad.toml").string() + ":2:1: disk.alpha = -1.0", 0),
            0u)
      << message;
}

// The ~20 warnings of a resolved fiducial scene were its keys that no run of it reads
// (disk.r_c_au of a power-law disk, ...), all written out: the resolved scene marks
// them, and such a line warns about nothing; the same key without the mark still does.
TEST_F(SceneBase, AResolvedSceneReRunsWithoutWarnings) {
  const Config c = load_scene(fs::path(PANOPTIC_SOURCE_DIR) / "params/fiducial.toml",
                              std::vector<std::string>{"disk.r_c_au=80"});
  EXPECT_EQ(unused_key_warnings(c).size(), 1u);  // the --set one
  const std::string resolved = c.resolved_toml();
  EXPECT_NE(line_of(resolved, "r_c_au").find("(not read: disk.model = \"powerlaw\")"),
            std::string::npos)
      << resolved;
  EXPECT_EQ(line_of(resolved, "sigma_1au").find("not read"), std::string::npos);
  const Config back = load_scene_text(resolved, "resolved.toml");
  EXPECT_TRUE(back.values_ == c.values_);
  EXPECT_TRUE(unused_key_warnings(back).empty()) << unused_key_warnings(back).front();
  EXPECT_EQ(unused_key_warnings(
                load_scene_text("[disk]\nr_c_au = 80.0  # a comment\n", "x.toml"))
                .size(),
            1u);
}

}  // namespace
}  // namespace panoptic
