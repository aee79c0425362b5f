#!/usr/bin/python3
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
"""Converts a sequence (OTB folder, folder of images, generated scene, or video) to a rosbag.

usage: sequence_to_bag.py SEQ OUT.bag [--fps F] [--frame-id camera] [--fx FX] [--fy FY]
                          [--cx CX] [--cy CY] [--hfov DEG] [--gt FILE] [--encoding auto|bgr8|mono8]
                          [--start-stamp S] [--max-frames N] [--image-topic T] [--info-topic T]
                          [--gt-topic T] [--score-boxes PATH]

Writes, per frame i (stamp = start_stamp + i / fps, also the bag time):
  IMAGE_TOPIC (default /camera/image_raw)    sensor_msgs/Image (bgr8, mono8 or mono16 as decoded)
  INFO_TOPIC  (default /camera/camera_info)  sensor_msgs/CameraInfo, plumb_bob, no distortion,
              K from --fx/--fy/--cx/--cy, else the scene's focal_length_px (scene.yaml), else a
              pinhole with --hfov (default 60 degrees) and the principal point at the centre
  GT_TOPIC    (default /ground_truth)        obstacle_tracker/ObstacleArray: one obstacle (id 1,
              confidence 1, STATE_TRACKING) with the ground-truth box; empty when absent
all with the same header (stamp, frame_id). The sequence is read as evaluate and track_sequence
read it: the package's C++ `score_boxes` tool (--describe) finds its frames, frame rate and
ground-truth file (--score-boxes gives the tool's path; see score_boxes_tool.py for where it is
looked for otherwise). The frame rate is --fps, else the sequence's (the video's, else the `fps`
of scene.yaml / fps.txt, else 30, the OTB convention).

Needs Debian's python3-rosbag, python3-sensor-msgs, python3-cv-bridge, python3-opencv, and the
package's generated Python messages: source <build>/devel/setup.bash, or put
<build>/devel/lib/python3/dist-packages on PYTHONPATH (OT_DEVEL=<build>/devel also works).
"""
import argparse
import glob
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import score_boxes_tool  # noqa: E402


def import_messages():
    """The generated obstacle_tracker messages, looking in the usual build folders if needed."""
    try:
        from obstacle_tracker.msg import Obstacle, ObstacleArray  # noqa: F401
        return Obstacle, ObstacleArray
    except ImportError:
        pass
    here = os.path.dirname(os.path.abspath(__file__))
    candidates = []
    if os.environ.get("OT_DEVEL"):
        candidates.append(os.path.join(os.environ["OT_DEVEL"], "lib", "python3", "dist-packages"))
    candidates += glob.glob(os.path.join(here, "..", "_build", "devel", "lib", "python3", "dist-packages"))
    for c in candidates:
        if os.path.isdir(os.path.join(c, "obstacle_tracker", "msg")):
            sys.path.insert(0, c)
            # A namespace already imported from elsewhere would hide the generated one.
            sys.modules.pop("obstacle_tracker", None)
            try:
                from obstacle_tracker.msg import Obstacle, ObstacleArray  # noqa: F401
                return Obstacle, ObstacleArray
            except ImportError:
                sys.path.pop(0)
    sys.exit("sequence_to_bag: cannot import obstacle_tracker.msg; build the package and source "
             "<build>/devel/setup.bash (or PYTHONPATH=<build>/devel/lib/python3/dist-packages)")


def read_key_value(path, key):
    """`key: value` / `key=value` / `key value` from a small text file; None when absent."""
    try:
        with open(path) as f:
            for line in f:
                m = re.match(r"\s*%s\s*[:= ]\s*([-+0-9.eE]+)" % re.escape(key), line)
                if m:
                    return float(m.group(1))
    except OSError:
        pass
    return None


def scene_focal_length(path):
    """focal_length_px of a generated scene: scene.yaml in its folder, or <stem>_scene.yaml / the
    folder's scene.yaml beside its video; None when not given."""
    if os.path.isdir(path):
        names = [os.path.join(path, "scene.yaml")]
    else:
        stem, folder = os.path.splitext(path)[0], os.path.dirname(path)
        names = [stem + "_scene.yaml", os.path.join(folder, "scene.yaml")]
    for name in names:
        if os.path.isfile(name):
            return read_key_value(name, "focal_length_px")
    return None


class SequenceSource:
    """Frames (decoded as stored) and ground truth of an OTB folder, image folder or video, found
    by the package's own rules (score_boxes --describe, i.e. eval::Sequence)."""

    def __init__(self, path, gt_path=None, score_boxes=None):
        import cv2
        self.cv2 = cv2
        self.path = path
        info = score_boxes_tool.describe_sequence(path, score_boxes_tool.find_tool(score_boxes), gt_path)
        self.files = info["files"]
        self.video = info["video"]
        self.fps = info["fps"]
        self.count = len(self.files) if self.video is None else info["frame_count"]
        self.gt = info["gt"]
        self.meta = {"focal_length_px": scene_focal_length(path)}

    def frames(self):
        if self.video is None:
            for f in self.files:
                img = self.cv2.imread(f, self.cv2.IMREAD_UNCHANGED)
                if img is None:
                    sys.exit("sequence_to_bag: cannot decode %s" % f)
                yield img
        else:
            capture = self.cv2.VideoCapture(self.video)
            if not capture.isOpened():
                sys.exit("sequence_to_bag: cannot open video %s" % self.video)
            while True:
                ok, img = capture.read()
                if not ok:
                    return
                yield img

    def gt_at(self, i):
        return self.gt[i] if i < len(self.gt) else score_boxes_tool.ABSENT


