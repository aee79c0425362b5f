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
# Each step's wall time is printed, to see where CI's time goes.
start=$SECONDS
ctest --test-dir _build -j2 --output-on-failure --timeout 900 || status=1
echo "== ctest: $((SECONDS - start)) s"
for extra in scripts/extra_tests.d/*.sh; do
  [ -e "$extra" ] || continue
  echo "== $extra"
  start=$SECONDS
  bash "$extra" || { echo "FAILED: $extra"; status=1; }
  echo "== $extra: $((SECONDS - start)) s"
done
exit $status
