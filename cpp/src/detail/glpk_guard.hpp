#pragma once
// GLPK aborts the process on misuse (glp_error). Code that calls GLPK installs this hook with a state
// of its own and a setjmp right before the calls: the hook longjmps back there, after which GLPK
// requires glp_free_env() (which frees every problem of the thread's environment).
#include <csetjmp>

namespace pathpace::detail {

struct GlpkHookState {
  std::jmp_buf env;
};

extern "C" void pathpace_glpk_error_hook(void* info);

}  // namespace pathpace::detail
