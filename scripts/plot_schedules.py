#!/usr/bin/python3
"""Compare relaxed and every-step growth of the same skins, into one PNG.

usage: plot_schedules.py OUT.png LABEL=RELAXED.json,EVERY.json [LABEL=...] ...

Each pair is the `--report` of `dynmesh skin INPUT --grow --schedule relaxed` and of the same
run with `--schedule every-step`. EVERY.json may be `-` when the every-step run did not finish
(the bar is then left out and marked). Two panels: checks and wall-clock seconds per input
(logarithmic), each pair labelled with the factor relaxed saves.
Needs matplotlib (run with /usr/bin/python3).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path, label):
    if path == "-":
        return None
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except OSError as e:
        sys.exit(f"plot_schedules.py: error: {path}: {e.strerror}")
    except json.JSONDecodeError as e:
        sys.exit(f"plot_schedules.py: error: {path}:{e.lineno}: {e.msg}")
    for key in ("checks", "seconds", "violations"):
        if key not in report:
            sys.exit(f"plot_schedules.py: error: {path}: no field '{key}' (not a skin --report)")
    if report.get("mode") != "grow":
        sys.exit(f"plot_schedules.py: error: {path}: not a growth run ({label})")
    return report


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        sys.exit(__doc__.strip().splitlines()[2])
    out = argv[1]
    if not out.endswith(".png"):
        sys.exit(f"plot_schedules.py: error: {out}: the output must end in .png")
    rows = []
    for arg in argv[2:]:
        label, sep, paths = arg.partition("=")
        relaxed, comma, every = paths.partition(",")
        if not sep or not comma or not label:
            sys.exit(f"plot_schedules.py: error: '{arg}': expected LABEL=RELAXED.json,EVERY.json")
        rows.append((label, load(relaxed, label), load(every, label)))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    width = 0.38
    for ax, key, title in ((axes[0], "checks", "checks"), (axes[1], "seconds", "wall-clock seconds")):
        for i, (label, r, e) in enumerate(rows):
            ax.bar(i - width / 2, r[key], width, color="#3b7dd8", label="relaxed" if i == 0 else None)
            if e is not None:
                ax.bar(i + width / 2, e[key], width, color="#d8833b", label="every-step" if i == 0 else None)
                factor = e[key] / r[key] if r[key] > 0 else float("inf")
                ax.annotate(f"{factor:.1f}x", (i, max(r[key], e[key])), ha="center", va="bottom", fontsize=9)
            else:
                ax.annotate("every-step\nnot finished", (i + width / 2, r[key]), ha="center", va="bottom", fontsize=8)
        ax.set_yscale("log")
        ax.set_xticks(range(len(rows)))
        ax.set_xticklabels([label for label, _, _ in rows], rotation=15)
        ax.set_title(title)
        ax.legend(loc="upper left", fontsize=8)
    missed = sum(r["violations"] + (e["violations"] if e else 0) for _, r, e in rows)
    fig.suptitle(f"Skin growth: relaxed against every-step scheduling ({missed} missed checks in all runs)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
