#!/usr/bin/env bash
# Builds interfaces/tf2_msgs (tf2_msgs/msg/TFMessage) into the venv, for a ROS 2 from PyPI,
# which has no tf2_msgs. Called by setup.sh only when `import tf2_msgs` fails; a real ROS
# install has its own tf2_msgs and never runs this. ~1-3 min the first time (cmake + g++).
#
# The five workarounds (ENVIRONMENT.md, "Interface packages and TF"):
#   1. build-only wheels that rosidl_default_generators does not pull in (requirements-build.txt);
#   2. ament_cmake_ros's test dependencies (gmock/gtest vendors, ament_lint, ...) in the same file;
#   3. the wheels' exported CMake targets hard-code the wheel builder's Python and numpy include
#      directories: rewritten to this interpreter's;
#   4. -DPython3_EXECUTABLE=<venv python> -DBUILD_TESTING=OFF;
#   5. AMENT_PREFIX_PATH / CMAKE_PREFIX_PATH = the venv, which is also the install prefix, so the
#      libraries land in <venv>/lib (on the wheels' library path) and the Python package in the
#      venv's site-packages.
set -euo pipefail
cd "$(dirname "$0")"
venv=$(cd ../.venv && pwd)
python="$venv/bin/python"

missing=()
for tool in cmake g++ make; do command -v "$tool" >/dev/null || missing+=("$tool"); done
if ((${#missing[@]})); then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing cmake g++ make"
  $sudo apt-get install -y -q cmake g++ make || { $sudo apt-get update -q && $sudo apt-get install -y -q cmake g++ make; }
fi

"$python" -m pip install -q --disable-pip-version-check -r requirements-build.txt 2>&1 | grep -v "^WARNING: Location" || true

python_include=$("$python" -c "import sysconfig; print(sysconfig.get_paths()['include'])")
numpy_include=$("$python" -c "import numpy; print(numpy.get_include())")
{ grep -rlE "/opt/python/cp3[0-9]+-cp3[0-9]+" --include="*Export.cmake" "$venv/share" 2>/dev/null || true; } | while read -r file; do
  sed -i -E "s#/opt/python/cp3[0-9]+-cp3[0-9]+/include/python3\.[0-9]+#$python_include#g; \
             s#/opt/python/cp3[0-9]+-cp3[0-9]+/lib/python3\.[0-9]+/site-packages/numpy/_core/include#$numpy_include#g" "$file"
done

export AMENT_PREFIX_PATH="$venv" CMAKE_PREFIX_PATH="$venv"
mkdir -p build
cmake -S tf2_msgs -B build/tf2_msgs -DCMAKE_INSTALL_PREFIX="$venv" -DPython3_EXECUTABLE="$python" \
      -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release > build/tf2_msgs.log 2>&1 \
  && cmake --build build/tf2_msgs -j "$(nproc)" >> build/tf2_msgs.log 2>&1 \
  && cmake --install build/tf2_msgs >> build/tf2_msgs.log 2>&1 \
  || { tail -n 30 build/tf2_msgs.log; echo "tf2_msgs build failed (log: interfaces/build/tf2_msgs.log)" >&2; exit 1; }
"$python" -c "from tf2_msgs.msg import TFMessage; TFMessage()" && echo "tf2_msgs installed into $venv"
