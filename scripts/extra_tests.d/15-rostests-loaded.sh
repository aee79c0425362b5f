#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# Every rostest again with the machine loaded: `stress-ng --cpu N` (N = the cores) runs beside
# them. No test may depend on the machine's speed, so what passes on an idle machine must pass
# here too; a timing race shows up here first.
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
export ROS_HOSTNAME=localhost
BUILD=${OT_BUILD_DIR:-_build}
export ROS_HOME=$PWD/$BUILD/ros_home
command -v stress-ng >/dev/null || { echo "15-rostests-loaded: stress-ng is not installed (scripts/setup.sh deps)"; exit 1; }
CORES=$(nproc)
stress-ng --cpu "$CORES" --timeout 1800 --quiet &
STRESS=$!
trap 'kill "$STRESS" 2>/dev/null || true; wait "$STRESS" 2>/dev/null || true' EXIT
sleep 1
kill -0 "$STRESS" 2>/dev/null || { echo "15-rostests-loaded: stress-ng did not start"; exit 1; }
echo "== rostests with stress-ng --cpu $CORES beside them"
ctest --test-dir "$BUILD" -R "_rostest_" -j2 --output-on-failure --timeout 900 --no-tests=error
kill -0 "$STRESS" 2>/dev/null || { echo "15-rostests-loaded: stress-ng ended before the tests did"; exit 1; }
