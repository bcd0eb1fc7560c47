#!/usr/bin/env python3
"""Size against quality with relume from Python.

Loads a reflectance field (by default the shared DiLiGenT "bear" crop), compresses it with
several residual budgets, relights the uncompressed field and every compressed one under an HDR
environment map, and plots what each stored byte buys: the paper's error (Eq. 16) and the error
of the relit image against the uncompressed one, per byte of file per pixel, plus the relit
images themselves.

    PYTHONPATH=build/python python3 python/examples/compression_trade.py --out out/trade

Writes trade.png (the plot and the images) and trade.json (every number in the plot) to --out.
The shared data folder is RELUME_DATA, else ../shared/data next to the repository.
"""
import argparse
import json
import os
import pathlib
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after choosing the backend)
import numpy as np  # noqa: E402

import relume  # noqa: E402


def shared_data():
    default = pathlib.Path(__file__).resolve().parents[2] / ".." / "shared" / "data"
    return pathlib.Path(os.environ.get("RELUME_DATA", default))


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("field", nargs="?", default=shared_data() / "olat" / "diligent-bear-crop8",
                        help="field folder or .lp file (default: the shared DiLiGenT bear)")
    parser.add_argument("--env", default=shared_data() / "envmaps" / "grace_cross.hdr",
                        help="environment map (default: the shared Grace Cathedral cross)")
    parser.add_argument("--rotate", type=float, default=180,
                        help="degrees about +y; DiLiGenT's lights face the camera, so 180 turns "
                             "the map's forward view onto them (default 180)")
    parser.add_argument("--clusters", type=int, default=32)
    parser.add_argument("--terms", type=int, default=4)
    parser.add_argument("--residuals", default="0,2,5,10",
                        help="residual entries per function, one compression each")
    parser.add_argument("--assign", default="opencl", choices=["opencl", "cpu"])
    parser.add_argument("--exposure", type=float, default=0.0,
                        help="stops applied to the images shown (default 0: auto)")
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out/trade"))
    return parser.parse_args()


def relit_error(image, reference, mask):
    """Relative RMS error of a relit image inside the mask: ||a - b|| / ||b||."""
    inside = mask.astype(bool)
    difference = (image - reference)[inside]
    return float(np.sqrt((difference.astype(np.float64) ** 2).sum() /
                         (reference[inside].astype(np.float64) ** 2).sum()))


def shown(image, exposure):
    """Exposed by 2**exposure, clipped and gamma-encoded for display."""
    return np.clip(image * 2.0 ** exposure, 0, 1) ** (1 / 2.2)


def main():
    args = arguments()
    args.out.mkdir(parents=True, exist_ok=True)
    field = relume.load(args.field)
    light = relume.light_vector(field.directions, str(args.env), rotate=args.rotate)
    reference = field.relight(light)
    exposure = args.exposure or float(-np.log2(np.percentile(reference[field.mask > 0], 99.5)))
    print(f"{args.field}: {field.width}x{field.height}, {field.channels} channels, "
          f"{field.lights} lights; {args.clusters} clusters x {args.terms} terms")

    points = []
    relit_images = []
    for residual in (int(text) for text in args.residuals.split(",")):
        start = time.perf_counter()
        compressed = relume.compress(field, clusters=args.clusters, terms=args.terms,
                                     residual=residual, assign=args.assign)
        seconds = time.perf_counter() - start
        relit = compressed.relight(light)
        point = {"residual": residual,
                 "bytes": compressed.file_size(),
                 "bytes_per_pixel": compressed.file_size() / (field.width * field.height),
                 "error_eq16_masked": relume.relative_error(field, compressed),
                 "relit_error": relit_error(relit, reference, field.mask),
                 "compress_seconds": seconds}
        points.append(point)
        relit_images.append(relit)
        print("residual {residual:3d}: {bytes_per_pixel:8.2f} bytes/pixel, Eq. 16 error "
              "{error_eq16_masked:.5f}, relit error {relit_error:.5f}, "
              "{compress_seconds:.1f} s".format(**point))
    uncompressed = field.values.nbytes / (field.width * field.height)

    figure = plt.figure(figsize=(13, 4.2))
    plot = figure.add_subplot(1, 4, 1)
    sizes = [p["bytes_per_pixel"] for p in points]
    plot.loglog(sizes, [p["error_eq16_masked"] for p in points], "o-", label="Eq. 16 (masked)")
    plot.loglog(sizes, [p["relit_error"] for p in points], "s-", label="relit image (rel. RMS)")
    for p in points:
        plot.annotate(f"n={p['residual']}", (p["bytes_per_pixel"], p["relit_error"]),
                      textcoords="offset points", xytext=(4, 4), fontsize=8)
    plot.set_xlabel(f"bytes per pixel (float32 field: {uncompressed:.0f})")
    plot.set_ylabel("error")
    plot.set_title("size against quality")
    plot.legend(fontsize=8)
    inside = field.mask[..., None] > 0  # what a compressed field stores
    panels = [("uncompressed (masked)", reference * inside), (f"n={points[0]['residual']}", relit_images[0]),
              (f"n={points[-1]['residual']}", relit_images[-1])]
    for index, (title, image) in enumerate(panels):
        axis = figure.add_subplot(1, 4, index + 2)
        axis.imshow(shown(image, exposure))
        axis.set_title(title)
        axis.axis("off")
    figure.tight_layout()
    figure.savefig(args.out / "trade.png", dpi=110)
    (args.out / "trade.json").write_text(json.dumps({
        "field": str(args.field), "env": str(args.env), "rotate": args.rotate,
        "clusters": args.clusters, "terms": args.terms, "assign": args.assign,
        "uncompressed_bytes_per_pixel": uncompressed, "points": points}, indent=2))
    print(f"wrote {args.out / 'trade.png'} and {args.out / 'trade.json'}")


if __name__ == "__main__":
    main()
