#!/usr/bin/env bash
# rviz overlay test: starts rviz under Xvfb with config/obstacle_tracker.rviz (through
# launch/tracker.launch rviz:=true) while synthetic frames are published, takes screenshots with
# ImageMagick's import and passes when the overlay's box colour (pure green, tracking) is visible,
# the overlay is the main view (its sky, synthetic_frames.h, covers at least 30 % of the screen,
# which a small dock panel beside the 3D view does not) and, in the 3D view, the ~markers bearing
# arrow of an obstacle that is not closing (cyan, a confirmed track with confidence >= 0.5;
# ros/markers.h).
# Skipped, with exit 0 and a SKIPPED message, where rviz, Xvfb or ImageMagick is not installed.
#   usage: rviz_screenshot.sh DEVEL_DIR OUT_DIR
set -u
DEVEL=${1:?devel dir}
OUT=${2:?output dir}
HERE=$(cd "$(dirname "$0")" && pwd)

for tool in rviz xvfb-run Xvfb /usr/bin/import /usr/bin/identify; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "SKIPPED: rviz screenshot test: '$tool' is not installed (apt-get install rviz xvfb imagemagick)"
    exit 0
  fi
done

if [ "${1:-}" != "--inner" ] && [ -z "${OT_RVIZ_INNER:-}" ]; then
  mkdir -p "$OUT"
  export OT_RVIZ_INNER=1
  exec xvfb-run -a -s "-screen 0 1280x1024x24" bash "$0" "$DEVEL" "$OUT"
fi

# Inside Xvfb: our own master on a free port.
export PATH=/usr/bin:/bin:$PATH
export ROS_HOSTNAME=localhost
export ROS_HOME=${ROS_HOME:-$OUT/ros_home}
PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$PORT
export LIBGL_ALWAYS_SOFTWARE=1
SHOT=$OUT/rviz_overlay.png
LOG=$OUT/rviz_overlay_roslaunch.log
rm -f "$SHOT"

launch() {
  "$DEVEL/env.sh" roslaunch -p "$PORT" "$HERE/rviz_overlay.launch" >>"$LOG" 2>&1 &
  LAUNCH=$!
}
stop() {
  kill -INT "$LAUNCH" 2>/dev/null
  for _ in $(seq 1 20); do kill -0 "$LAUNCH" 2>/dev/null || break; sleep 0.5; done
  kill -KILL "$LAUNCH" 2>/dev/null
  wait "$LAUNCH" 2>/dev/null
}
: >"$LOG"
launch

# rviz (Ogre with software GL) sometimes aborts while it starts on a loaded machine, inside its own
# process ("malloc(): unaligned tcache chunk detected" before it subscribed to anything): that is
# rviz's crash, not the overlay missing. It is started again, at most twice, and said so; a third
# crash fails the test.
restarts=0
status=1
green=0
cyan=0
sky_share=0
for attempt in $(seq 1 40); do
  sleep 3
  if ! kill -0 "$LAUNCH" 2>/dev/null; then
    echo "roslaunch ended early; log:"; tail -30 "$LOG"
    break
  fi
  if grep -q "obstacle_tracker_rviz-[0-9]*\] process has died" "$LOG"; then
    if [ "$restarts" -ge 2 ]; then echo "rviz died $((restarts + 1)) times; log:"; tail -30 "$LOG"; break; fi
    restarts=$((restarts + 1))
    echo "rviz died (an abort inside rviz, see $LOG): started again ($restarts of 2)"
    stop
    sed -i 's/process has died/process had died (restarted)/' "$LOG"
    launch
    continue
  fi
  /usr/bin/import -window root "$SHOT" 2>/dev/null || continue
  green=$("$DEVEL/lib/obstacle_tracker/tool_count_colour" "$SHOT" 0 255 0 60 || echo 0)
  cyan=$("$DEVEL/lib/obstacle_tracker/tool_count_colour" "$SHOT" 255 255 0 60 || echo 0)
  # The published frames' sky runs from BGR (170, 100, 40) to (210, 160, 110): all of it within 36
  # of the middle, and nothing else rviz draws is.
  sky=$("$DEVEL/lib/obstacle_tracker/tool_count_colour" "$SHOT" 190 130 75 36 || echo 0)
  pixels=$(/usr/bin/identify -format '%w*%h' "$SHOT" 2>/dev/null) || continue
  [ -n "$pixels" ] || continue  # a screenshot ImageMagick cannot read: take another
  sky_share=$(( 100 * sky / (pixels) ))
  echo "screenshot $attempt: $green overlay-green pixels, $sky_share % of the screen overlay sky, $cyan bearing-arrow cyan pixels"
  # The drawn box: at least a few dozen pixels of its outline after rviz scales the image; the
  # overlay: the main part of the window; the arrow (5 m long, 5 cm thick, seen from 10 m): at
  # least a hundred.
  if [ "$green" -ge 40 ] && [ "$sky_share" -ge 30 ] && [ "$cyan" -ge 100 ]; then status=0; break; fi
done
stop

if [ $status -eq 0 ]; then
  echo "PASSED: rviz shows the overlay box ($green green pixels) in the main view ($sky_share % of the screen) and the bearing arrow ($cyan cyan pixels), screenshot $SHOT"
else
  echo "FAILED: no overlay box ($green green pixels), overlay not the main view ($sky_share % of the screen, < 30 %) or no bearing arrow ($cyan cyan pixels) in rviz's window after 120 s (last screenshot $SHOT, log $LOG)"
  tail -20 "$LOG"
fi
exit $status
