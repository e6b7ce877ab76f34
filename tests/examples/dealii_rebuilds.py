"""Checks from a run's tetray_log.csv (docs/outputs.md) that tetray rebuilt its BVH exactly where
the deal.II example changed its mesh: at the first rendered step, and at the first rendered step
after each adaptation (every N steps, rendered or not: the flags of the off-trigger calls carry
over), and only refit the field's ranges (field_refit) at every other rendered step. The
column `bvh_update` says which, in the first row of each step (the first scene of the field).

    dealii_rebuilds.py LOG --refine-every N --steps S
"""

import argparse
import csv
import sys


def decisions(log):
    """The BVH decision of each rendered step, in the order of the log."""
    steps = {}
    with open(log, newline="") as file:
        for row in csv.DictReader(file):
            step = int(row["step"])
            if step in steps and row["bvh_update"] != "none":
                sys.exit(f"{log}: step {step} logged twice (a second run into the same folder?)")
            if row["bvh_update"] != "none" or step not in steps:
                steps[step] = row["bvh_update"]
    return steps


def expected(rendered, refine_every, last_step):
    """rebuild or field_refit per rendered step, from the example's adaptation schedule."""
    adapted = set(range(refine_every, last_step + 1, refine_every)) if refine_every else set()
    result, previous = {}, 0
    for step in rendered:
        changed = previous == 0 or any(previous < s <= step for s in adapted)
        result[step] = "rebuild" if changed else "field_refit"
        previous = step
    return result


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("log")
    parser.add_argument("--refine-every", type=int, required=True)
    parser.add_argument("--steps", type=int, required=True)
    args = parser.parse_args()
    found = decisions(args.log)
    if len(found) < 2:
        sys.exit(f"{args.log}: {len(found)} rendered steps, expected more")
    wanted = expected(sorted(found), args.refine_every, args.steps)
    wrong = [s for s in sorted(found) if found[s] != wanted[s]]
    for step in sorted(found):
        mark = "" if step not in wrong else f", expected {wanted[step]}"
        print(f"step {step}: {found[step]}{mark}")
    rebuilds = sum(1 for s in found if found[s] == "rebuild")
    print(f"{len(found)} rendered steps, {rebuilds} rebuilds, {len(wrong)} wrong")
    sys.exit(1 if wrong else 0)


if __name__ == "__main__":
    main()
