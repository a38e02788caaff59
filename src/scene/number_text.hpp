#pragma once
//! How a text reads as a number (std::strtod, std::strtoll), to say why a value that
//! looks like a number is not one: "1e999" is beyond the range of a double, and a --set
//! value or a TOML token of that kind reaches the scene layer as text.
#include <string>

namespace panoptic {

struct NumberText {
  bool real = false;           //!< the whole text reads as a floating-point number
  bool beyond_double = false;  //!< ... and std::strtod reports ERANGE (|x| > 1.8e308)
  bool integer = false;        //!< the whole text reads as a base-10 integer
  bool beyond_int64 = false;   //!< ... and std::strtoll reports ERANGE
};

//! How `text` reads as a number; all false for "" and for text that is not one.
NumberText read_number_text(const std::string& text);

}  // namespace panoptic
