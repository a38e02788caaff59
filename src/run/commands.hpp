#pragma once
//! The bodies of the subcommands that are not a run: `panoptic check` and `panoptic
//! track` (run: run.hpp; scan: src/scan/scan.hpp; observe: src/observe/observe.hpp).
//! Each returns the exit code and throws the Error of a failure.
#include <string>
#include <vector>

namespace panoptic {

//! `panoptic check`: validates the scene and prints it resolved, with defaults.
int check_scene(const std::string& scene, const std::vector<std::string>& overrides);

//! `panoptic track`: one particle along its drift path (spec §13).
int track_command(const std::string& scene, const std::vector<std::string>& overrides,
                  double r0_au, double a_stop_cm, double t_max_yr);

}  // namespace panoptic
