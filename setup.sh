#!/usr/bin/env bash
# One command from a fresh Debian 12 / Python 3.11 machine to a running door task:
#   1. Debian libraries open3d needs (installed only if missing),
#   2. a venv in .venv with the pinned requirements (skipped when requirements.txt is unchanged),
#   3. tf2_msgs built into the venv, only where `import tf2_msgs` fails (ROS 2 from PyPI has none),
#   4. `colcon build` of the ROS 2 workspace in ros_ws/ (ament_python packages),
#   5. the main job (skip with --no-run).
# Idempotent: a second run takes a few seconds.
set -euo pipefail
cd "$(dirname "$0")"
root=$(pwd)
run_main=1
for arg in "$@"; do
  case "$arg" in
    --no-run) run_main=0 ;;
    *) echo "usage: $0 [--no-run]" >&2; exit 2 ;;
  esac
done
export ROS_AUTOMATIC_DISCOVERY_RANGE=${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}

step() { printf '\n== %s\n' "$*"; }

step "Debian libraries"
missing=()
for pkg in libusb-1.0-0 libgomp1 libegl1 libgl1 libx11-6; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if ((${#missing[@]})); then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing ${missing[*]}"
  $sudo apt-get install -y -q "${missing[@]}" || { $sudo apt-get update -q && $sudo apt-get install -y -q "${missing[@]}"; }
else
  echo "present"
fi

step "Python venv (.venv) with requirements.txt"
python=${PYTHON:-python3}
[ -x .venv/bin/python ] || "$python" -m venv .venv
stamp=.venv/.requirements.sha256
wanted=$(sha256sum requirements.txt | cut -d' ' -f1)
if [ "$(cat "$stamp" 2>/dev/null)" != "$wanted" ]; then
  .venv/bin/python -m pip install -q --disable-pip-version-check -r requirements.txt 2>&1 | grep -v "^WARNING: Location" || true
  .venv/bin/python -c "import rclpy, pinocchio, pybullet, open3d, cv2, osqp, rosbags, foxglove"
  echo "$wanted" > "$stamp"
else
  echo "up to date"
fi

step "tf2_msgs for /tf (built only where it is not importable)"
tf2_stamp=.venv/.tf2_msgs.sha256
tf2_wanted=$(cat requirements.txt interfaces/requirements-build.txt interfaces/build_tf2_msgs.sh \
               interfaces/tf2_msgs/CMakeLists.txt interfaces/tf2_msgs/package.xml interfaces/tf2_msgs/msg/*.msg | sha256sum | cut -d' ' -f1)
if .venv/bin/python -c "import tf2_msgs.msg" 2>/dev/null && { [ ! -f "$tf2_stamp" ] || [ "$(cat "$tf2_stamp")" = "$tf2_wanted" ]; }; then
  echo "present"   # the system's (real ROS install), or ours from an earlier run
else
  tf2_started=$SECONDS
  interfaces/build_tf2_msgs.sh
  echo "$tf2_wanted" > "$tf2_stamp"
  echo "tf2_msgs built in $((SECONDS - tf2_started)) s"
fi

step "Source packages importable from the venv (like pip install -e)"
site=$(.venv/bin/python -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")
printf '%s\n' "$root/msgs" "$root/sim_bridge" "$root"/src/*/ > "$site/door_traversal.pth"
echo "$site/door_traversal.pth"

step "colcon build (ros_ws)"
(cd ros_ws && AMENT_PREFIX_PATH="$root/.venv" ../.venv/bin/colcon --log-base log build \
   --event-handlers console_direct- 2>&1 | tail -n 3)

if ((run_main)); then
  step "Main job: the door task in simulation (python -m door_bringup.door_task; options: --help)"
  .venv/bin/python -m door_bringup.door_task
fi
