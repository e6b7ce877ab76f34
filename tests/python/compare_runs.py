"""Checks that two runs of the same in-situ example wrote the same images: the same PNG files,
identical byte for byte, at least `--min-images` of them, each showing surface (pixels unlike the
first pixel's background) and each unlike the step before (the scene changes in time).

    compare_runs.py DIR_A DIR_B --scene NAME [--min-images N]
"""

import argparse
import pathlib
import sys

import numpy as np

import support


def images(directory, scene):
    return {p.name: p for p in sorted((pathlib.Path(directory) / scene).glob("*.png"))}


def problems(a, b, min_images):
    names = sorted(a)
    if sorted(b) != names:
        yield f"different files: {sorted(set(a) ^ set(b))}"
        return
    if len(names) < min_images:
        yield f"{len(names)} images, expected at least {min_images}"
    previous = None
    for name in names:
        pixels = support.read_png(a[name])
        if a[name].read_bytes() != b[name].read_bytes():
            differing = int(np.any(pixels != support.read_png(b[name]), axis=2).sum())
            yield f"{name}: the files differ ({differing} pixels)"
        surface = int(np.any(pixels != pixels[0, 0], axis=2).sum())
        if surface < 100:
            yield f"{name}: only {surface} pixels of surface"
        if previous is not None and np.array_equal(pixels, previous):
            yield f"{name}: the same image as the step before"
        previous = pixels


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("first")
    parser.add_argument("second")
    parser.add_argument("--scene", required=True)
    parser.add_argument("--min-images", type=int, default=2)
    args = parser.parse_args()
    a, b = images(args.first, args.scene), images(args.second, args.scene)
    found = list(problems(a, b, args.min_images))
    for p in found:
        print(p)
    print(f"{len(a)} images of scene {args.scene}: "
          f"{'identical byte for byte' if not found else 'NOT identical or not usable'}")
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
