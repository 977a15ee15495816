#include "lp/glpk_guard.hpp"

#include <csetjmp>

#include <glpk.h>

namespace pathpace::detail {

namespace {

struct Frame {  // plain data only: this is what the longjmp returns to
  std::jmp_buf env;
};

thread_local int depth = 0;             // > 0 inside a guarded call
thread_local unsigned long epoch = 0;   // glp_free_env calls after a GLPK error
thread_local long fail_countdown = -1;  // the test hook (glpk_test_fail_after)

extern "C" void jump_back(void* info) { std::longjmp(static_cast<Frame*>(info)->env, 1); }

// GLPK prints nothing of ours: the solver's messages are off anyway, and glp_error's own message (it
// turns the terminal on first) becomes a status.
extern "C" int swallow(void*, const char*) { return 1; }

// A real error from inside GLPK: row 1 of a problem without rows. The problem is freed with the
// environment.
void raise_test_error() {
  glp_prob* p = glp_create_prob();
  glp_set_row_bnds(p, 1, GLP_UP, 0.0, 0.0);
}

}  // namespace

bool glpk_guarded(void (*f)(void*), void* data) noexcept {
  if (depth > 0) {
    f(data);
    return true;
  }
  Frame frame;
  glp_term_hook(swallow, nullptr);
  glp_error_hook(jump_back, &frame);
  depth = 1;
  if (setjmp(frame.env) != 0) {
    // GLPK requires the environment freed after an error; every problem of this thread goes with it.
    depth = 0;
    glp_free_env();
    ++epoch;
    return false;
  }
  if (fail_countdown >= 0 && fail_countdown-- == 0) raise_test_error();
  f(data);
  glp_error_hook(nullptr, nullptr);
  glp_term_hook(nullptr, nullptr);
  depth = 0;
  return true;
}

unsigned long glpk_epoch() noexcept { return epoch; }

bool GlpkProblem::create() noexcept {
  reset();
  glp_prob* p = nullptr;
  if (!guarded([&] { p = glp_create_prob(); })) return false;
  lp_ = p;
  epoch_ = epoch;
  return true;
}

void GlpkProblem::reset() noexcept {
  if (glp_prob* p = get()) (void)guarded([p] { glp_delete_prob(p); });  // an error frees it anyway
  lp_ = nullptr;
}

void glpk_test_fail_after(long calls) noexcept { fail_countdown = calls < 0 ? -1 : calls; }

bool glpk_test_failure_pending() noexcept { return fail_countdown >= 0; }

}  // namespace pathpace::detail
