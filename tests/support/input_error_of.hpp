#pragma once
// What an input is refused with: the message of the io::InputError the call throws, or a message that
// makes the test fail readably when it throws something else or nothing.
#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "imucal/io/errors.hpp"

namespace imucal::testing {

template <class F>
std::string inputErrorOf(F&& f) {
  try {
    f();
  } catch (const io::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no exception";
}

}  // namespace imucal::testing

#define EXPECT_CONTAINS(message, part) \
  EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message) << "\nexpected: " << (part)
