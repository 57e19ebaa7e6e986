#!/usr/bin/python3
"""Plot the per-time-unit log of a deforming-mesh run, or a speed sweep, into one PNG.

usage: plot_deform.py LOG.csv OUT.png [--title T]
       plot_deform.py --sweep SWEEP.csv OUT.png [--title T]

LOG.csv: one row per time unit. Every column is optional except t; the panels use those
present among
  t, R_over_h, max_radius_edge, hausdorff_over_h      (ratios panel, log scale)
  min_angle_deg, normal_dev_max_deg, normal_dev_mean_deg, min_edge_angle_deg
                                                      (angles panel; the edge-angle is
                                                       drawn as 180 - min edge-angle)
  flips, insertions, removals                         (cumulative changes panel)
  samples, vertices                                   (sizes panel)
  update                                              (1 at a mesh update: light vertical
                                                       lines on every panel, or a rug of
                                                       ticks when there are > 150)
Empty cells, "nan" and "inf" are skipped; lines starting with '#' are comments.

SWEEP.csv: columns schedule, speed, updates, changes (one row per run; e.g. schedule
"scheduled" or "every-step"). Plots total changes and number of updates against the speed
theta, log-log, one line per schedule (the "scheduled vs every-step" curve).

Needs matplotlib (run with /usr/bin/python3).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def to_float(text):
    try:
        x = float(text)
    except (TypeError, ValueError):
        return math.nan
    return x if math.isfinite(x) else math.nan


def read_csv(path):
    """Columns of a CSV file as {name: [float or str]} (numbers where they parse)."""
    with open(path, newline="") as f:
        lines = [line for line in f if line.strip() and not line.lstrip().startswith("#")]
    rows = list(csv.DictReader(lines))
    if not rows:
        sys.exit(f"{path}: no data rows")
    cols = {}
    for name in rows[0]:
        if name is None:
            continue
        key = name.strip()
        raw = [(r.get(name) or "").strip() for r in rows]
        nums = [to_float(v) for v in raw]
        numeric = any(not math.isnan(x) for x in nums) or all(v == "" for v in raw)
        cols[key] = nums if numeric else raw
    return cols


def finite_pairs(xs, ys):
    pts = [(x, y) for x, y in zip(xs, ys) if not (math.isnan(x) or math.isnan(y))]
    return [p[0] for p in pts], [p[1] for p in pts]


def cumulative(values):
    total, out = 0.0, []
    for v in values:
        total += 0.0 if math.isnan(v) else v
        out.append(total)
    return out


def plot_log(path, out, title):
    c = read_csv(path)
    if "t" not in c:
        sys.exit(f"{path}: no column 't'")
    t = c["t"]
    has = lambda *names: [n for n in names if n in c]  # noqa: E731

    panels = []
    ratios = has("R_over_h", "max_radius_edge", "hausdorff_over_h")
    if ratios:
        panels.append("ratios")
    if has("min_angle_deg", "normal_dev_max_deg", "normal_dev_mean_deg", "min_edge_angle_deg"):
        panels.append("angles")
    if has("flips", "insertions", "removals"):
        panels.append("changes")
    if has("samples", "vertices"):
        panels.append("sizes")
    if not panels:
        sys.exit(f"{path}: none of the known columns besides t")

    updates = []
    if "update" in c:
        updates = [x for x, u in zip(t, c["update"]) if not math.isnan(u) and u > 0]

    fig, axes = plt.subplots(len(panels), 1, figsize=(10, 2.8 * len(panels)), sharex=True,
                             squeeze=False)
    axes = [a[0] for a in axes]
    labels = {
        "R_over_h": "R / h",
        "max_radius_edge": "max radius-edge",
        "hausdorff_over_h": "Hausdorff / h",
        "min_angle_deg": "min angle",
        "normal_dev_max_deg": "max normal deviation",
        "normal_dev_mean_deg": "mean normal deviation",
        "flips": "flips",
        "insertions": "insertions (Add)",
        "removals": "removals",
        "samples": "samples",
        "vertices": "vertices",
    }
    for ax, panel in zip(axes, panels):
        if len(updates) <= 150:
            for x in updates:
                ax.axvline(x, color="0.85", linewidth=0.6, zorder=0)
        else:  # too many lines would grey out the panel: a rug of ticks along the bottom
            ax.plot(updates, [0.0] * len(updates), "|", color="0.6", markersize=6,
                    transform=ax.get_xaxis_transform(), clip_on=False, zorder=0)
        if panel == "ratios":
            positive = False
            for name in ratios:
                xs, ys = finite_pairs(t, c[name])
                ax.plot(xs, ys, label=labels[name], linewidth=1.2)
                positive = positive or any(y > 0 for y in ys)
            if positive:
                ax.set_yscale("log")
            ax.set_ylabel("ratio")
        elif panel == "angles":
            for name in has("min_angle_deg", "normal_dev_max_deg", "normal_dev_mean_deg"):
                xs, ys = finite_pairs(t, c[name])
                ax.plot(xs, ys, label=labels[name], linewidth=1.2)
            if "min_edge_angle_deg" in c:
                xs, ys = finite_pairs(t, c["min_edge_angle_deg"])
                ax.plot(xs, [180.0 - y for y in ys], label="180 - min edge-angle", linewidth=1.2)
            ax.set_ylabel("degrees")
        elif panel == "changes":
            cum = {n: cumulative(c[n]) for n in has("flips", "insertions", "removals")}
            for name, ys in cum.items():
                ax.plot(t, ys, label=labels[name], linewidth=1.2)
            if len(cum) > 1:
                total = [sum(v) for v in zip(*cum.values())]
                ax.plot(t, total, label="total", color="black", linewidth=1.6)
            ax.set_ylabel("cumulative changes")
        else:
            for name in has("samples", "vertices"):
                xs, ys = finite_pairs(t, c[name])
                ax.plot(xs, ys, label=labels[name], linewidth=1.2)
            ax.set_ylabel("count")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("t (time units)")
    sub = f"{len(updates)} updates" if "update" in c else ""
    fig.suptitle(title or path, fontsize=11)
    if sub:
        axes[0].set_title(sub, fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


def plot_sweep(path, out, title):
    c = read_csv(path)
    missing = [n for n in ("schedule", "speed", "updates", "changes") if n not in c]
    if missing:
        sys.exit(f"{path}: missing column(s) {', '.join(missing)}")
    schedules = []
    for s in c["schedule"]:
        s = str(s)
        if s not in schedules:
            schedules.append(s)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, quantity, label in [(axes[0], "changes", "total mesh changes"),
                                (axes[1], "updates", "updates")]:
        for s in schedules:
            pts = sorted((v, q) for name, v, q in zip(c["schedule"], c["speed"], c[quantity])
                         if str(name) == s and v > 0 and q > 0)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=s)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("speed theta")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title or path, fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


def main():
    parser = argparse.ArgumentParser(
        description="Plot a deforming-mesh log (or, with --sweep, a speed sweep).")
    parser.add_argument("--sweep", action="store_true",
                        help="input is a sweep CSV (schedule, speed, updates, changes)")
    parser.add_argument("input", help="LOG.csv or SWEEP.csv")
    parser.add_argument("output", help="OUT.png")
    parser.add_argument("--title", default=None)
    args = parser.parse_args()
    try:
        if args.sweep:
            plot_sweep(args.input, args.output, args.title)
        else:
            plot_log(args.input, args.output, args.title)
    except OSError as e:
        sys.exit(f"plot_deform.py: {e}")


if __name__ == "__main__":
    main()
