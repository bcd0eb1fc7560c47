#!/usr/bin/env python3
"""Draws the plots of `relume eval` from the CSV, NPY and PNG files it wrote into DIR.

Usage: python3 plot_eval.py DIR

relume eval embeds this script, writes a copy to DIR/plot_eval.py and runs it, so the plots can be
redrawn (or restyled) from the same files without running the evaluation again. Needs matplotlib
and NumPy (Debian: python3-matplotlib python3-numpy). Every plot is written atomically (a
temporary file renamed over the target).
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# One colour per method, the same in every plot.
COLOURS = {"l1": "tab:blue", "l1-refit": "tab:green", "cpca": "tab:red", "cpca-mean": "tab:orange"}
LABELS = {
    "l1": "relume L1",
    "l1-refit": "relume L1 + trimmed LS refit",
    "cpca": "CPCA",
    "cpca-mean": "CPCA (mean + t-1)",
}
SUBSETS = [("error_all", "all masked functions"), ("error_diffuse", "mostly diffuse"),
           ("error_specular", "mostly specular / shadowed")]


def read_csv(directory, name):
    with open(os.path.join(directory, name), newline="") as handle:
        return list(csv.DictReader(handle))


def number(text):
    return float(text) if text not in ("", None) else math.nan


def save(figure, directory, name, title=None):
    """Titles, lays out and writes `figure` as DIR/name, atomically."""
    if title:
        figure.suptitle(title)
    figure.tight_layout()
    path = os.path.join(directory, name)
    temporary = os.path.join(directory, "." + name + ".tmp.png")
    figure.savefig(temporary, dpi=110)
    plt.close(figure)
    os.replace(temporary, path)


def configs_of(rows):
    seen = []
    for row in rows:
        key = (int(row["clusters"]), int(row["terms"]))
        if key not in seen:
            seen.append(key)
    return seen


def series(rows, method, clusters, terms, *columns):
    """Sorted tuples of `columns` (as numbers) of the rows of one method and configuration."""
    return sorted(tuple(number(r[c]) for c in columns) for r in rows
                  if r["method"] == method and int(r["clusters"]) == clusters
                  and int(r["terms"]) == terms)


def line_style(index):
    return ["-", "--", ":", "-."][index % 4]


def plot_error_vs_entries(directory):
    """Paper Fig. 4 a-c: Eq. 16 error against residual entries, all and the two subsets."""
    rows = read_csv(directory, "error_vs_entries.csv")
    configs = configs_of(rows)
    figure, axes = plt.subplots(1, 3, figsize=(16, 5), sharey=True)
    for axis, (column, title) in zip(axes, SUBSETS):
        for index, (clusters, terms) in enumerate(configs):
            for method in COLOURS:
                points = [p for p in series(rows, method, clusters, terms, "entries", column)
                          if p[1] > 0]
                if not points:
                    continue
                marker = "o" if method == "l1-refit" else "."
                axis.plot([p[0] for p in points], [p[1] for p in points], line_style(index),
                          marker=marker, color=COLOURS[method],
                          label=f"{LABELS[method]}, {clusters} clusters, {terms} terms")
        axis.set_yscale("log")
        axis.set_xlabel("residual entries per function")
        axis.set_title(title)
        axis.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("Eq. 16 error (relative squared, mean over functions)")
    axes[-1].legend(fontsize=7, loc="upper right")
    save(figure, directory, "error_vs_entries.png",
         "Error against residual entries (paper Fig. 4 a-c)")


def plot_sparseness(directory):
    """Paper Fig. 4d: fraction of the full residual below a threshold."""
    rows = read_csv(directory, "sparseness.csv")
    configs = configs_of(rows)
    figure, axis = plt.subplots(figsize=(8, 5))
    for index, (clusters, terms) in enumerate(configs):
        for method in COLOURS:
            points = series(rows, method, clusters, terms, "threshold", "fraction_at_or_below")
            if not points:
                continue
            axis.plot([p[0] for p in points], [p[1] for p in points], line_style(index),
                      color=COLOURS[method], label=f"{LABELS[method]}, {clusters}x{terms}")
    axis.set_xscale("log")
    axis.set_xlabel("threshold (fraction of the function's L2 norm)")
    axis.set_ylabel("fraction of residual entries with |e| <= threshold")
    axis.set_title("Sparseness of the full residual (paper Fig. 4d)")
    axis.grid(True, which="both", alpha=0.3)
    axis.legend(fontsize=7)
    save(figure, directory, "sparseness.png")


def plot_ratio(directory):
    """Paper Fig. 5: CPCA's error over relume's, against residual entries."""
    rows = read_csv(directory, "error_ratio.csv")
    configs = configs_of(rows)
    figure, axes = plt.subplots(1, 3, figsize=(16, 5), sharey=True)
    for axis, (column, title) in zip(axes, SUBSETS):
        ratio_column = column.replace("error_", "ratio_")
        for index, (clusters, terms) in enumerate(configs):
            for method in ("l1", "l1-refit"):
                points = [p for p in series(rows, method, clusters, terms, "entries", ratio_column)
                          if not math.isnan(p[1])]
                if not points:
                    continue
                axis.plot([p[0] for p in points], [p[1] for p in points], line_style(index),
                          marker="o" if method == "l1-refit" else ".", color=COLOURS[method],
                          label=f"CPCA / {LABELS[method]}, {clusters}x{terms}")
        axis.axhline(1.0, color="black", linewidth=0.8)
        axis.set_yscale("log")
        axis.set_xlabel("residual entries per function")
        axis.set_title(title)
        axis.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("CPCA error / relume error (> 1: relume better)")
    axes[-1].legend(fontsize=7)
    save(figure, directory, "error_ratio.png", "Ratio of the two methods' errors (paper Fig. 5)")


def plot_error_difference(directory, summary):
    """Paper Fig. 6: per-pixel error of CPCA minus relume's, false colour."""
    maps = [(name, title) for name, title in
            (("error_difference.npy", "CPCA - relume L1"),
             ("error_difference_refit.npy", "CPCA - relume L1 + refit"))
            if os.path.exists(os.path.join(directory, name))]
    figure, axes = plt.subplots(1, len(maps), figsize=(7 * len(maps), 6), squeeze=False)
    entries = summary["images"]["entries"]
    for axis, (name, title) in zip(axes[0], maps):
        values = np.load(os.path.join(directory, name))
        finite = values[np.isfinite(values)]
        limit = float(np.percentile(np.abs(finite), 99)) if finite.size else 1.0
        limit = limit if limit > 0 else 1.0
        image = axis.imshow(values, cmap="RdBu", vmin=-limit, vmax=limit)
        axis.set_title(f"{title}, {entries} entries (blue: relume better)")
        axis.set_xticks([])
        axis.set_yticks([])
        figure.colorbar(image, ax=axis, fraction=0.046, label="Eq. 16 error difference per pixel")
    save(figure, directory, "error_difference.png", "Per-pixel error difference (paper Fig. 6)")


