#!/usr/bin/env bash
# Runs every test of an existing build (_build, made by scripts/setup.sh): the unit, sequence and
# rostests through CTest, then the extra suites (sanitizers, fuzzing) that scripts/extra_tests.d
# adds. Exits non-zero on any failure.
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
export ROS_HOSTNAME=localhost
export ROS_HOME=$PWD/_build/ros_home
status=0
ctest --test-dir _build -j2 --output-on-failure --timeout 900 || status=1
for extra in scripts/extra_tests.d/*.sh; do
  [ -e "$extra" ] || continue
  echo "== $extra"
  bash "$extra" || { echo "FAILED: $extra"; status=1; }
done
exit $status
