#!/usr/bin/env bash
# RNEA per call in C++: pathpace vs pinocchio (from the pin wheel's headers and libraries).
# Needs `make cpp` (build/install is made here) and the .venv of scripts/setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
PREFIX=$(.venv/bin/python -c 'import importlib.metadata as m; print(m.distribution("pin").locate_file("cmeel.prefix"))')
ROBOTS=$(.venv/bin/python -c 'from pathpace.robots import example_robot_data_dir; print(example_robot_data_dir())')
cmake --install build/cpp --prefix build/install >/dev/null
mkdir -p build/bench
# pinocchio needs boost::variant with more alternatives than boost.mpl preprocesses by default.
g++ -O3 -DNDEBUG -std=c++17 -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION -DPINOCCHIO_WITH_URDFDOM bench/rnea_cpp.cpp -o build/bench/rnea_cpp \
  -I build/install/include -I "$PREFIX/include" -I /usr/include/eigen3 \
  build/install/lib/libpathpace.a -L "$PREFIX/lib" -Wl,-rpath,"$PREFIX/lib" \
  -lpinocchio_default -lpinocchio_parsers -lglpk -lurdfdom_model -lconsole_bridge
echo "Panda (fingers locked):"
build/bench/rnea_cpp "$ROBOTS/panda_description/urdf/panda.urdf" fixed panda_finger_joint1 panda_finger_joint2
MIMIC=$(.venv/bin/python -c "
import xml.etree.ElementTree as ET
print(' '.join(j.get('name') for j in ET.parse('$ROBOTS/talos_data/robots/talos_full_v2.urdf').getroot().iter('joint') if j.find('mimic') is not None))")
echo "Talos + floating base (mimic joints locked):"
# shellcheck disable=SC2086
build/bench/rnea_cpp "$ROBOTS/talos_data/robots/talos_full_v2.urdf" floating $MIMIC
