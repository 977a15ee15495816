#pragma once
// The one way pathpace calls GLPK (never installed: no GLPK type leaves cpp/src).
//
// GLPK reports misuse and internal failures with glp_error, which prints, calls the hook installed by
// glp_error_hook and then calls abort(). The only way back to the caller is a longjmp out of that hook.
// The environment is then in its error state (glp_at_error), and the only thing to do with it is
// glp_free_env(), which, in GLPK's words, "invalidates all problem objects as if no GLPK routine were
// called": every problem of the thread's environment, not only the one that failed. Hence the rules:
//  1. Every GLPK call runs inside guarded(f). The setjmp is in glpk_guarded's own frame, which holds only
//     plain data. f may only call GLPK and read or write plain data (scalars, arrays sized beforehand):
//     it creates no object with a destructor and throws nothing, because a longjmp skips destructors
//     ([csetjmp.syn]: undefined behaviour wherever a throw would run one). Containers are built before
//     the call and read after it.
//  2. A GLPK error frees every problem of the thread. So every glp_prob* is held by a GlpkProblem, which
//     records the environment's epoch (glpk_epoch(), +1 at each glp_free_env) when it creates the problem.
//     Once the epoch has moved on, get() returns nullptr and the destructor does not delete the problem
//     (it is gone already). The owner then rebuilds the problem from its own copy of the data.
// GLPK keeps one environment per thread (it is built with thread-local storage), so the epoch is per
// thread too.

#include <type_traits>

struct glp_prob;  // GLPK's problem object (glpk.h stays in the .cpp files)

namespace pathpace::detail {

/// Runs f(data) under GLPK's error hook, with GLPK's terminal output swallowed (glp_error turns it on
/// before it prints). Returns false if GLPK raised an error: the environment has then been freed and
/// glpk_epoch() has grown. A call from inside f runs directly, under the outer call's guard.
[[nodiscard]] bool glpk_guarded(void (*f)(void*), void* data) noexcept;

/// guarded([&] { ...GLPK calls on plain data... }): see rule 1 above.
template <typename F>
[[nodiscard]] bool guarded(F&& f) noexcept {
  using Fn = std::remove_reference_t<F>;
  return glpk_guarded([](void* p) { (*static_cast<Fn*>(p))(); }, const_cast<void*>(static_cast<const void*>(&f)));
}

/// The number of times a GLPK error has freed this thread's GLPK environment.
unsigned long glpk_epoch() noexcept;

/// Owner of one GLPK problem that knows whether a GLPK error has freed it (rule 2 above).
class GlpkProblem {
 public:
  GlpkProblem() = default;
  ~GlpkProblem() { reset(); }
  GlpkProblem(const GlpkProblem&) = delete;
  GlpkProblem& operator=(const GlpkProblem&) = delete;

  /// The problem; nullptr if none was created or a GLPK error has freed it since.
  glp_prob* get() const noexcept { return lp_ != nullptr && epoch_ == glpk_epoch() ? lp_ : nullptr; }
  /// A new empty problem in place of the old one. False after a GLPK error (then get() == nullptr).
  bool create() noexcept;
  /// Deletes the problem if it is still alive.
  void reset() noexcept;

 private:
  glp_prob* lp_ = nullptr;
  unsigned long epoch_ = 0;
};

/// Test hook (tests/cpp only): the guarded call that comes after `calls` more guarded calls of this
/// thread (0: the next one) makes GLPK raise an error, from inside GLPK, before it runs its own work.
/// A negative count disarms it.
void glpk_test_fail_after(long calls) noexcept;
/// True while an armed test failure has not fired yet.
bool glpk_test_failure_pending() noexcept;

}  // namespace pathpace::detail
