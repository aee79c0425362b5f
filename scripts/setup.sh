#!/usr/bin/env bash
# obstacle_tracker: install what a fresh Debian 12 machine needs, build, then run the demo or the
# tests.   usage: bash scripts/setup.sh demo|test|build|deps
#   deps   install Debian's ROS 1 and OpenCV packages (apt; root or sudo)
#   build  deps + configure and build into _build/ (catkin package, plain CMake, no workspace)
#   demo   build + run the built-in demo on a generated flight scene (writes _demo/)
#   test   build + every test (unit, sequence, rostest, sanitizer, fuzz); non-zero on any failure
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
MODE=${1:-test}
JOBS=${JOBS:-$(nproc)}
# A pyenv/conda python3 earlier on PATH breaks catkin's generators: use Debian's.
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
export ROS_HOSTNAME=localhost
export ROS_HOME=$ROOT/_build/ros_home

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; fi

PACKAGES=(
  cmake g++ make pkg-config libgtest-dev libbenchmark-dev libeigen3-dev libyaml-cpp-dev libcli11-dev libboost-dev
  catkin ros-message-generation ros-std-msgs ros-geometry-msgs ros-sensor-msgs python3-geometry-msgs python3-std-msgs
  libroscpp-dev libxmlrpcpp-dev libstd-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev
  libdiagnostic-msgs-dev libros-rosgraph-msgs-dev python3-rospy
  libnodeletlib-dev libnodeletlib-tools
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libcv-bridge-dev libimage-transport-dev libimage-geometry-dev libopencv-contrib-dev
  libtf2-ros-dev libdiagnostic-updater-dev libvisualization-msgs-dev
  tf2-tools  # Debian ships tf2_ros's static_transform_publisher (launch files, rostests) in it
  librosbag-dev python3-rosbag librostest-dev python3-rostest python3-sensor-msgs
  rosbash python3-rostopic python3-rosnode python3-rosmsg python3-rosparam python3-roslaunch python3-diagnostic-msgs
  python3-numpy python3-matplotlib python3-yaml python3-opencv python3-cv-bridge
  clang libclang-rt-14-dev valgrind
  rviz xvfb imagemagick stress-ng
)

deps() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "== installing ${#missing[@]} Debian packages: ${missing[*]}"
    $SUDO apt-get update -q
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

build() {
  deps
  cmake -S . -B _build -DCMAKE_BUILD_TYPE=Release
  cmake --build _build -j"$JOBS"
}

case "$MODE" in
  deps) deps ;;
  build) build ;;
  demo)
    build
    bash scripts/demo.sh
    ;;
  test)
    build
    cmake --build _build -j"$JOBS" --target tests
    echo "== install and build: $SECONDS s"
    bash scripts/run_tests.sh
    ;;
  *)
    echo "usage: bash scripts/setup.sh demo|test|build|deps" >&2
    exit 2
    ;;
esac
