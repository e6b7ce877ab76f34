#!/usr/bin/env python3
"""Fails when a relative link of README.md or docs/*.md leads nowhere.

A link is [text](target) or ![alt](target) outside code; web links (scheme://, mailto:) and
links to an anchor of the same page (#...) are not checked. The target, without its #anchor,
is resolved against the linking file's folder and must exist.

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


def main(root):
    root = pathlib.Path(root)
    files = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    broken = []
    for path in files:
        for number, target in links(path.read_text(encoding="utf-8")):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            file_part = target.split("#", 1)[0]
            if not (path.parent / file_part).exists():
                broken.append(f"{path.relative_to(root)}:{number}: {target} does not exist")
    for line in broken:
        print(line)
    print(f"{len(files)} files checked, {len(broken)} broken links")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
