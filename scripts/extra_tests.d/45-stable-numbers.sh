#!/usr/bin/env bash
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#
# The same scores whichever vector code OpenCV picks and on one thread: scripts/stable_numbers.sh
# on two generated scenes and, when ../shared is there, three real clips; any precision or AUC
# more than 0.02 from the default run fails (docs/portability.md).
#   OT_BUILD_DIR  the catkin build (default _build)
set -euo pipefail
cd "$(dirname "$0")/../.."
exec bash scripts/stable_numbers.sh
