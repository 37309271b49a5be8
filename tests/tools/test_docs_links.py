#!/usr/bin/env python3
"""README.md and docs/: every relative link resolves, and the README stays a short manual.

Checks, for README.md and every docs/**/*.md:
- each relative link or image, [text](path) or [text](path#anchor), names a file or folder
  that exists (relative to the page), and an anchor names a heading of the target page
  (GitHub's rule: lower case, punctuation dropped, spaces to hyphens, -1, -2 for repeats);
- README.md is at most 300 lines;
- the README's quick start is the first ```sh block under "## Quick start" and holds exactly
  the two commands tools/ci/fresh_machine_check.sh runs.
usage: test_docs_links.py SOURCE_DIR
"""
import pathlib
import re
import sys

MAX_README_LINES = 300
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def strip_code(text):
    """The page without fenced blocks and inline code, where brackets are not links."""
    lines, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            lines.append("")
            continue
        lines.append("" if fenced else re.sub(r"`[^`]*`", "", line))
    return lines


def slug(heading):
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)  # keeps letters, digits, _, -, spaces
    return text.replace(" ", "-")


def anchors(path):
    found, seen, fenced = set(), {}, False
    for line in path.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        base = slug(m.group(1))
        n = seen.get(base, 0)
        seen[base] = n + 1
        found.add(base if n == 0 else f"{base}-{n}")
    return found


def check_page(page, root, errors):
    for number, line in enumerate(strip_code(page.read_text(encoding="utf-8")), 1):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            where = f"{page.relative_to(root)}:{number}"
            path_part, _, anchor = target.partition("#")
            dest = (page.parent / path_part).resolve() if path_part else page
            if not dest.exists():
                errors.append(f"{where}: link to '{target}': no such file")
                continue
            try:
                dest.relative_to(root)
            except ValueError:
                errors.append(f"{where}: link to '{target}' leaves the repository")
                continue
            if anchor:
                if dest.suffix != ".md":
                    errors.append(f"{where}: anchor '#{anchor}' on a file that is not Markdown")
                elif anchor not in anchors(dest):
                    errors.append(f"{where}: link to '{target}': no heading with anchor '#{anchor}' in "
                                  f"{dest.relative_to(root)}")


def quick_start_commands(readme_text):
    commands, section, block = [], False, False
    for line in readme_text.splitlines():
        if line.startswith("## Quick start"):
            section = True
            continue
        if section and line.startswith("## "):
            break
        if section and line.startswith("```sh"):
            block = True
            continue
        if block and line.startswith("```"):
            break
        if block and line.split() and not line.split()[0].startswith("#"):
            commands.append(re.sub(r"[ \t]+#.*$", "", line))
    return commands


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    readme = root / "README.md"
    pages = [readme] + sorted((root / "docs").rglob("*.md"))
    errors = []
    for page in pages:
        check_page(page, root, errors)
    text = readme.read_text(encoding="utf-8")
    lines = len(text.splitlines())
    if lines > MAX_README_LINES:
        errors.append(f"README.md: {lines} lines, at most {MAX_README_LINES} (put the rest in docs/)")
    commands = quick_start_commands(text)
    if commands != ["bash tools/quickstart.sh", "bash tools/test.sh"]:
        errors.append(f"README.md: the quick start's commands are {commands}, "
                      "expected ['bash tools/quickstart.sh', 'bash tools/test.sh'] (tools/ci/fresh_machine_check.sh)")
    for error in errors:
        print("FAIL", error)
    print(f"{len(pages)} pages checked, README.md {lines} lines, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
