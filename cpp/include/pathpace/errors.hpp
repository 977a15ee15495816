#pragma once
/// @file errors.hpp
/// Exceptions thrown by pathpace. Infeasible problems are not errors: they are a Result status.

#include <stdexcept>
#include <string>

namespace pathpace {

/// Base of every exception pathpace throws.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// Bad input: a wrong shape, a NaN, a limit of the wrong sign, an unknown link name...
/// The message names the argument, the index, the value and what was expected,
/// e.g. "vmax[3] = -2 must be > 0". Python sees it as pathpace.InvalidInputError (a ValueError).
class InvalidInput : public Error {
 public:
  explicit InvalidInput(const std::string& what) : Error(what) {}
};

}  // namespace pathpace
