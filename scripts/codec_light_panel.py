#!/usr/bin/python3
"""Light images side by side, brightened so the dark background and its shadows can be judged:
each image times GAIN on the 8-bit scale, then a 2.2 gamma, with its label above. An image is an
8-bit PNG of codes (a light image, or one a codec decoded) or a linear EXR in the field's units
(1 = code 255, as `relume relight C --lights ONE_LIGHT.txt -o L.exr` writes a container's light).
Used by scripts/bench_codecs.sh; needs numpy, Pillow and OpenImageIO's Python module.

Example:
  scripts/codec_light_panel.py panel.png --gain 8 original=ball8/041.png relume=l41.exr \\
      av1=av1_crf30_light41.png
"""
import argparse
import sys

import numpy as np
import OpenImageIO as oiio
from PIL import Image, ImageDraw

LABEL_HEIGHT = 24


def read_codes(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"codec_light_panel.py: cannot read {path}: {oiio.geterror()}")
    # OpenImageIO gives an 8-bit PNG's codes over 255 and an EXR's values as they are: either way
    # the 8-bit scale is 255 times what it reads.
    pixels = image.read_image(oiio.FLOAT)[..., :3]
    image.close()
    return pixels * 255.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", help="the panel, a PNG")
    parser.add_argument("images", nargs="+", metavar="LABEL=IMAGE")
    parser.add_argument("--gain", type=float, default=8.0, help="brightening (default 8)")
    args = parser.parse_args()
    tiles = []
    for item in args.images:
        label, _, path = item.partition("=")
        if not path:
            sys.exit(f"codec_light_panel.py: '{item}' is not LABEL=IMAGE")
        codes = read_codes(path)
        shown = np.clip(codes * args.gain / 255.0, 0.0, 1.0) ** (1 / 2.2)
        tile = Image.new("RGB", (codes.shape[1], codes.shape[0] + LABEL_HEIGHT), "white")
        tile.paste(Image.fromarray((shown * 255 + 0.5).astype(np.uint8)), (0, LABEL_HEIGHT))
        ImageDraw.Draw(tile).text((6, 6), label, fill="black")
        tiles.append(tile)
    if len({tile.height for tile in tiles}) != 1:
        sys.exit("codec_light_panel.py: the images differ in size")
    panel = Image.new("RGB", (sum(tile.width for tile in tiles), tiles[0].height), "white")
    x = 0
    for tile in tiles:
        panel.paste(tile, (x, 0))
        x += tile.width
    panel.save(args.output)


if __name__ == "__main__":
    main()
