# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
"""Ground-truth parsing and tracking metrics for the Python helpers (score_bag.py,
sequence_to_bag.py). Same definitions as the C++ src/eval/metrics.cpp (see metrics.h):

- OTB (Wu et al., TPAMI 2015): precision(t) = fraction of frames with centre error <= t px,
  t = 0..50; success(o) = fraction of frames with IoU > o, o = 0, 0.05, ..., 1; AUC = mean of the
  success curve. Frames whose ground truth is absent are left out; a frame without a reported box
  is a failure (centre error inf, IoU 0).
- VOT long-term (Lukezic et al. 2018): Pr(tau) = mean IoU over frames with a report of
  confidence >= tau (IoU 0 where the target is absent), Re(tau) = mean IoU over frames with the
  target present; F = max over tau of 2 Pr Re / (Pr + Re).

Only the standard library (no numpy needed).
"""
import math
import re

ABSENT = (0.0, 0.0, 0.0, 0.0)


def is_absent(box):
    if box is None:
        return True
    x, y, w, h = box
    return any(math.isnan(v) or math.isinf(v) for v in box) or not (w > 0) or not (h > 0)


def parse_gt_line(line):
    """One ground-truth line -> (x, y, w, h); ABSENT for NaN / empty / zero size.
    Separators: commas, tabs, spaces, semicolons. 8 values = VOT polygon -> its bounding box.
    Raises ValueError when the line is not a box."""
    tokens = [t for t in re.split(r"[,\s;]+", line.strip()) if t]
    if not tokens:
        return ABSENT
    values = [float(t) for t in tokens]  # ValueError for a non-number
    if len(values) == 8:
        xs, ys = values[0::2], values[1::2]
        values = [min(xs), min(ys), max(xs) - min(xs), max(ys) - min(ys)]
    if len(values) != 4:
        raise ValueError("expected 4 or 8 values, got %d" % len(values))
    box = tuple(values)
    return ABSENT if is_absent(box) else box


def load_gt(path):
    boxes = []
    with open(path) as f:
        lines = f.read().splitlines()
    while lines and not lines[-1].strip():
        lines.pop()
    for n, line in enumerate(lines):
        try:
            boxes.append(parse_gt_line(line))
        except ValueError as e:
            if n == 0:
                continue  # a header line
            raise ValueError("%s:%d: %s" % (path, n + 1, e))
    return boxes


def centre_error(a, b):
    if is_absent(a) or is_absent(b):
        return math.inf
    dx = (a[0] + 0.5 * a[2]) - (b[0] + 0.5 * b[2])
    dy = (a[1] + 0.5 * a[3]) - (b[1] + 0.5 * b[3])
    return math.hypot(dx, dy)


def iou(a, b):
    if is_absent(a) or is_absent(b):
        return 0.0
    ix = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
    iy = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    if ix <= 0 or iy <= 0:
        return 0.0
    inter = ix * iy
    union = a[2] * a[3] + b[2] * b[3] - inter
    return min(1.0, inter / union) if union > 0 else 0.0


PRECISION_THRESHOLDS = [float(t) for t in range(51)]
SUCCESS_THRESHOLDS = [0.05 * i for i in range(21)]


def otb_scores(predicted, gt):
    if len(predicted) != len(gt):
        raise ValueError("%d predicted boxes for %d ground-truth boxes" % (len(predicted), len(gt)))
    errors, overlaps = [], []
    for p, g in zip(predicted, gt):
        if is_absent(g):
            continue
        errors.append(centre_error(p, g))
        overlaps.append(iou(p, g))
    n = len(errors)
    precision = [sum(1 for e in errors if e <= t) / n if n else 0.0 for t in PRECISION_THRESHOLDS]
    success = [sum(1 for o in overlaps if o > t) / n if n else 0.0 for t in SUCCESS_THRESHOLDS]
    finite = [e for e in errors if math.isfinite(e)]
    return {
        "frames": n,
        "precision": precision,
        "success": success,
        "precision20": precision[20],
        "auc": sum(success) / len(success),
        "mean_centre_error": sum(finite) / len(finite) if finite else math.nan,
        "lost_fraction": (n - len(finite)) / n if n else 0.0,
    }


def long_term_scores(predicted, confidence, gt, max_thresholds=100):
    if not (len(predicted) == len(confidence) == len(gt)):
        raise ValueError("boxes, confidences and ground truth differ in length")
    ov = [iou(p, g) for p, g in zip(predicted, gt)]
    present = sum(1 for g in gt if not is_absent(g))
    reported = sorted(set(c for p, c in zip(predicted, confidence) if not is_absent(p)))
    result = {"frames": len(gt), "present_frames": present, "precision": 0.0, "recall": 0.0,
              "fscore": 0.0, "threshold": 0.0}
    if not reported:
        return result
    k = min(len(reported), max_thresholds)
    taus = []
    for j in range(k):
        idx = len(reported) - 1 if k == 1 else j * (len(reported) - 1) // (k - 1)
        if not taus or taus[-1] != reported[idx]:
            taus.append(reported[idx])
    best = None
    for tau in taus:
        s_rep = s_pre = 0.0
        n_rep = 0
        for p, c, g, o in zip(predicted, confidence, gt, ov):
            rep = not is_absent(p) and c >= tau
            o = o if rep else 0.0
            if rep:
                s_rep += o
                n_rep += 1
            if not is_absent(g):
                s_pre += o
        pr = s_rep / n_rep if n_rep else 0.0
        re_ = s_pre / present if present else 0.0
        f = 2 * pr * re_ / (pr + re_) if pr + re_ > 0 else 0.0
        if best is None or f > best[0]:
            best = (f, pr, re_, tau)
    result.update(fscore=best[0], precision=best[1], recall=best[2], threshold=best[3])
    return result
