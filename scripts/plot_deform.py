#!/usr/bin/python3
"""Plot the per-time-unit log of a deforming-mesh run, or a speed sweep, into one PNG.

usage: plot_deform.py LOG.csv OUT.png [--title T]
       plot_deform.py --sweep SWEEP.csv OUT.png [--title T]
       plot_deform.py --kappa KAPPA.csv OUT.png [--title T]

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
"paper" or "every-step"; optional: samples, kappa, lambda). Plots total changes and number of
updates against the speed theta, log-log, one line per schedule (the "scheduled vs
every-step" curve), and, when there are exactly two schedules, the ratios of the second
(every-step) to the first (paper) per speed, with a 1/theta reference line.

KAPPA.csv (--kappa): one row per kappa with columns kappa, updates, changes and any of
worst_min_angle_deg, worst_normal_deviation_deg, worst_min_edge_angle_deg,
worst_max_radius_edge, worst_R_over_eps, worst_hausdorff_over_eps, self_intersections,
inverted_triangles, violations, emergency_updates (scripts/deform_sweep --kappa). Plots them
against kappa (log scale): work, angles, ratios and failure counts.

Needs matplotlib (run with /usr/bin/python3).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, NullFormatter  # noqa: E402

PLAIN = FuncFormatter(lambda x, _: f"{x:g}")


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


def first_value(c, name):
    """The first finite value of a numeric column, or None."""
    for x in c.get(name, []):
        if isinstance(x, float) and not math.isnan(x):
            return x
    return None


def run_parameters(c):
    """'2000 samples, kappa 32' from the optional columns samples and kappa."""
    parts = []
    n = first_value(c, "samples")
    if n is not None:
        parts.append(f"{n:g} samples")
    k = first_value(c, "kappa")
    if k is not None and len(set(c["kappa"])) == 1:
        parts.append(f"kappa {k:g}")
    return ", ".join(parts)


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
    # Prefer the order (paper, every-step) for the ratio: naive / scheduled.
    if "paper" in schedules:
        schedules.remove("paper")
        schedules.insert(0, "paper")
    series = {}
    for quantity in ("changes", "updates"):
        for s in schedules:
            series[s, quantity] = dict(sorted(
                (v, q) for name, v, q in zip(c["schedule"], c["speed"], c[quantity])
                if str(name) == s and v > 0 and q > 0))
    ratio = len(schedules) == 2
    speeds = sorted({v for v in c["speed"] if v > 0})

    def speed_axis(ax, ylabel, loc="best"):
        ax.set_xscale("log")
        ax.set_xticks(speeds)
        ax.xaxis.set_major_formatter(PLAIN)
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.tick_params(axis="x", labelrotation=45)
        ax.set_xlabel("speed theta")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="major", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc=loc)

    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5)) if ratio else \
        plt.subplots(1, 2, figsize=(11, 4.4))
    axes = list(axes.flat)
    # Changes on a linear axis from 0 (their differences are small); updates log-log.
    for s in schedules:
        pts = series[s, "changes"]
        if pts:
            axes[0].plot(list(pts), list(pts.values()), marker="o", label=s)
    axes[0].set_ylim(bottom=0)
    speed_axis(axes[0], "total mesh changes (flips + Adds + Removes)", loc="lower right")
    for s in schedules:
        pts = series[s, "updates"]
        if pts:
            axes[1].plot(list(pts), list(pts.values()), marker="o", label=s)
    axes[1].set_yscale("log")
    speed_axis(axes[1], "updates")
    if ratio:
        a, b = schedules
        def ratios(quantity):
            common = sorted(set(series[a, quantity]) & set(series[b, quantity]))
            return common, [series[b, quantity][v] / series[a, quantity][v] for v in common]
        ax = axes[2]
        xs, ys = ratios("updates")
        if xs:
            ax.plot(xs, ys, marker="s", color="C1", label=f"updates: {b} / {a}")
            v0, y0 = xs[0], ys[0]  # 1/theta through the ratio at the smallest speed
            ax.plot(xs, [y0 * v0 / v for v in xs], "k--", linewidth=0.8,
                    label="proportional to 1/theta (the paper's O(1/theta))")
        xs, ys = ratios("changes")
        if xs:
            ax.plot(xs, ys, marker="o", color="C0", label=f"changes: {b} / {a}")
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(PLAIN)
        speed_axis(ax, "ratio")
        ax = axes[3]
        if xs:
            ax.plot(xs, ys, marker="o", color="C0", label=f"changes: {b} / {a}")
        ax.axhline(1.0, color="0.5", linewidth=0.8)
        lo, hi = min(ys + [1.0]), max(ys + [1.0])
        pad = max(0.01, 0.1 * (hi - lo))
        ax.set_ylim(lo - pad, hi + pad)
        speed_axis(ax, "changes ratio (linear scale)")
    params = run_parameters(c)
    lam, speed = first_value(c, "lambda"), first_value(c, "speed")
    if lam is not None and speed:
        params += (", " if params else "") + f"lambda = {lam / speed:.3g} theta"
    fig.suptitle((title or path) + (f" ({params})" if params else ""), fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


def plot_kappa(path, out, title):
    c = read_csv(path)
    if "kappa" not in c:
        sys.exit(f"{path}: no column 'kappa'")
    order = sorted(range(len(c["kappa"])), key=lambda i: c["kappa"][i])
    k = [c["kappa"][i] for i in order]
    col = lambda name: [c[name][i] for i in order]  # noqa: E731
    has = lambda *names: [n for n in names if n in c]  # noqa: E731
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    axes = [a for row in axes for a in row]

    def finish(ax, ylabel, log=False, loc="best"):
        ax.set_xscale("log")
        ax.set_xticks(k)
        ax.set_xticklabels([f"{x:g}" for x in k])
        ax.minorticks_off()
        if log:
            ax.set_yscale("log")
        ax.set_xlabel("kappa")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="major", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc=loc)

    for name in has("updates", "changes"):
        axes[0].plot(k, col(name), marker="o", label=name)
    finish(axes[0], "count over the run", log=True)
    labels = {"worst_min_angle_deg": "smallest triangle angle",
              "worst_normal_deviation_deg": "largest normal deviation",
              "worst_max_radius_edge": "largest radius-edge ratio",
              "worst_R_over_eps": "largest R / h",
              "worst_hausdorff_over_eps": "largest Hausdorff / h"}
    for name in has("worst_min_angle_deg", "worst_normal_deviation_deg"):
        axes[1].plot(k, col(name), marker="o", label=labels[name])
    if "worst_min_edge_angle_deg" in c:
        axes[1].plot(k, [180.0 - y for y in col("worst_min_edge_angle_deg")], marker="o",
                     label="180 - smallest edge-angle")
    top = max([y for line in axes[1].get_lines() for y in line.get_ydata()
               if math.isfinite(y)] + [1.0])
    axes[1].set_ylim(0, 1.45 * top)  # room for the legend above the lines
    finish(axes[1], "degrees (worst over all time units)", loc="upper right")
    for name in has("worst_max_radius_edge", "worst_R_over_eps", "worst_hausdorff_over_eps"):
        axes[2].plot(k, col(name), marker="o", label=labels[name])
    finish(axes[2], "ratio (worst over all time units)")
    any_count = False
    for name in has("self_intersections", "inverted_triangles", "violations",
                    "emergency_updates"):
        ys = col(name)
        axes[3].plot(k, ys, marker="o", label=name.replace("_", " "))
        any_count = any_count or any(y > 0 for y in ys)
    if any_count:
        axes[3].set_yscale("symlog", linthresh=1)
    else:  # all zero: show 0 plainly
        axes[3].set_ylim(-0.5, 1.5)
        axes[3].set_yticks([0, 1])
    finish(axes[3], "count (summed over the run)")
    params = run_parameters(c)
    sp = first_value(c, "speed")
    if sp is not None:
        params += (", " if params else "") + f"speed {sp:g}"
    fig.suptitle((title or path) + (f" ({params})" if params else ""), fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


def main():
    parser = argparse.ArgumentParser(
        description="Plot a deforming-mesh log (or, with --sweep, a speed sweep; with --kappa, "
                    "a kappa sweep).")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--sweep", action="store_true",
                      help="input is a sweep CSV (schedule, speed, updates, changes)")
    mode.add_argument("--kappa", action="store_true",
                      help="input is a kappa-sweep CSV (kappa, updates, changes, worst_*)")
    parser.add_argument("input", help="LOG.csv or SWEEP.csv")
    parser.add_argument("output", help="OUT.png")
    parser.add_argument("--title", default=None)
    args = parser.parse_args()
    try:
        if args.sweep:
            plot_sweep(args.input, args.output, args.title)
        elif args.kappa:
            plot_kappa(args.input, args.output, args.title)
        else:
            plot_log(args.input, args.output, args.title)
    except OSError as e:
        sys.exit(f"plot_deform.py: {e}")


if __name__ == "__main__":
    main()
