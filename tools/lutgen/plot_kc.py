#!/usr/bin/env python3
"""Plots of the Kulla-Conty tables from the CSV lutgen-kc writes.

usage: plot_kc.py kc_plot.csv OUTDIR
Writes OUTDIR/kc_E.png (single-scattering albedo E(mu) for several roughnesses) and
OUTDIR/kc_furnace.png (white furnace: albedo before and after compensation).
"""
import csv
import sys
from collections import defaultdict

try:  # --help works without it; main() says it is missing
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
except ImportError:
    plt = None


def finish(fig, axes, ylabel, path):
    """The axes both figures share (mu from 0 to 1, a grid), the y label and legend, saved."""
    for ax in axes:
        ax.set_xlabel("mu = cos theta_o")
        ax.set_xlim(0, 1)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(ylabel)
    axes[0].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(sys.argv) != 3 or sys.argv[1].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    if plt is None:
        sys.exit("plot_kc.py: needs matplotlib (python3-matplotlib)")
    data = defaultdict(lambda: defaultdict(list))
    with open(sys.argv[1], newline="") as f:
        for row in csv.DictReader(f):
            d = data[row["variant"]][float(row["r"])]
            d.append((float(row["mu"]), float(row["E_ss"]), float(row["E_total"])))
    shown = [v for v in ("ggx_hc", "beckmann_hc", "ggx_sep", "beckmann_sep") if v in data]
    cmap = plt.get_cmap("viridis")

    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 3.8), sharey=True)
    for ax, v in zip(axes, shown):
        rs = sorted(data[v])
        for i, r in enumerate(rs):
            pts = sorted(data[v][r])
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=cmap(i / max(1, len(rs) - 1)),
                    label=f"r={r:g} (alpha={r * r:.3g})")
        ax.set_title(f"E(mu), {v}")
        ax.set_ylim(0, 1.05)
    finish(fig, axes, "single-scattering albedo, F = 1", f"{sys.argv[2]}/kc_E.png")

    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 3.8), sharey=True)
    for ax, v in zip(axes, shown):
        rs = sorted(data[v])
        for i, r in enumerate(rs):
            pts = sorted(data[v][r])
            col = cmap(i / max(1, len(rs) - 1))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=col, ls="--", lw=1)
            ax.plot([p[0] for p in pts], [p[2] for p in pts], color=col, lw=1.5, label=f"r={r:g}")
        ax.set_title(f"white furnace, {v}")
        ax.set_ylim(0.3, 1.05)
    finish(fig, axes, "albedo: dashed f_ss, solid f_ss + f_ms", f"{sys.argv[2]}/kc_furnace.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
