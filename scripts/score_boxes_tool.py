# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
"""How the Python helpers (score_bag.py, sequence_to_bag.py) reach the C++ `score_boxes` tool, which
finds a sequence's files, reads ground-truth and box files and scores them with the metrics of
`evaluate` (src/eval/metrics.cpp), so that the package reads sequences, parses and scores in one
place.

The tool is found by, in order: the path given (a script's --score-boxes), $OT_SCORE_BOXES,
$OT_DEVEL/lib/obstacle_tracker/score_boxes, the catkin build beside the scripts
(_build/devel/lib/obstacle_tracker/score_boxes), `score_boxes` on PATH.
"""
import os
import shutil
import subprocess
import sys
import tempfile

TOOL = "score_boxes"
ABSENT = (0.0, 0.0, 0.0, 0.0)


def find_tool(explicit=None):
    """The score_boxes executable; exits with a message when there is none."""
    if explicit:
        cands = [explicit]
    else:
        here = os.path.dirname(os.path.abspath(__file__))
        cands = [os.environ.get("OT_SCORE_BOXES")]
        if os.environ.get("OT_DEVEL"):
            cands.append(os.path.join(os.environ["OT_DEVEL"], "lib", "obstacle_tracker", TOOL))
        cands.append(os.path.join(here, "..", "_build", "devel", "lib", "obstacle_tracker", TOOL))
        cands.append(shutil.which(TOOL))
    for c in cands:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    sys.exit("%s: cannot find the %s tool (looked at %s); build the package, or give its path with "
             "--score-boxes or OT_SCORE_BOXES" % (os.path.basename(sys.argv[0]), TOOL,
                                                     ", ".join(c for c in cands if c) or "nothing"))


def _run(tool, args):
    proc = subprocess.run([tool] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    if proc.returncode != 0:
        sys.exit(proc.stderr.strip() or "%s exited with %d" % (tool, proc.returncode))
    return proc.stdout


def load_gt(path, tool):
    """The ground-truth boxes of a file as the package reads it: (x, y, w, h) per frame, ABSENT
    where the target is absent."""
    out = []
    for line in _run(tool, ["--gt", path, "--print-gt"]).splitlines():
        out.append(tuple(float(v) for v in line.split(",")))
    return out


def describe_sequence(path, tool, gt_path=None):
    """What the package finds in a sequence folder or video (eval::Sequence): a dict with name,
    kind (otb_folder, image_folder or video), frame_count, fps, video (the path, for a video),
    files (the frame images in order, for a folder) and gt (boxes as load_gt gives them)."""
    if "\n" in path:
        sys.exit("cannot describe a sequence whose path holds a newline: %r" % path)
    # --describe=PATH: a path that starts with '-' is not taken for an option.
    args = ["--describe=" + path] + (["--gt=" + gt_path] if gt_path else [])
    info = {"files": [], "gt": [], "video": None}
    for line in _run(tool, args).splitlines():
        key, _, value = line.partition("=")
        if key == "file":
            info["files"].append(value)
        elif key == "gt":
            info["gt"].append(tuple(float(v) for v in value.split(",")))
        elif key in ("frame_count",):
            info[key] = int(value)
        elif key == "fps":
            info[key] = float(value)
        else:
            info[key] = value
    return info


def is_absent(box):
    return not (box[2] > 0 and box[3] > 0)


def write_boxes(path, boxes, confidence=None):
    """A box file score_boxes reads (x,y,w,h[,confidence] per frame); exact float values."""
    with open(path, "w") as f:
        for i, b in enumerate(boxes):
            values = list(b) + ([confidence[i]] if confidence is not None else [])
            f.write(",".join(repr(float(v)) for v in values) + "\n")


def score_files(boxes_path, gt_path, tool):
    """score_boxes's scores of a box file against a ground-truth file: a dict of floats (frames,
    gt_frames, absent_frames, precision20, auc, mean_centre_error, lost_fraction, and lt_* when the
    target is absent somewhere)."""
    scores = {}
    for line in _run(tool, [boxes_path, "--gt", gt_path]).splitlines():
        key, _, value = line.partition("=")
        scores[key] = float(value)
    return scores


def score(pred, conf, gt, tool):
    """Scores predicted boxes with confidences against ground-truth boxes (equal lengths)."""
    with tempfile.TemporaryDirectory(prefix="score_boxes_") as tmp:
        boxes_path, gt_path = os.path.join(tmp, "boxes.txt"), os.path.join(tmp, "gt.txt")
        write_boxes(boxes_path, pred, conf)
        write_boxes(gt_path, gt)
        return score_files(boxes_path, gt_path, tool)
