#!/usr/bin/python3
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
"""Scores a tracker's recorded obstacles against ground truth with the evaluate tool's metrics.

usage: score_bag.py RECORDED.bag --gt GT.bag|groundtruth_rect.txt [--topic T] [--gt-topic T]
                    [--fps F] [--start-stamp S] [--name NAME] [--csv FILE] [--score-boxes PATH]
       score_bag.py --boxes BOXES.txt --gt groundtruth_rect.txt  (a box file of evaluate or track_sequence)

RECORDED.bag holds the tracker's obstacle_tracker/ObstacleArray (`~obstacles`, recorded by
launch/replay.launch); the default topic is the one ObstacleArray topic ending in "obstacles".
Each ground-truth frame is matched to the output with the same header stamp; its first (best)
obstacle is the tracker's box and confidence, an empty array or a missing output is "no target".
Ground truth: the /ground_truth ObstacleArray of the bag made by sequence_to_bag.py, or an OTB
text file whose i-th line belongs to stamp START_STAMP + i / FPS (the converter's defaults:
1000 s, 30 fps, or the sequence's fps).

Prints OTB precision@20, success AUC, mean centre error, long-term precision/recall/F (when the
target is absent in some frames), how many frames got exactly one output, and the tracker's
processing_time (median, 99th percentile). The ground-truth file is read and every score computed
by the package's C++ `score_boxes` tool (the metrics of `evaluate`; see score_boxes_tool.py for
where it is looked for); --score-boxes gives its path. Needs python3-rosbag and the package's
generated messages (see sequence_to_bag.py); --boxes needs neither.
"""
import argparse
import bisect
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import score_boxes_tool  # noqa: E402


def stamp_ns(header):
    return header.stamp.secs * 1000000000 + header.stamp.nsecs


def percentile(values, q):
    if not values:
        return math.nan
    v = sorted(values)
    k = (len(v) - 1) * q / 100.0
    lo, hi = int(math.floor(k)), int(math.ceil(k))
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def find_topic(bag, wanted, exclude):
    info = bag.get_type_and_topic_info().topics
    if wanted:
        if wanted not in info:
            sys.exit("score_bag: topic %s not in the bag (topics: %s)" % (wanted, ", ".join(sorted(info))))
        return wanted
    cands = [t for t, i in info.items() if i.msg_type == "obstacle_tracker/ObstacleArray" and t != exclude]
    ending = [t for t in cands if t.endswith("obstacles")]
    if len(ending) == 1:
        return ending[0]
    if len(cands) == 1:
        return cands[0]
    sys.exit("score_bag: cannot tell which ObstacleArray topic to score (%s); use --topic" % ", ".join(cands))


def read_gt_bag(path, topic):
    import rosbag
    out = []  # (stamp_ns, box)
    with rosbag.Bag(path) as bag:
        topic = find_topic(bag, topic, None) if topic is None else topic
        for _, msg, _ in bag.read_messages(topics=[topic]):
            box = score_boxes_tool.ABSENT
            if msg.obstacles:
                o = msg.obstacles[0]
                box = (o.x, o.y, o.width, o.height)
            out.append((stamp_ns(msg.header), box))
    if not out:
        sys.exit("score_bag: no ground truth on %s in %s" % (topic, path))
    out.sort()
    return out


def read_recorded(path, topic, gt_topic):
    import rosbag
    outputs = {}  # stamp_ns -> list of (box, confidence)
    proc, lat = [], []
    with rosbag.Bag(path) as bag:
        topic = find_topic(bag, topic, gt_topic)
        for _, msg, t in bag.read_messages(topics=[topic]):
            box, conf = score_boxes_tool.ABSENT, 0.0
            if msg.obstacles:
                o = msg.obstacles[0]
                box, conf = (o.x, o.y, o.width, o.height), float(o.confidence)
            s = stamp_ns(msg.header)
            outputs.setdefault(s, []).append((box, conf))
            proc.append(float(msg.processing_time))
            lat.append(t.to_sec() - s * 1e-9)
    return topic, outputs, proc, lat


def table(rows):
    widths = [max(len(str(r[i])) for r in rows) for i in range(len(rows[0]))]
    lines = []
    for n, r in enumerate(rows):
        lines.append("| " + " | ".join(str(c).ljust(w) for c, w in zip(r, widths)) + " |")
        if n == 0:
            lines.append("|" + "|".join("-" * (w + 2) for w in widths) + "|")
    return "\n".join(lines)


def fmt(v, p=3):
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else ("%.*f" % (p, v))


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("recorded", nargs="?", help="bag with the tracker's ObstacleArray")
    ap.add_argument("--gt", required=True, help="ground-truth bag (/ground_truth) or OTB text file")
    ap.add_argument("--topic", default=None, help="the tracker's topic (default: auto)")
    ap.add_argument("--gt-topic", default="/ground_truth")
    ap.add_argument("--fps", type=float, default=30.0, help="frame rate for a text ground truth")
    ap.add_argument("--start-stamp", type=float, default=1000.0, help="first stamp for a text ground truth")
    ap.add_argument("--boxes", default=None,
                    help="score a box file of evaluate or track_sequence (x,y,w,h,confidence per frame)")
    ap.add_argument("--name", default=None, help="row name (default: the recorded file's name)")
    ap.add_argument("--csv", default=None, help="append a CSV row with the scores to this file")
    ap.add_argument("--score-boxes", default=None, metavar="PATH",
                    help="the score_boxes tool (default: see score_boxes_tool.py)")
    args = ap.parse_args(argv)
    if args.boxes and args.gt.endswith(".bag"):
        ap.error("--boxes goes with a text ground truth")
    if not args.boxes and not args.recorded:
        ap.error("RECORDED.bag is required (or --boxes)")
    return args


