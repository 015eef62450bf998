// One error type for everything a user can cause or meet: its message is a single line that
// the CLI prints as it is before exiting non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace hmb {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace hmb
