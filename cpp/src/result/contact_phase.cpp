// contact_phase_of_s: which contact phase holds at s (Trajectory.contact_phase, the simulator's plan).
#include "pathpace/contact_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/validate.hpp"

namespace pathpace {

Eigen::VectorXi contact_phase_of_s(const std::vector<std::shared_ptr<const ContactConstraint>>& phases,
                                   const Eigen::Ref<const Eigen::VectorXd>& s) {
  if (phases.empty()) detail::fail("phases is empty, expected at least one ContactConstraint");
  for (size_t p = 0; p < phases.size(); ++p) {
    const std::string name = "phases[" + std::to_string(p) + "]";
    if (!phases[p]) detail::fail(name + " is null, expected a ContactConstraint");
    // "The later phase at a switch" needs the list in order of s.
    if (p > 0 && phases[p]->options().active_begin < phases[p - 1]->options().active_begin)
      detail::fail(name + ".active_begin = " + detail::fmt(phases[p]->options().active_begin) + " must be >= phases[" +
                   std::to_string(p - 1) + "].active_begin = " + detail::fmt(phases[p - 1]->options().active_begin) +
                   " (phases in order of s)");
  }
  Eigen::VectorXi out(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i])) detail::fail(detail::at("s", i) + " = " + detail::fmt(s[i]) + " must be finite");
    // The last phase that holds s (active_at: its ends widened by 1e-12 relative, as its rows are): at a
    // switch both adjacent phases hold, and the later one has the contacts that hold after it. Else the
    // phase nearest to s, the later one on a tie (a rounding beyond the path's ends, or a gap).
    int nearest = -1;
    double best = std::numeric_limits<double>::infinity();
    out[i] = -1;
    for (size_t p = phases.size(); p-- > 0;) {
      const ContactOptions& o = phases[p]->options();
      if (phases[p]->active_at(s[i])) {
        out[i] = static_cast<int>(p);
        break;
      }
      const double d = s[i] < o.active_begin ? o.active_begin - s[i] : s[i] - o.active_end;
      if (d < best) {
        best = d;
        nearest = static_cast<int>(p);
      }
    }
    if (out[i] < 0) out[i] = nearest;
  }
  return out;
}

}  // namespace pathpace
