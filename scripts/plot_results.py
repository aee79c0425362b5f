#!/usr/bin/python3
# Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
"""OTB-style precision and success plots from the curves.csv that `evaluate` writes.

usage: plot_results.py CURVES.csv [--results RESULTS.csv] [--out DIR] [--sequence mean:all] [--dpi 80]

Writes one PNG per (mode, subset, curve): e.g. precision_ope_all.png, success_ope_flying.png,
success_tre_all.png. Legends rank the trackers as OTB does: by precision at 20 px for the
precision plot, by the area under the success curve for the success plot; both are evaluate's
own precision20 and auc from the results.csv written beside CURVES (or --results).
Needs only Debian's python3-matplotlib (Agg backend, no display).
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after use("Agg"))


def read_curves(path):
    """{(mode, sequence, curve): {tracker: [(threshold, value), ...]}}"""
    data = defaultdict(lambda: defaultdict(list))
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["mode"], row["sequence"], row["curve"])
            data[key][row["tracker"]].append((float(row["threshold"]), float(row["value"])))
    return data


def read_summaries(path):
    """{(mode, sequence, tracker): {"precision": precision20, "success": auc}} from results.csv"""
    scores = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            scores[(row["mode"], row["sequence"], row["tracker"])] = {
                "precision": float(row["precision20"]), "success": float(row["auc"])}
    return scores


def plot(key, per_tracker, scores, out_dir, dpi):
    mode, sequence, curve = key
    subset = sequence.split(":", 1)[1] if sequence.startswith("mean:") else sequence

    def summary(tracker):
        return scores[(mode, sequence, tracker)][curve]

    ranked = sorted(per_tracker.items(), key=lambda kv: -summary(kv[0]))
    fig, ax = plt.subplots(figsize=(5.2, 4.0))
    styles = ["-", "--", "-.", ":"]
    for i, (tracker, points) in enumerate(ranked):
        points.sort()
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        width = 2.4 if tracker.startswith("ours") else 1.4
        ax.plot(xs, ys, styles[(i // 10) % len(styles)], linewidth=width,
                label="%s [%.3f]" % (tracker, summary(tracker)))
    if curve == "precision":
        ax.set_xlabel("location error threshold (px)")
        ax.set_ylabel("precision")
        ax.set_xlim(0, 50)
        title = "Precision plots of %s" % mode
    else:
        ax.set_xlabel("overlap threshold")
        ax.set_ylabel("success rate")
        ax.set_xlim(0, 1)
        title = "Success plots of %s" % mode
    ax.set_ylim(0, 1)
    ax.grid(True, alpha=0.3)
    ax.set_title("%s (%s)" % (title, subset), fontsize=10)
    ax.legend(loc="lower right" if curve == "precision" else "upper right", fontsize=7)
    fig.tight_layout()
    name = "%s_%s_%s.png" % (curve, mode.lower(), subset.replace("/", "_"))
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("curves", help="curves.csv written by evaluate")
    ap.add_argument("--results", default=None,
                    help="results.csv written by evaluate (default: the one beside CURVES)")
    ap.add_argument("--out", default=None, help="output folder (default: the folder of CURVES)")
    ap.add_argument("--sequence", action="append", default=None,
                    help="which rows to plot (default: every mean:* subset); repeatable")
    ap.add_argument("--dpi", type=int, default=80)
    args = ap.parse_args(argv)
    out_dir = args.out or os.path.dirname(os.path.abspath(args.curves))
    os.makedirs(out_dir, exist_ok=True)
    data = read_curves(args.curves)
    if not data:
        print("plot_results: no curves in %s" % args.curves, file=sys.stderr)
        return 1
    results = args.results or os.path.join(os.path.dirname(os.path.abspath(args.curves)), "results.csv")
    if not os.path.isfile(results):
        print("plot_results: no %s (the results.csv evaluate wrote with the curves; --results FILE)"
              % results, file=sys.stderr)
        return 1
    scores = read_summaries(results)
    wanted = args.sequence
    written = []
    missing = sorted({"%s/%s/%s" % (k[0], k[1], t) for k in data for t in data[k]
                      if (k[0], k[1], t) not in scores})
    if missing:
        print("plot_results: %s has no summary row for %s (curves and results from different runs?)"
              % (results, ", ".join(missing[:3])), file=sys.stderr)
        return 1
    for key in sorted(data):
        sequence = key[1]
        if wanted is None and not sequence.startswith("mean:"):
            continue
        if wanted is not None and sequence not in wanted:
            continue
        written.append(plot(key, data[key], scores, out_dir, args.dpi))
    for p in written:
        print("plot_results: wrote %s" % p, file=sys.stderr)
    return 0 if written else 1


if __name__ == "__main__":
    sys.exit(main())
