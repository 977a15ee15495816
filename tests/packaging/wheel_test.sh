#!/usr/bin/env bash
# The wheel of `make wheel` works without the build tree or the Debian -dev packages' libraries on the
# path: installed into a fresh venv (no system site-packages), run from an empty directory, it loads the
# bundled libraries and solves a torque-limited problem; `auditwheel show` finds nothing external
# beyond the manylinux policy; the bundled libraries' licences are in the wheel.
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD
wheel=$(ls build/wheel/dist/pathpace-*-manylinux_*.whl)
export PATH="$repo/.venv/bin:$PATH"

show=$(auditwheel show "$wheel" 2>&1)
flat=$(echo "$show" | tr -s ' \n' '  ')   # auditwheel wraps its lines
echo "$flat" | grep -q 'consistent with the following platform tag: "manylinux_' ||
  { echo "wheel_test: auditwheel show: not a manylinux wheel:"; echo "$show"; exit 1; }
if echo "$flat" | grep -q "external shared libraries"; then
  echo "wheel_test: auditwheel show finds external libraries:"; echo "$show"; exit 1
fi
listing=$(python -m zipfile -l "$wheel")
for lic in libglpk40 liburdfdom-model3.0 libconsole-bridge1.0; do
  echo "$listing" | grep -q "licenses/third_party/$lic.copyright" ||
    { echo "wheel_test: licence of $lic missing from the wheel"; exit 1; }
done

venv=build/wheel/venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install -q numpy "$wheel" 2>&1 | grep -v "^WARNING: Location" || true
work=$(mktemp -d)
cp tests/data/pendulum.urdf "$work/"
cd "$work"
# Nothing of the repository on the path; the glpk/urdfdom libraries must be the bundled ones.
PYTHONPATH= "$repo/$venv/bin/python" - <<'PY'
import sys

import numpy as np
import pathpace as pp

assert pp.__file__.startswith(sys.prefix) and "site-packages" in pp.__file__, pp.__file__  # the venv's copy
assert not any(p.endswith("/python") or "/build/cp" in p for p in sys.path), sys.path
robot = pp.RobotModel.from_urdf("pendulum.urdf")
prob = pp.TimeScalingProblem(pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]])), grid=500)
prob.add_torque_limits(robot, scale=0.9)
res = prob.solve()
assert res.ok, res
maps = open("/proc/self/maps").read()
for lib in ("libglpk", "liburdfdom_model"):
    paths = {line.split()[-1] for line in maps.splitlines() if lib in line}
    assert paths and all("pathpace.libs" in p for p in paths), (lib, paths)
print(f"wheel_test: fresh venv, torque-limited pendulum: {res.status.name}, T = {res.duration:.4f} s; "
      f"glpk and urdfdom loaded from pathpace.libs")
PY
# The command-line entry point of the wheel, on a JSON problem file (no YAML parser in the fresh venv).
echo '{"robot": {"urdf": "pendulum.urdf"}, "path": {"waypoints": [[0.0], [-0.3], [0.4]]}, "grid": 500,
       "limits": {"torque": {"scale": 0.9}}}' > problem.json
out=$("$repo/$venv/bin/pathpace" solve problem.json --out traj.csv --stats)  # --stats: the JSON, not the one-line summary
echo "$out" | grep -q '"status": "optimal"' ||
  { echo "wheel_test: pathpace solve failed in the fresh venv"; exit 1; }
head -1 traj.csv | tr -d '\r' | grep -q '^t,q_hinge,qd_hinge,qdd_hinge$' || { echo "wheel_test: unexpected CSV header"; exit 1; }
cd "$repo"
rm -rf "$work"
