#pragma once
// The error tiers of moreau (see docs/design): bad input is reported with where it is and what
// would be valid (exit code 2); numerical failure names step, time and object (exit code 3).
#include <stdexcept>
#include <string>

namespace moreau {

/// A scene, mesh or parameter the user supplied is not valid. The message names the file, the
/// JSON path (or line) and what is allowed.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// The simulation diverged (NaN, explosion, inverted elements beyond recovery). The message names
/// the step, the simulated time and the object.
class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace moreau
