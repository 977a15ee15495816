# Two entry points for a newcomer (see README.md); each installs what is missing first.
#   make demo   - solve a real problem (Panda arm path) and print the timing
#   make test   - build the library, run the C++ tests (ctest) and the Python tests (pytest), then
#                 both once more under ASan + UBSan (build/asan)
#   make bench  - peer comparison against toppra; writes bench/README.md's table
#   make wheel  - build/wheel/dist/pathpace-*-manylinux_*.whl, installable without the Debian -dev packages
SHELL := /bin/bash
VENV := .venv
PY := $(VENV)/bin/python
export PATH := $(CURDIR)/$(VENV)/bin:$(PATH)
JOBS ?= 2

.PHONY: setup cpp python wheel test test-cpp test-python test-packaging test-wheel test-sanitize fuzz-long demo bench clean

setup:
	@bash scripts/setup.sh

cpp: setup
	@cmake -S . -B build/cpp -G Ninja -DCMAKE_BUILD_TYPE=Release -DPATHPACE_BUILD_TESTS=ON >/dev/null
	@cmake --build build/cpp -j $(JOBS)

python: setup
	@$(PY) -m pip install -q --no-build-isolation .

test-cpp: cpp
	@cd build/cpp && ctest --output-on-failure -j $(JOBS)

test-packaging: cpp
	@cmake --install build/cpp --prefix build/install >/dev/null
	@cmake -S tests/packaging -B build/packaging -G Ninja -DCMAKE_PREFIX_PATH=$(CURDIR)/build/install >/dev/null
	@cmake --build build/packaging >/dev/null
	@./build/packaging/consumer

test-python: python
	@$(PY) -m pytest -q tests/python

# A manylinux wheel with libglpk, liburdfdom and their dependencies bundled (auditwheel), licences included.
wheel: python
	@bash scripts/build_wheel.sh

test-wheel: wheel
	@bash tests/packaging/wheel_test.sh

# ASan + UBSan build of the library, its C++ tests and the extension in build/asan (scripts/sanitize.sh).
test-sanitize: setup
	@JOBS=$(JOBS) bash scripts/sanitize.sh

# The fuzz suite with 20x the examples of `make test` and a fresh seed (PATHPACE_FUZZ_SEED to repeat).
fuzz-long: python
	@PATHPACE_FUZZ=long $(PY) -m pytest -q tests/python/fuzz

test: test-cpp test-packaging test-python test-wheel test-sanitize

demo: python
	@$(PY) examples/demo.py

bench: python cpp
	@$(PY) bench/run.py
	@$(PY) bench/torque.py
	@bash bench/rnea_cpp.sh

clean:
	rm -rf build
