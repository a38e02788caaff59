#pragma once
//! The entries of a run's HDF5 output as `panoptic reference --outputs` lists them
//! (src/io/README.md, Output). Each is declared once, next to the code that writes it,
//! and written from that declaration, so the listing cannot miss one.
#include <string>
#include <variant>

namespace panoptic {

//! The value of an attribute, as h5::set_attr writes it.
using AttributeValue = std::variant<long, double, std::string>;

//! An attribute of the group `group` ("" for the file's root), with its value.
struct OutputAttribute {
  std::string group;
  std::string name;
  std::string units;  //!< "" for a pure number or a text
  std::string description;
  AttributeValue value;
};

//! One row of the listing: a dataset ("grid/r_c") or an attribute ("solver@nst", and
//! "@scene" for one of the root).
struct OutputEntry {
  std::string path;
  std::string units;  //!< "" for a pure number or a text
  std::string description;
};

}  // namespace panoptic
