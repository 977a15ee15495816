#!/usr/bin/env bash
# The wheel from scripts/build_wheel.sh works with no build tree and no Debian -dev package on the path:
# installed into a fresh venv, imported from an empty directory, it solves a torque-limited problem;
# auditwheel finds no external library beyond the manylinux policy, and the bundled GLPK is the one
# the extension loads.
set -euo pipefail
cd "$(dirname "$0")/../.."
whl=$(ls dist/pathpace-*manylinux*.whl)
PATH="$PWD/.venv/bin:$PATH"

show=$(auditwheel show "$whl" 2>&1 | tr '\n' ' ')
echo "$show" | grep -q 'is consistent with the following platform tag: "manylinux_' \
  || { echo "test_wheel: auditwheel: $show" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
V="$tmp/venv"
python3 -m venv "$V"
"$V/bin/python" -m pip install -q "$whl" 2>&1 | { grep -v '^WARNING: Location' || true; }
urdf="$PWD/tests/data/pendulum.urdf"
mkdir "$tmp/run"
cd "$tmp/run"
# -I: isolated mode (no PYTHONPATH, no user site, no current directory on sys.path).
"$V/bin/python" -I - "$urdf" <<'PY'
import os, subprocess, sys
import numpy as np
import pathpace as pp

here = os.path.dirname(pp.__file__)
assert here.startswith(sys.prefix) and "site-packages" in here, here
core = pp._core.__file__
ldd = subprocess.run(["ldd", core], capture_output=True, text=True, check=True).stdout
glpk = [l for l in ldd.splitlines() if "libglpk" in l]
assert glpk and "pathpace.libs" in glpk[0], ldd
robot = pp.RobotModel.from_urdf(sys.argv[1])
path = pp.CubicSplinePath(np.array([[0.0], [0.25], [0.5]]))
prob = pp.TimeScalingProblem(path, grid=200)
prob.add_velocity_limits(-robot.velocity_limits, robot.velocity_limits)
prob.add_torque_limits(robot)
res = prob.solve()
assert res.status == pp.Status.OPTIMAL, res.message
t = np.linspace(0.0, res.duration, 50)
tau = res.trajectory().torques(t)
print(f"wheel ok: {os.path.basename(core)}, T = {res.duration:.4f} s, max |tau| = {np.abs(tau).max():.3f} N m")
PY
