#pragma once
//! Test helper: EXPECT_EQ on the given members of two objects, one assertion per member,
//! for the round trips (checkpoint file, scan task message) and the "same as a fresh
//! build" checks whose objects have no operator==. A failure names the member by its
//! place in the list (0 first).
#include <gtest/gtest.h>

namespace panoptic::test_support {

template <class T, class... Members>
void expect_fields_equal(const T& a, const T& b, Members T::*... members) {
  int k = 0;
  const auto expect_equal = [&](auto member) {
    EXPECT_EQ(a.*member, b.*member) << "member " << k << " of the list";
    ++k;
  };
  (expect_equal(members), ...);
}

}  // namespace panoptic::test_support
