#pragma once
// Wall-clock time of the solve's stages (SolverStats::time_*) and its budget (SolverOptions::time_limit).

#include <chrono>

namespace pathpace::detail {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace pathpace::detail
