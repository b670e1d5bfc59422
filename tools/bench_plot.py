#!/usr/bin/env python3
"""Speedup and parallel-efficiency plots of `make bench` (docs/bench/bench.csv), in the
manner of Figs. 6-7 of Huang et al. (MPM3DMP): one line per deck and
adaptive-grid setting, the ideal line, and the paper's measured points (speedup 3.82 at 4
threads and 6.23 at 8; efficiency 0.96 and 0.78).

usage: bench_plot.py BENCH_CSV OUT_DIR   -> OUT_DIR/speedup.png, OUT_DIR/efficiency.png
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PAPER = {"threads": [1, 4, 8], "speedup": [1.0, 3.82, 6.23], "efficiency": [1.0, 0.955, 0.779]}


def main():
    path, out = sys.argv[1], sys.argv[2]
    with open(path) as f:
        rows = list(csv.DictReader(f))
    series = {}
    for r in rows:
        key = (r["deck"].replace(".mpm", ""), int(r.get("regrid_every") or 0))
        series.setdefault(key, []).append((int(r["threads"]), float(r["speedup"]), float(r["efficiency"]),
                                           float(r.get("load1_max") or 0)))
    maxt = max((int(r["threads"]) for r in rows), default=1)
    loads = [float(r.get("load1_max") or 0) for r in rows]
    note = f"this machine: {os.cpu_count()} cores"
    if any(loads):
        note += f"; 1-min load during the runs {min(loads):.2f}-{max(loads):.2f}"
    for what, ylabel in (("speedup", "speedup"), ("efficiency", "parallel efficiency")):
        fig, ax = plt.subplots(figsize=(6.4, 4.8))
        top = max(maxt, 8)
        if what == "speedup":
            ax.plot([1, top], [1, top], "k:", lw=1, label="ideal")
        else:
            ax.axhline(1.0, color="k", ls=":", lw=1, label="ideal")
        ax.plot(PAPER["threads"], PAPER[what], "ks--", label="MPM3DMP paper (Taylor bar)")
        for (deck, rg), pts in sorted(series.items()):
            pts.sort()
            t = [p[0] for p in pts]
            y = [p[1] if what == "speedup" else p[2] for p in pts]
            marker = "o" if rg == 0 else "^"
            label = deck + (f", regrid {rg}" if rg else "")
            ax.plot(t, y, "-", marker=marker, label=label)
        ax.set_xlabel("threads")
        ax.set_ylabel(ylabel)
        ax.set_xlim(0.8, top + 0.2)
        if what == "efficiency":
            ax.set_ylim(0.0, 1.1)
        ax.set_title(f"MPM3D-CXX {ylabel}\n{note}", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, loc="upper left" if what == "speedup" else "lower left")
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"{what}.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main()
