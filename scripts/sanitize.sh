#!/usr/bin/env bash
# ASan + UBSan run (part of `make test`; alone: `make test-sanitize`): the library, the C++ tests and
# the Python extension are built once more with -fsanitize=address,undefined in build/asan, then
#   - ctest runs there (leak detection on), and
#   - the Python tests that exercise the bindings run against that extension, with libasan preloaded
#     into the (uninstrumented) interpreter and leak detection off (CPython keeps its arenas).
# Any sanitizer report aborts the process (halt_on_error, -fno-sanitize-recover), which fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-2}
B=build/asan
PY=.venv/bin/python
SAN="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"

# Debug with -O1: Eigen's bounds assertions stay on (an abort fails the run too), the code stays fast
# enough for the tests, and pybind11 adds no LTO. -g1 (line tables) is all a report's stack needs and
# compiles the pybind11 files much faster than full debug information.
cmake -S . -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
  -DCMAKE_CXX_FLAGS="$SAN" -DCMAKE_EXE_LINKER_FLAGS="$SAN" -DCMAKE_SHARED_LINKER_FLAGS="$SAN" \
  -DCMAKE_MODULE_LINKER_FLAGS="$SAN" -DPATHPACE_BUILD_TESTS=ON -DPATHPACE_BUILD_PYTHON=ON -DBUILD_SHARED_LIBS=OFF \
  -DPython_EXECUTABLE="$PWD/$PY" -Dpybind11_DIR="$($PY -m pybind11 --cmakedir)" >/dev/null
cmake --build "$B" -j "$JOBS"

export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$B" && ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:strict_string_checks=1 \
  ctest --output-on-failure -j "$JOBS")

# The package as installed, with the sanitized extension in it.
stage="$B/python/pathpace"
rm -rf "$B/python"
mkdir -p "$stage"
for f in python/pathpace/*; do ln -s "$PWD/$f" "$stage/"; done
cp "$B"/cpp/bindings/_core*.so "$stage/"

# libstdc++ is preloaded too: otherwise ASan's __cxa_throw interceptor, resolved when libasan loads
# into the C interpreter, finds no real __cxa_throw and aborts at the first C++ exception.
PRELOAD="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libstdc++.so)"
# Tests that drive the bindings (paths, problems, robots, contacts, threads, bad input, fuzz; Python
# callbacks called from the solver's threads: path-likes, user dynamics, toppra's constraint objects; frame
# limits); examples and the pinocchio/cvxpy-heavy comparisons add time, not binding coverage.
TESTS=(tests/python/test_robustness.py tests/python/test_api.py tests/python/test_paths.py
       tests/python/test_problem.py tests/python/test_contact.py tests/python/test_contact_phases.py
       tests/python/test_argument_errors.py tests/python/test_path_like.py tests/python/test_second_order.py
       tests/python/test_frame_limits.py tests/python/test_toppra_compat.py tests/python/fuzz)
PYTHONPATH="$PWD/$B/python" LD_PRELOAD="$PRELOAD" \
  ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:allocator_may_return_null=1 \
  "$PY" -m pytest -q -p no:cacheprovider "${TESTS[@]}" \
  --deselect tests/python/test_api.py::test_malloc_tuning_is_on_by_default_and_can_be_switched_off  # ASan owns malloc
