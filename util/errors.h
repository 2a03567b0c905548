// The error types every floor shares, so that a library reports bad input without including
// the scene loader.
#pragma once

#include <stdexcept>

namespace radkit {

/// A problem with the user's input: the message names the file, the element and the fix.
/// Front ends print it and exit non-zero without writing outputs.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace radkit
