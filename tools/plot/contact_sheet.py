#!/usr/bin/python3
"""Images side by side on one sheet, each over white with its label, for the README's figures.

Every input image (PNG, transparent background allowed) is composited over white, labelled in
its top-left corner with DejaVu Sans (fonts-dejavu-core), laid out row by row in --columns
columns of the first image's size, and the sheet is scaled by --scale:

  contact_sheet.py flat.png smooth.png --labels flat "shading: smooth" --columns 2 \
      --out sheet.png
"""
import argparse
import sys

from PIL import Image, ImageDraw, ImageFont

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("images", nargs="+", help="input images, in reading order")
    p.add_argument("--labels", nargs="+", required=True, help="one label per image")
    p.add_argument("--columns", type=int, default=3, help="images per row")
    p.add_argument("--scale", type=float, default=1.0, help="size of the sheet, relative")
    p.add_argument("--out", required=True, help="output PNG")
    args = p.parse_args(argv)
    if len(args.labels) != len(args.images):
        p.error(f"{len(args.images)} images but {len(args.labels)} labels")
    if args.columns < 1 or not 0 < args.scale <= 4:
        p.error("--columns must be at least 1 and --scale in (0, 4]")
    return args


def labelled(path, label, size, font):
    image = Image.open(path).convert("RGBA").resize(size)
    tile = Image.new("RGBA", size, (255, 255, 255, 255))
    tile.alpha_composite(image)
    ImageDraw.Draw(tile).text((size[0] // 40, size[1] // 50), label, fill=(0, 0, 0, 255), font=font)
    return tile


def main(argv):
    args = parse_args(argv)
    width, height = Image.open(args.images[0]).size
    font = ImageFont.truetype(FONT, max(10, height // 23))
    rows = (len(args.images) + args.columns - 1) // args.columns
    sheet = Image.new("RGBA", (args.columns * width, rows * height), (255, 255, 255, 255))
    for k, (path, label) in enumerate(zip(args.images, args.labels)):
        tile = labelled(path, label, (width, height), font)
        sheet.paste(tile, ((k % args.columns) * width, (k // args.columns) * height))
    out_size = (round(sheet.width * args.scale), round(sheet.height * args.scale))
    sheet.convert("RGB").resize(out_size, Image.LANCZOS).save(args.out, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
