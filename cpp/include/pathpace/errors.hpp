#pragma once
/// @file errors.hpp
/// Exceptions thrown by pathpace. Infeasible problems are not errors: they are a Result status.

#include <stdexcept>
#include <string>

namespace pathpace {

// docstrings.txt @@ Error
/// @brief Base of every error pathpace raises; e.g. Result.trajectory() without a timing, or a problem modified
/// while another thread solves it. Infeasible problems are not errors: they are a Result status.
///
/// A std::runtime_error.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// docstrings.txt @@ InvalidInputError
/// @brief Bad input: the message names the argument, index, value and what was expected.
///
/// A wrong shape, a NaN, a limit of the wrong sign, an unknown link name...: e.g. "vmax[3] = -2 must be > 0".
///
/// Python sees it as pathpace.InvalidInputError (a ValueError).
class InvalidInput : public Error {
 public:
  explicit InvalidInput(const std::string& what) : Error(what) {}
};

}  // namespace pathpace
