#pragma once
//! The builders of the key tables (keys_*.cpp): one KeySpec per call, in the words of
//! the schema. Internal to the scene layer.
#include <optional>
#include <string>
#include <vector>

#include "src/scene/scene_keys.hpp"

namespace panoptic::scene_detail {

//! A default as the schema writes it: below 0.01 with an exponent ("1e-3", as the
//! reference lists small numbers), else as a TOML float ("280.0").
std::string literal(double x);

//! A real key, bounded by min and max when given (strict bounds with min_excl, max_excl).
KeySpec real(std::string key, std::string def, std::string unit, std::string doc,
             std::optional<double> min = std::nullopt, bool min_excl = false,
             std::optional<double> max = std::nullopt, bool max_excl = false);
//! A real key > 0.
KeySpec positive(std::string key, std::string def, std::string unit, std::string doc);
//! An integer key in [min, max].
KeySpec integer(std::string key, std::string def, std::string doc, double min,
                double max);
//! A bool key.
KeySpec flag(std::string key, std::string def, std::string doc);
//! A string key holding one of `choices`; `def` is given unquoted.
KeySpec choice(std::string key, std::string def, std::vector<std::string> choices,
               std::string doc);
//! A free string key, default "".
KeySpec text(std::string key, std::string doc);
//! A list of reals, default [], every element >= min when given.
KeySpec real_list(std::string key, std::string unit, std::string doc,
                  std::optional<double> min = std::nullopt);
//! A list of reals with a default (a table of values), every element > min.
KeySpec real_table(std::string key, std::string def, std::string unit, std::string doc,
                   double min);

//! When a run reads a key (KeySpec::used_when), taken from the code that reads it
//! (src/model/scene_to_physics.cpp, src/model/simulation.cpp, physics/growth_rates.hpp
//! and the processes it combines, physics/modules/planetesimals_cell_rates.hpp,
//! src/observe/observe.cpp). Values are TOML literals.
UsedWhen is(std::string key, std::vector<std::string> values);
//! A string switch (a choice) holding one of `names`.
UsedWhen one_of(std::string key, std::vector<std::string> names);
//! growth.enabled = true
UsedWhen growth_on();
//! disk.model = "m"
UsedWhen disk_model(const std::string& m);
//! dust.init = "i"
UsedWhen dust_init(const std::string& i);
//! model.kind = "single_size"
UsedWhen single_size();
//! model.kind = "distribution"
UsedWhen distribution();
//! `first`, or else any of `alternatives` (UsedWhen::or_else)
UsedWhen either(UsedWhen first, std::vector<UsedWhen> alternatives);
//! erosion.model is one of `models`
UsedWhen erosion(std::vector<std::string> models);
//! planetesimals.si is one of `models`
UsedWhen si(std::vector<std::string> models);
//! `k`, read only when every condition holds.
KeySpec when(std::vector<UsedWhen> conditions, KeySpec k);

}  // namespace panoptic::scene_detail
