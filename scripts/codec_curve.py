#!/usr/bin/python3
"""The rate-distortion curve of a general video codec over a folder of 8-bit light images, the way
a user would compress them without relume (issue 32): the images in light order as one video
(consecutive lights look alike, which inter prediction exploits), full-range BT.709 4:4:4, then
decoded back to RGB. For each quality setting prints one JSON line: codec, setting, bytes,
bytes_per_pixel (file bytes / (width x height)), and PSNR on the 8-bit scale per light image then
averaged (model/field_psnr.hpp's definition), over the whole frame and inside a mask. With
--light-vectors, also each vector's relit-image error (scripts/relit_error.py), the seconds to
load (decode every frame into the float32 matrices a relighter multiplies) and the seconds of
one relit frame from them (one BLAS matrix-vector product per channel, median of 5): a video
relights only after decoding every frame.

Codecs (FFmpeg 5.1, Debian 12): av1 (libaom, yuv444p, cpu-used 6, crf), x265 (yuv444p10le,
preset slow, crf), svtav1 (libsvtav1, yuv420p10le: SVT-AV1 has no 4:4:4, preset 6, crf).
Needs numpy, OpenImageIO's Python module and ffmpeg; none of relume's code.

Example:
  scripts/codec_curve.py ball8 ../shared/data/olat/diligent-ball-16bit/mask.png av1 50,40,30
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import OpenImageIO as oiio

import relit_error

CODECS = {
    "av1": ["-pix_fmt", "yuv444p", "-c:v", "libaom-av1", "-cpu-used", "6", "-b:v", "0",
            "-g", "300"],
    "x265": ["-pix_fmt", "yuv444p10le", "-c:v", "libx265", "-preset", "slow",
             "-x265-params", "keyint=300:log-level=error"],
    "svtav1": ["-pix_fmt", "yuv420p10le", "-c:v", "libsvtav1", "-preset", "6", "-g", "300"],
}


def psnr(decoded, reference, where):
    difference = decoded.astype(np.float64) - reference.astype(np.float64)
    mse = (difference ** 2)[:, where].reshape(len(reference), -1).mean(axis=1)
    return float(20 * np.log10(255.0) - 10 * np.log10(max(mse.mean(), 1e-12)))


def relight_seconds(planes, vector, height, width):
    times = []
    for _ in range(5):
        start = time.perf_counter()
        relit_error.relight(planes, vector, height, width)
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("lights", help="folder of numbered 8-bit PNG light images")
    parser.add_argument("mask", help="PNG mask (non-zero inside) for the masked PSNR")
    parser.add_argument("codec", choices=sorted(CODECS))
    parser.add_argument("crf", help="quality settings (crf), comma-separated")
    parser.add_argument("--keep-light", type=int, metavar="N",
                        help="also write light N (1-based) as decoded to --keep-dir, as "
                             "CODEC_crfQ_lightN.png, to look at")
    parser.add_argument("--keep-dir", default=".", help="folder for --keep-light (default .)")
    parser.add_argument("--light-vectors", metavar="A.txt,B.txt",
                        help="light vectors (`relume lights -o`) to relight with, comma-separated")
    args = parser.parse_args()
    images = relit_error.light_images(args.lights)
    vectors = [relit_error.light_vector(v) for v in args.light_vectors.split(",")] \
        if args.light_vectors else []
    references = [relit_error.relight(relit_error.planar(images), v, *images.shape[1:3])
                  for v in vectors]
    lights, height, width, _ = images.shape
    mask = relit_error.read_rgb(args.mask, oiio.UINT8)[..., 0] > 0
    frame = np.ones((height, width), bool)
    with tempfile.TemporaryDirectory() as scratch:
        stack = os.path.join(scratch, "stack.rgb")
        images.tofile(stack)
        for crf in args.crf.split(","):
            video = os.path.join(scratch, "out.mkv")
            subprocess.run(
                ["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                 f"{width}x{height}", "-r", "25", "-i", stack, "-vf",
                 "scale=out_color_matrix=bt709:out_range=full", "-color_range", "pc",
                 "-colorspace", "bt709", *CODECS[args.codec], "-crf", crf, video], check=True)
            decoded_path = os.path.join(scratch, "back.rgb")
            start = time.perf_counter()
            subprocess.run(
                ["ffmpeg", "-v", "error", "-y", "-i", video, "-vf",
                 "scale=in_color_matrix=bt709:in_range=full", "-f", "rawvideo", "-pix_fmt",
                 "rgb24", decoded_path], check=True)
            decoded = np.fromfile(decoded_path, np.uint8).reshape(images.shape)
            planes = relit_error.planar(decoded) if vectors else None
            load_seconds = time.perf_counter() - start
            if args.keep_light:
                kept = os.path.join(args.keep_dir,
                                    f"{args.codec}_crf{crf}_light{args.keep_light}.png")
                out = oiio.ImageBuf(oiio.ImageSpec(width, height, 3, oiio.UINT8))
                out.set_pixels(oiio.ROI(), decoded[args.keep_light - 1])
                if not out.write(kept):
                    sys.exit(f"codec_curve.py: cannot write {kept}: {out.geterror()}")
            size = os.path.getsize(video)
            point = {"codec": args.codec, "setting": f"crf {crf}", "bytes": size,
                     "bytes_per_pixel": size / (width * height),
                     "psnr_whole_frame": psnr(decoded, images, frame),
                     "psnr_mask": psnr(decoded, images, mask)}
            if vectors:
                point["relit_error"] = [
                    relit_error.relative_error(relit_error.relight(planes, v, height, width), r)
                    for v, r in zip(vectors, references)]
                point["load_seconds"] = load_seconds
                point["relight_seconds"] = relight_seconds(planes, vectors[0], height, width)
            print(json.dumps(point), flush=True)


if __name__ == "__main__":
    main()