def plot_relighting(directory):
    """Paper Table 1: frames/s and relit error per residual cap."""
    rows = read_csv(directory, "relighting.csv")
    figure, (speed, error) = plt.subplots(1, 2, figsize=(13, 5))
    for method in COLOURS:
        points = sorted((int(r["cap"]), number(r["frames_per_second"]), number(r["relit_error"]))
                        for r in rows if r["method"] == method)
        if not points:
            continue
        caps = [p[0] for p in points]
        speed.plot(caps, [p[1] for p in points], "-o", color=COLOURS[method],
                   label=LABELS[method])
        error.plot(caps, [p[2] for p in points], "-o", color=COLOURS[method],
                   label=LABELS[method])
    device = rows[0]["device"] if rows else ""
    speed.set_xlabel("residual cap (entries per function)")
    speed.set_ylabel("frames / s (one relight call, median)")
    speed.set_title(f"OpenCL relighter on {device}", fontsize=9)
    error.set_xlabel("residual cap (entries per function)")
    error.set_ylabel("relit image relative squared error")
    error.set_yscale("log")
    error.set_title("relit error against the uncompressed field")
    for axis in (speed, error):
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=8)
    save(figure, directory, "relighting.png",
         "Relighting speed and error per residual cap (paper Table 1)")


def plot_rate_distortion(directory):
    """Eq. 16 and 8-bit PSNR against bytes per pixel, as the containers store them."""
    rows = read_csv(directory, "rate_distortion.csv")
    configs = configs_of(rows)
    figure, (eq16, psnr) = plt.subplots(1, 2, figsize=(14, 5))
    for index, (clusters, terms) in enumerate(configs):
        for method in COLOURS:
            points = series(rows, method, clusters, terms, "bytes_per_pixel", "error_masked",
                            "psnr_mask")
            if not points:
                continue
            marker = "o" if method == "l1-refit" else "."
            label = f"{LABELS[method]}, {clusters}x{terms}"
            eq16.plot([p[0] for p in points], [p[1] for p in points], line_style(index),
                      marker=marker, color=COLOURS[method], label=label)
            psnr.plot([p[0] for p in points], [p[2] for p in points], line_style(index),
                      marker=marker, color=COLOURS[method], label=label)
    eq16.set_yscale("log")
    eq16.set_ylabel("Eq. 16 error (masked, as stored)")
    psnr.set_ylabel("8-bit PSNR inside the mask (dB)")
    for axis in (eq16, psnr):
        axis.set_xlabel("bytes per pixel (container file / pixels)")
        axis.grid(True, which="both", alpha=0.3)
    psnr.legend(fontsize=7)
    save(figure, directory, "rate_distortion.png",
         "Rate against distortion (each point one container)")


