"""Checks that two runs of the same in-situ example wrote the same images: the same PNG files,
identical byte for byte, at least `--min-images` of them per scene, each showing surface (pixels
unlike the first pixel's background) and each unlike the step before (the scene changes in time).
With `--differ-by N` the files must instead differ, each in at least N pixels: the second run left
out something (`heat_insitu.py --without ghost`) that must show in every image.

    compare_runs.py DIR_A DIR_B --scene NAME [--scene NAME ...] [--min-images N] [--differ-by N]
"""

import argparse
import pathlib
import sys

import numpy as np

import support


def images(directory, scene):
    return {p.name: p for p in sorted((pathlib.Path(directory) / scene).glob("*.png"))}


def differing_pixels(first, second):
    return int(np.any(first != second, axis=2).sum())


def problems(a, b, min_images, differ_by):
    """What is wrong with the images `a` and `b` (name -> path) of one scene; prints the pixels
    that differ in each pair when they must differ."""
    names = sorted(a)
    if sorted(b) != names:
        yield f"different files: {sorted(set(a) ^ set(b))}"
        return
    if len(names) < min_images:
        yield f"{len(names)} images, expected at least {min_images}"
    previous = None
    for name in names:
        pixels = support.read_png(a[name])
        differing = differing_pixels(pixels, support.read_png(b[name]))
        if differ_by:
            print(f"{name}: {differing} pixels differ")
            if differing < differ_by:
                yield f"{name}: {differing} pixels differ, expected at least {differ_by}"
        elif a[name].read_bytes() != b[name].read_bytes():
            yield f"{name}: the files differ ({differing} pixels)"
        surface = differing_pixels(pixels, pixels[0, 0])
        if surface < 100:
            yield f"{name}: only {surface} pixels of surface"
        if previous is not None and np.array_equal(pixels, previous):
            yield f"{name}: the same image as the step before"
        previous = pixels


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("first")
    parser.add_argument("second")
    parser.add_argument("--scene", required=True, action="append")
    parser.add_argument("--min-images", type=int, default=2)
    parser.add_argument("--differ-by", type=int, default=0,
                        help="each pair of images must differ in at least this many pixels")
    args = parser.parse_args()
    failed = False
    for scene in args.scene:
        a, b = images(args.first, scene), images(args.second, scene)
        found = list(problems(a, b, args.min_images, args.differ_by))
        for p in found:
            print(p)
        expected = (f"each differing in at least {args.differ_by} pixels" if args.differ_by
                    else "identical byte for byte")
        verdict = expected if not found else f"NOT {expected}, or not usable"
        print(f"{len(a)} images of scene {scene}: {verdict}")
        failed = failed or bool(found)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
