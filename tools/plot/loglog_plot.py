#!/usr/bin/python3
"""A log-log plot of error (or any y columns) against time (or any x column) from a CSV file.

Generic for convergence studies: each --y column is one series through the rows in file order,
each point marked with its --label cell (with --group, one series per y column and value of the
group column, e.g. one per mesh size); rows whose label is listed in --alone are drawn as
single markers outside the series (e.g. an exact method beside a family of step sizes). Rows with
a non-positive or non-numeric value cannot go on a log axis and are left out with a note.

  loglog_plot.py study.csv --x ms --y mean_error max_error --label step --alone exact \
      --out study.png --title "..."
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.pyplot as plt  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv", help="input CSV with a header row")
    p.add_argument("--x", required=True, help="column on the x axis")
    p.add_argument("--y", required=True, nargs="+", help="columns on the y axis, one series each")
    p.add_argument("--label", help="column whose cell marks each point")
    p.add_argument("--alone", nargs="*", default=[], help="labels drawn as single markers")
    p.add_argument("--group", help="column whose values split the rows into series")
    p.add_argument("--out", required=True, help="output PNG")
    p.add_argument("--title", default="")
    p.add_argument("--xlabel", help="x axis label (default: the column name)")
    p.add_argument("--ylabel", help="y axis label (default: the column names)")
    return p.parse_args(argv)


def positive(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if value > 0 else None


def read_rows(path, columns):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    missing = [c for c in columns if c not in rows[0]]
    if missing:
        sys.exit(f"{path}: no column {', '.join(missing)} (has {', '.join(rows[0].keys())})")
    return rows


def plot_series(axes, rows, args, y, name):
    series = [r for r in rows if not args.label or r[args.label] not in args.alone]
    points = [(positive(r[args.x]), positive(r[y]), r) for r in series]
    kept = [(x, v, r) for x, v, r in points if x is not None and v is not None]
    for x, v, r in points:
        if x is None or v is None:
            print(f"left out (not positive): {y} at {r}", file=sys.stderr)
    line = axes.plot([p[0] for p in kept], [p[1] for p in kept], "o-", label=name)[0]
    for r in rows:
        if args.label and r[args.label] in args.alone:
            x, v = positive(r[args.x]), positive(r[y])
            if x is not None and v is not None:
                axes.plot([x], [v], "*", markersize=12, color=line.get_color())
                axes.annotate(r[args.label], (x, v), textcoords="offset points", xytext=(6, -4))
    if args.label:
        for x, v, r in kept:
            axes.annotate(r[args.label], (x, v), textcoords="offset points", xytext=(5, 3),
                          fontsize=8)


def main(argv):
    args = parse_args(argv)
    rows = read_rows(args.csv, [args.x] + args.y + [c for c in (args.label, args.group) if c])
    groups = list(dict.fromkeys(r[args.group] for r in rows)) if args.group else [None]
    figure, axes = plt.subplots(figsize=(6.4, 4.8), dpi=100)
    for group in groups:
        part = [r for r in rows if group is None or r[args.group] == group]
        for y in args.y:
            plot_series(axes, part, args, y, y if group is None else f"{y}, {args.group} = {group}")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel(args.xlabel or args.x)
    axes.set_ylabel(args.ylabel or ", ".join(args.y))
    axes.set_title(args.title)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(args.out)


if __name__ == "__main__":
    main(sys.argv[1:])
