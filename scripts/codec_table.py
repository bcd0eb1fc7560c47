#!/usr/bin/python3
"""The table and plot of scripts/bench_codecs.sh: every point of POINTS (JSON lines: codec,
setting, bytes_per_pixel, psnr_whole_frame, psnr_mask, optionally relit_error (one per map),
load_seconds and relight_seconds; relume's with seconds, its default's setting starting with
"default"), and for each relume point the codecs' PSNR interpolated at its bytes per pixel
(linear in log bytes between the two codec points around it; blank outside a codec's range) with
relume's lead in dB. The plot: PSNR over the whole frame and inside the mask, and the relit error
under the first map, against bytes per pixel.

Usage: scripts/codec_table.py POINTS TABLE.md PLOT.png
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def interpolate(curve, rate, key):
    curve = sorted(curve, key=lambda p: p["bytes_per_pixel"])
    for a, b in zip(curve, curve[1:]):
        if a["bytes_per_pixel"] <= rate <= b["bytes_per_pixel"]:
            t = math.log(rate / a["bytes_per_pixel"]) / math.log(
                b["bytes_per_pixel"] / a["bytes_per_pixel"])
            return a[key] + t * (b[key] - a[key])
    return None


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    points = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    codecs = sorted({p["codec"] for p in points if p["codec"] != "relume"})
    lines = ["| codec | setting | seconds | B/px | whole-frame dB | mask dB | "
             "relit error, Grace / St. Peter's | load s | relit frame ms | " +
             " | ".join(f"{c} at equal bytes (whole / mask), relume's lead" for c in codecs) + " |",
             "|---" * (9 + len(codecs)) + "|"]
    for p in points:
        seconds = f"{p['seconds']:.0f}" if "seconds" in p else ""
        relit = " / ".join(f"{e:.2e}" for e in p.get("relit_error", []))
        load = f"{p['load_seconds']:.2f}" if "load_seconds" in p else ""
        frame = f"{1000 * p['relight_seconds']:.1f}" if "relight_seconds" in p else ""
        row = [p["codec"], p["setting"], seconds, f"{p['bytes_per_pixel']:.4f}",
               f"{p['psnr_whole_frame']:.2f}", f"{p['psnr_mask']:.2f}", relit, load, frame]
        for codec in codecs:
            curve = [q for q in points if q["codec"] == codec]
            whole = interpolate(curve, p["bytes_per_pixel"], "psnr_whole_frame")
            mask = interpolate(curve, p["bytes_per_pixel"], "psnr_mask")
            if p["codec"] != "relume" or whole is None:
                row.append("")
            else:
                row.append(f"{whole:.2f} / {mask:.2f}, {p['psnr_whole_frame'] - whole:+.2f} / "
                           f"{p['psnr_mask'] - mask:+.2f}")
        lines.append("| " + " | ".join(row) + " |")
    open(sys.argv[2], "w").write("\n".join(lines) + "\n")
    relit = all("relit_error" in p for p in points)
    panels = [("psnr_whole_frame", "whole frame", "8-bit PSNR (dB)"),
              ("psnr_mask", "inside the mask", "8-bit PSNR (dB)")]
    if relit:
        for p in points:
            p["relit_error_first"] = p["relit_error"][0]
        panels.append(("relit_error_first", "relit under the first map",
                       "relative squared error"))
    figure, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 4.2))
    for axis, (key, title, label) in zip(axes, panels):
        # relume's rate targets are its curve; its default (no target) is a point of its own.
        default = [q for q in points if q["codec"] == "relume" and q["setting"].startswith("default")]
        for codec in ["relume"] + codecs:
            curve = sorted((q for q in points if q["codec"] == codec and q not in default),
                           key=lambda q: q["bytes_per_pixel"])
            axis.plot([q["bytes_per_pixel"] for q in curve], [q[key] for q in curve], "o-",
                      label=codec + (" rate targets" if codec == "relume" else ""))
        axis.plot([q["bytes_per_pixel"] for q in default], [q[key] for q in default], "k*",
                  markersize=10, label="relume default")
        axis.set_xscale("log")
        if key == "relit_error_first":
            axis.set_yscale("log")
        axis.set_xlabel("bytes per pixel")
        axis.set_ylabel(label)
        axis.set_title(title)
        axis.grid(True, which="both", alpha=0.3)
        axis.legend()
    figure.tight_layout()
    figure.savefig(sys.argv[3], dpi=110)


if __name__ == "__main__":
    main()
