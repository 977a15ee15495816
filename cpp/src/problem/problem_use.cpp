// TimeScalingProblem::Use: a problem is read by any number of threads or modified by one, never both
// (solve() reads the rows that add_*() appends to; an add during a solve would free them under it).
#include <string>

#include "pathpace/errors.hpp"
#include "pathpace/time_scaling_problem.hpp"

namespace pathpace {

TimeScalingProblem::Use::Use(const TimeScalingProblem& problem, Kind kind, const char* what)
    : count_(problem.use_), kind_(kind) {
  std::lock_guard<std::mutex> lock(count_.mutex);
  // The thread that modifies a problem may read it and modify it again (add_contacts -> add_constraint).
  const bool own = count_.writers > 0 && count_.writer == std::this_thread::get_id();
  if (!own && (count_.writers > 0 || (kind == Write && count_.readers > 0)))
    throw Error(std::string(what) + ": this TimeScalingProblem is being " + (count_.writers > 0 ? "modified" : "solved") +
                " in another thread; add every constraint before solving from several threads");
  if (kind == Write) {
    ++count_.writers;
    count_.writer = std::this_thread::get_id();
  } else {
    ++count_.readers;
  }
}

TimeScalingProblem::Use::~Use() {
  std::lock_guard<std::mutex> lock(count_.mutex);
  if (kind_ == Write) {
    if (--count_.writers == 0) count_.writer = std::thread::id();
  } else {
    --count_.readers;
  }
}

}  // namespace pathpace
