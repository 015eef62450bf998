// The shape every user-facing failure must have: hmb::Error with a one-line message.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "hmblur/error.h"

namespace hmb::test {

// Runs `action`, which must throw hmb::Error with a one-line message containing `needle`.
template <typename Action>
void expectError(Action&& action, const std::string& needle) {
  try {
    action();
    ADD_FAILURE() << "expected hmb::Error containing '" << needle << "'";
  } catch (const hmb::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace hmb::test