def image_message(img, encoding, header, bridge):
    """The frame as a sensor_msgs/Image through cv_bridge: bgr8 or mono8, or mono16 for a 16-bit
    frame; --encoding bgr8 / mono8 converts an 8-bit frame first."""
    import numpy as np
    cv2 = sys.modules["cv2"]
    if img.ndim == 3 and img.shape[2] == 4:
        img = cv2.cvtColor(img, cv2.COLOR_BGRA2BGR)
    if encoding == "mono8" and img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    elif encoding == "bgr8" and img.ndim == 2:
        if img.dtype != np.uint8:
            sys.exit("sequence_to_bag: --encoding bgr8 with a 16-bit frame")
        img = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    if img.dtype == np.uint8:
        ros_encoding = "bgr8" if img.ndim == 3 else "mono8"
    elif img.dtype == np.uint16 and img.ndim == 2:
        ros_encoding = "mono16"
    else:
        sys.exit("sequence_to_bag: unsupported frame type %s x %d" % (img.dtype, 1 if img.ndim == 2 else img.shape[2]))
    return bridge.cv2_to_imgmsg(img, ros_encoding, header)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequence", help="OTB folder, folder of images, generated scene folder or video")
    ap.add_argument("bag", help="output .bag")
    ap.add_argument("--fps", type=float, default=None)
    ap.add_argument("--frame-id", default="camera")
    ap.add_argument("--fx", type=float, default=None)
    ap.add_argument("--fy", type=float, default=None)
    ap.add_argument("--cx", type=float, default=None)
    ap.add_argument("--cy", type=float, default=None)
    ap.add_argument("--hfov", type=float, default=60.0, help="horizontal field of view (deg) when no focal length is known")
    ap.add_argument("--gt", default=None, help="ground-truth file (default: the sequence's)")
    ap.add_argument("--encoding", choices=["auto", "bgr8", "mono8"], default="auto")
    ap.add_argument("--start-stamp", type=float, default=1000.0, help="stamp of the first frame, s")
    ap.add_argument("--max-frames", type=int, default=0, help="stop after N frames (0: all)")
    ap.add_argument("--image-topic", default="/camera/image_raw")
    ap.add_argument("--info-topic", default="/camera/camera_info")
    ap.add_argument("--gt-topic", default="/ground_truth")
    ap.add_argument("--score-boxes", default=None, metavar="PATH",
                    help="the score_boxes tool, which reads the ground truth (default: see score_boxes_tool.py)")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)

    import rosbag
    import rospy
    from cv_bridge import CvBridge
    from sensor_msgs.msg import CameraInfo
    from std_msgs.msg import Header
    Obstacle, ObstacleArray = import_messages()

    src = SequenceSource(args.sequence, args.gt, args.score_boxes)
    fps = args.fps or src.fps
    if not (fps > 0):
        sys.exit("sequence_to_bag: --fps must be > 0")
    total = src.count if args.max_frames <= 0 else min(src.count, args.max_frames)
    if not src.gt and not args.quiet:
        print("sequence_to_bag: no ground truth found; %s carries empty arrays" % args.gt_topic, file=sys.stderr)
    written = 0
    bridge = CvBridge()
    with rosbag.Bag(args.bag, "w") as bag:
        for i, img in enumerate(src.frames()):
            if args.max_frames > 0 and i >= args.max_frames:
                break
            stamp = rospy.Time.from_sec(args.start_stamp + i / fps)
            im = image_message(img, args.encoding, Header(seq=i, stamp=stamp, frame_id=args.frame_id), bridge)
            h, w = im.height, im.width
            f_default = src.meta.get("focal_length_px") or (0.5 * w / math.tan(math.radians(args.hfov) / 2))
            fx = args.fx or f_default
            fy = args.fy or fx
            cx = args.cx if args.cx is not None else (w - 1) / 2.0
            cy = args.cy if args.cy is not None else (h - 1) / 2.0
            info = CameraInfo()
            info.header = im.header
            info.height, info.width = h, w
            info.distortion_model = "plumb_bob"
            info.D = [0.0] * 5
            info.K = [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0]
            info.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
            info.P = [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
            gt = ObstacleArray()
            gt.header = im.header
            gt.target_frame = args.frame_id
            gt.image_width, gt.image_height = w, h
            box = src.gt_at(i)
            if not score_boxes_tool.is_absent(box):
                o = Obstacle()
                o.id = 1
                o.x, o.y, o.width, o.height = box
                o.confidence = 1.0
                o.peak = 1.0
                o.state = Obstacle.STATE_TRACKING
                o.time_to_contact = math.inf
                o.time_to_contact_sigma = math.inf
                gt.obstacles.append(o)
            bag.write(args.image_topic, im, stamp)
            bag.write(args.info_topic, info, stamp)
            bag.write(args.gt_topic, gt, stamp)
            written += 1
            if not args.quiet and sys.stderr.isatty() and (written % 25 == 0 or written == total):
                print("\rsequence_to_bag: %d/%d frames" % (written, total), end="", file=sys.stderr)
    if not args.quiet:
        if sys.stderr.isatty():
            print("", file=sys.stderr)
        print("sequence_to_bag: wrote %s: %d frames %dx%d at %g fps (%s, %s, %s), stamps %.3f..%.3f s"
              % (args.bag, written, w if written else 0, h if written else 0, fps, args.image_topic,
                 args.info_topic, args.gt_topic, args.start_stamp, args.start_stamp + (written - 1) / fps),
              file=sys.stderr)
    if written == 0:
        sys.exit("sequence_to_bag: no frame written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