def match_outputs(gt_frames, outputs, tol):
    """The tracker's box and confidence for each ground-truth frame: the output with the same stamp
    (or, when tol > 0, the nearest within tol ns); ABSENT and 0 where there is none."""
    keys = sorted(outputs)
    pred, conf = [], []
    matched = set()
    missing = duplicates = 0
    for s, _ in gt_frames:
        k = None
        if s in outputs:
            k = s
        elif tol > 0 and keys:
            j = bisect.bisect_left(keys, s)
            best = min((keys[i] for i in (j - 1, j) if 0 <= i < len(keys)), key=lambda x: abs(x - s))
            if abs(best - s) <= tol:
                k = best
        if k is None:
            missing += 1
            pred.append(score_boxes_tool.ABSENT)
            conf.append(0.0)
            continue
        matched.add(k)
        if len(outputs[k]) > 1:
            duplicates += 1
        b, c = outputs[k][0]
        pred.append(b)
        conf.append(c)
    unknown = sum(1 for k in outputs if k not in matched)
    summary = {"outputs": sum(len(v) for v in outputs.values()), "missing": missing,
               "duplicates": duplicates, "unknown": unknown}
    return pred, conf, summary


def score_recorded(args, tool):
    """Scores of the recorded bag: (scores, summary, processing times, latencies)."""
    text_gt = not args.gt.endswith(".bag")
    if text_gt:
        boxes = score_boxes_tool.load_gt(args.gt, tool)
        gt_frames = [(int(round((args.start_stamp + i / args.fps) * 1e9)), b) for i, b in enumerate(boxes)]
        if not gt_frames:
            sys.exit("score_bag: no ground truth in %s" % args.gt)
    else:
        gt_frames = read_gt_bag(args.gt, args.gt_topic)
    topic, outputs, proc, lat = read_recorded(args.recorded, args.topic, args.gt_topic)
    # Text ground truth: stamps from fps may differ from the converter's by rounding; match
    # each to the nearest output stamp within a quarter frame.
    tol = int(0.25e9 / args.fps) if text_gt else 0
    pred, conf, summary = match_outputs(gt_frames, outputs, tol)
    print("score_bag: %s on %s: %d outputs for %d ground-truth frames (%d frames without output, "
          "%d with several, %d outputs with a stamp not in the ground truth)"
          % (args.recorded, topic, summary["outputs"], len(gt_frames), summary["missing"],
             summary["duplicates"], summary["unknown"]), file=sys.stderr)
    scores = score_boxes_tool.score(pred, conf, [b for _, b in gt_frames], tool)
    return scores, summary, proc, lat


def print_table(name, sc, proc, lat):
    frames, absent = int(sc["frames"]), int(sc["absent_frames"])
    header = ["run", "frames", "absent", "P@20", "AUC", "centre err (px)", "no box"]
    row = [name, frames, absent, fmt(sc["precision20"]), fmt(sc["auc"]), fmt(sc["mean_centre_error"], 1),
           fmt(sc["lost_fraction"])]
    if absent:
        header += ["LT Pr", "LT Re", "LT F"]
        row += [fmt(sc["lt_precision"]), fmt(sc["lt_recall"]), fmt(sc["lt_fscore"])]
    if proc:
        header += ["proc median (ms)", "proc p99 (ms)"]
        row += [fmt(1e3 * percentile(proc, 50), 2), fmt(1e3 * percentile(proc, 99), 2)]
        med_lat = percentile(lat, 50)
        if 0.0 <= med_lat < 10.0:  # record time vs stamp is a latency only when the stamps were live
            header += ["latency median (ms)", "latency p99 (ms)"]
            row += [fmt(1e3 * med_lat, 1), fmt(1e3 * percentile(lat, 99), 1)]
    print(table([header, row]))


def append_csv(path, name, sc, summary):
    lt = int(sc["absent_frames"]) > 0
    new = not os.path.exists(path)
    with open(path, "a") as f:
        if new:
            f.write("run,frames,absent,precision20,auc,mean_centre_error,lost_fraction,lt_precision,lt_recall,"
                    "lt_fscore,outputs,missing,duplicates,unknown\n")
        f.write(",".join(str(x) for x in [
            name, int(sc["frames"]), int(sc["absent_frames"]), "%.4f" % sc["precision20"], "%.4f" % sc["auc"],
            "%.2f" % sc["mean_centre_error"], "%.4f" % sc["lost_fraction"],
            "%.4f" % sc["lt_precision"] if lt else "", "%.4f" % sc["lt_recall"] if lt else "",
            "%.4f" % sc["lt_fscore"] if lt else "", summary["outputs"], summary["missing"],
            summary["duplicates"], summary["unknown"]]) + "\n")


def main(argv=None):
    args = parse_args(argv)
    tool = score_boxes_tool.find_tool(args.score_boxes)
    if args.boxes:
        scores = score_boxes_tool.score_files(args.boxes, args.gt, tool)
        summary = {"outputs": int(scores["frames"]), "missing": 0, "duplicates": 0, "unknown": 0}
        proc, lat = [], []
        name = args.name or os.path.basename(args.boxes)
    else:
        scores, summary, proc, lat = score_recorded(args, tool)
        name = args.name or os.path.basename(args.recorded)
    print_table(name, scores, proc, lat)
    if args.csv:
        append_csv(args.csv, name, scores, summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
