#!/usr/bin/env python3
"""Fails when a relative link of README.md or docs/*.md leads nowhere.

A link is [text](target) or ![alt](target) outside code; web links (scheme://, mailto:) are
not checked. The target, without its #anchor, is resolved against the linking file's folder and
must exist; an #anchor into a markdown file (or into the same page) must name one of its
headings as GitHub spells them (lower case, punctuation dropped, spaces as hyphens).

Usage: check_links.py REPOSITORY_ROOT
"""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def links(text):
    in_fence = False
    for number, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)  # inline code shows link syntax, it is not a link
        for match in LINK.finditer(line):
            yield number, match.group(1)


def anchors(path):
    """The anchors GitHub gives the headings of a markdown file."""
    found, seen, in_fence = set(), {}, False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
        if in_fence or not re.match(r"#{1,6} ", line):
            continue
        slug = re.sub(r"[^\w\- ]", "", line.lstrip("#").strip().lower()).replace(" ", "-")
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        found.add(slug if count == 0 else f"{slug}-{count}")
    return found


def main(root):
    root = pathlib.Path(root)
    files = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    broken = []
    for path in files:
        for number, target in links(path.read_text(encoding="utf-8")):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                continue
            file_part, _, anchor = target.partition("#")
            linked = path.parent / file_part if file_part else path
            if not linked.exists():
                broken.append(f"{path.relative_to(root)}:{number}: {target} does not exist")
            elif anchor and linked.suffix == ".md" and anchor not in anchors(linked):
                broken.append(f"{path.relative_to(root)}:{number}: {target}: no heading "
                              f"#{anchor} in {linked.relative_to(root)}")
    for line in broken:
        print(line)
    print(f"{len(files)} files checked, {len(broken)} broken links")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
