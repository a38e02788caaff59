// The scene schema: every key a scene may hold, its type, default, unit, meaning and
// allowed range. params/reference.toml is generated from this list (`panoptic reference`)
// and a unit test keeps the two identical. Physics defaults cite physics-spec sections.
//
// NEW_PROCESS: the keys of a new process are a table of their own: a function
// <table>_keys() in a keys_*.cpp file (key_builders.hpp has the words), declared in
// key_tables.hpp and listed below.
#include <iterator>

#include "src/scene/key_tables.hpp"

namespace panoptic {
namespace {

using KeyTable = std::vector<KeySpec> (*)();

// The tables in the order of params/reference.toml.
constexpr KeyTable kTables[] = {
    scene_detail::meta_keys,       scene_detail::star_keys,
    scene_detail::disk_keys,       scene_detail::gas_keys,
    scene_detail::dust_keys,       scene_detail::transport_keys,
    scene_detail::growth_keys,     scene_detail::porosity_keys,
    scene_detail::erosion_keys,    scene_detail::fragmentation_keys,
    scene_detail::bouncing_keys,   scene_detail::snowline_keys,
    scene_detail::material_keys,   scene_detail::planetesimals_keys,
    scene_detail::pebbles_keys,    scene_detail::model_keys,
    scene_detail::grid_keys,       scene_detail::solver_keys,
    scene_detail::checkpoint_keys, scene_detail::output_keys,
    scene_detail::observe_keys,
};

std::vector<KeySpec> make_keys() {
  std::vector<KeySpec> keys;
  for (const KeyTable table : kTables) {
    std::vector<KeySpec> t = table();
    keys.insert(keys.end(), std::make_move_iterator(t.begin()),
                std::make_move_iterator(t.end()));
  }
  return keys;
}

}  // namespace

const std::vector<KeySpec>& scene_keys() {
  static const std::vector<KeySpec> keys = make_keys();
  return keys;
}

}  // namespace panoptic
