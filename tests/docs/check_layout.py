#!/usr/bin/env python3
"""Compares the layout tree of docs/architecture.md with the repository's folders.

The tree is the first ```text block after the heading "## 1. Layout". A line whose first word
ends in "/" names a folder: at the start of the line a top-level folder, indented a subfolder of
the top-level folder above it. The repository's folders are those holding files git tracks.
Fails when a top-level folder, or a subfolder of render/ or adaptor/, is on one side only.

Usage: check_layout.py REPOSITORY_ROOT
"""
import pathlib
import subprocess
import sys

CHECKED_SUBFOLDERS = ("render", "adaptor")


def documented(architecture):
    lines = architecture.read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("## 1. Layout"))
    fence = next(i for i in range(start, len(lines)) if lines[i].startswith("```text"))
    top, sub, parent = set(), {name: set() for name in CHECKED_SUBFOLDERS}, None
    for line in lines[fence + 1:]:
        if line.startswith("```"):
            break
        word = line.split()[0] if line.split() else ""
        if not word.endswith("/"):
            continue
        name = word.strip("/").split("/")[0]
        if not line.startswith(" "):
            parent = name
            top.add(name)
        elif parent in sub:
            sub[parent].add(name)
    return top, sub


def tracked(root):
    try:
        files = subprocess.run(["git", "-C", str(root), "ls-files"], check=True,
                               capture_output=True, text=True).stdout.splitlines()
    except (OSError, subprocess.CalledProcessError):
        # Not a git checkout (an unpacked archive): every file but build and output folders.
        files = [str(p.relative_to(root)) for p in root.rglob("*") if p.is_file()
                 and not p.relative_to(root).parts[0].startswith(("build", "out"))]
    top, sub = set(), {name: set() for name in CHECKED_SUBFOLDERS}
    for f in files:
        parts = f.split("/")
        if len(parts) < 2 or parts[0].startswith("."):
            continue
        if not (root / f).exists():  # deleted in the working tree, not yet committed
            continue
        top.add(parts[0])
        if parts[0] in sub and len(parts) > 2:
            sub[parts[0]].add(parts[1])
    return top, sub


def compare(what, in_doc, in_tree):
    problems = []
    for name in sorted(in_tree - in_doc):
        problems.append(f"{what}{name}/ is in the repository but not in the layout tree")
    for name in sorted(in_doc - in_tree):
        problems.append(f"{what}{name}/ is in the layout tree but not in the repository")
    return problems


def main(root):
    root = pathlib.Path(root)
    doc_top, doc_sub = documented(root / "docs" / "architecture.md")
    tree_top, tree_sub = tracked(root)
    problems = compare("", doc_top, tree_top)
    for name in CHECKED_SUBFOLDERS:
        problems += compare(name + "/", doc_sub[name], tree_sub[name])
    for p in problems:
        print(p)
    print("layout tree and folders agree" if not problems else
          f"{len(problems)} differences between docs/architecture.md's layout and the folders")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