def plot_compression_time(directory):
    """Seconds to make each model, per (clusters, terms) and method."""
    rows = read_csv(directory, "compression_time.csv")
    configs = configs_of(rows)
    methods = [m for m in COLOURS if any(r["method"] == m for r in rows)]
    figure, axis = plt.subplots(figsize=(max(8, 2 * len(configs)), 5))
    width = 0.8 / max(1, len(methods))
    for index, method in enumerate(methods):
        heights = []
        for clusters, terms in configs:
            times = series(rows, method, clusters, terms, "seconds")
            heights.append(max(times)[0] if times else 0.0)  # l1-refit: its slowest budget
        positions = [c + (index - (len(methods) - 1) / 2) * width for c in range(len(configs))]
        axis.bar(positions, heights, width, color=COLOURS[method], label=LABELS[method])
    axis.set_xticks(range(len(configs)))
    axis.set_xticklabels([f"{c} clusters\n{t} terms" for c, t in configs])
    axis.set_ylabel("seconds (clustering; l1-refit includes its L1 run)")
    axis.set_title("Compression time against settings")
    axis.grid(True, axis="y", alpha=0.3)
    axis.legend(fontsize=8)
    save(figure, directory, "compression_time.png")


def plot_relit_images(directory, summary):
    """Reference, each method, and each method's 10x difference, side by side."""
    images = summary["images"]
    names = [("reference", images["reference"])] + [(m, f) for m, f in images["relit"].items()]
    differences = images["difference10"]
    figure, axes = plt.subplots(2, len(names), figsize=(4 * len(names), 8), squeeze=False)
    for column, (name, file) in enumerate(names):
        axes[0][column].imshow(plt.imread(os.path.join(directory, file)))
        axes[0][column].set_title(LABELS.get(name, name))
        if name in differences:
            axes[1][column].imshow(plt.imread(os.path.join(directory, differences[name])))
            axes[1][column].set_title(f"10x |{LABELS.get(name, name)} - reference|")
        else:
            axes[1][column].axis("off")
        for row in (0, 1):
            axes[row][column].set_xticks([])
            axes[row][column].set_yticks([])
    save(figure, directory, "relit_side_by_side.png",
         f"Relit under {images['environment']}, {images['entries']} residual entries")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_eval.py DIR (a folder written by relume eval)")
    directory = sys.argv[1]
    with open(os.path.join(directory, "eval.json")) as handle:
        summary = json.load(handle)
    plot_error_vs_entries(directory)
    plot_sparseness(directory)
    plot_ratio(directory)
    plot_error_difference(directory, summary)
    plot_relighting(directory)
    plot_rate_distortion(directory)
    plot_compression_time(directory)
    plot_relit_images(directory, summary)


if __name__ == "__main__":
    main()
