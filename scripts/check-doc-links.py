#!/usr/bin/env python3
"""Every relative link of every tracked Markdown file resolves to a file or folder of the tree:
`[text](path)` outside code blocks, anchors and web addresses left out. Prints the broken ones
as FILE:LINE: TARGET and exits 1 when there are any (ctest docs.LinksResolve)."""

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def markdown_files():
    listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "--cached", "--others",
                             "--exclude-standard", "*.md"], capture_output=True, text=True)
    if listed.returncode == 0 and listed.stdout.strip():
        return [ROOT / line for line in listed.stdout.splitlines()]
    return [p for p in ROOT.rglob("*.md") if "build" not in p.parts]


def broken_links(path: Path):
    in_code = False
    for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
            continue
        if in_code:
            continue
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            file_part = target.split("#", 1)[0]
            if file_part and not (path.parent / file_part).exists():
                yield number, target


def main() -> int:
    files = [f for f in markdown_files() if f.is_file()]
    bad = [f"{f.relative_to(ROOT)}:{n}: {t}" for f in files for n, t in broken_links(f)]
    for line in bad:
        print(line)
    print(f"check-doc-links: {len(files)} files, {len(bad)} broken links")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
