#!/usr/bin/env python3
"""Checks the links of the project's documentation (docs/architecture.md, "Structure checks"):

  check_links.py SOURCE_DIR

Every relative link and image in the Markdown files of SOURCE_DIR (build folders and hidden ones
left out) must name a file or folder inside SOURCE_DIR, and an anchor (#section) must name a
heading (or an <a id/name>) of the Markdown file it points into. Links with a scheme (https:,
mailto:) are not fetched; links inside code blocks and code spans are not links.

Prints every problem and exits with 1 if there is one.
"""
import os
import re
import sys
import urllib.parse

# The same walk as the other structure checks: build folders and hidden ones left out.
from check_structure import report, source_files

FENCE = re.compile(r"^\s{0,3}(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(?:.+?)\1", re.S)
INLINE_LINK = re.compile(r"\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ANCHOR = re.compile(r"<a\s+(?:name|id)=\"([^\"]+)\"")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")


def prose_lines(text, blank_code_spans=True):
    """(line number, line) of the lines outside fenced code blocks, code spans blanked unless
    told otherwise (a heading's anchor keeps their text)."""
    inside, fence = False, ""
    for number, line in enumerate(text.split("\n"), 1):
        match = FENCE.match(line)
        if match and (not inside or match.group(1) == fence):
            inside, fence = not inside, match.group(1)
            continue
        if not inside:
            yield number, (CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
                           if blank_code_spans else line)


def slug(heading):
    """The anchor GitHub gives a heading: its text without markup, lower case, punctuation
    dropped but for hyphens and underscores, spaces turned into hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = re.sub(r"[`*]", "", text).strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(text):
    """The anchors of a Markdown text: its headings' slugs (repeats numbered as GitHub does)
    and its HTML anchors."""
    found, seen = set(), {}
    for _, line in prose_lines(text, blank_code_spans=False):
        match = HEADING.match(line)
        if match:
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        found.update(HTML_ANCHOR.findall(line))
    return found


def links(text):
    """(line number, target) of every inline link, image and reference definition."""
    for number, line in prose_lines(text):
        for match in INLINE_LINK.finditer(line):
            yield number, match.group(1)
        match = REFERENCE_DEFINITION.match(line)
        if match:
            yield number, match.group(1)


def read(path):
    with open(path, encoding="utf-8") as stream:
        return stream.read()


def check_target(source_dir, path, target, anchor_cache):
    """A problem with one link of the Markdown file `path` (whose own anchors are in
    anchor_cache), or None."""
    if not target or SCHEME.match(target):
        return None if target else "empty link"
    location, _, fragment = target.partition("#")
    if not location:
        return None if urllib.parse.unquote(fragment) in anchor_cache[path] else (
            f"no heading or anchor '#{fragment}' in this file")
    location = urllib.parse.unquote(location)
    resolved = os.path.normpath(os.path.join(os.path.dirname(path), location))
    root = os.path.normpath(source_dir)
    if os.path.commonpath([root, resolved]) != root:
        return "points outside the repository"
    if not os.path.exists(resolved):
        return "no such file or folder"
    if fragment and resolved.endswith(".md") and os.path.isfile(resolved):
        if resolved not in anchor_cache:
            anchor_cache[resolved] = anchors(read(resolved))
        if urllib.parse.unquote(fragment) not in anchor_cache[resolved]:
            return f"no heading or anchor '#{fragment}' in {os.path.relpath(resolved, root)}"
    return None


def check_text(source_dir, path, text, anchor_cache):
    anchor_cache[path] = anchors(text)
    problems = []
    for number, target in links(text):
        problem = check_target(source_dir, path, target, anchor_cache)
        if problem:
            relative = os.path.relpath(path, source_dir)
            problems.append(f"{relative}:{number}: link '{target}': {problem}")
    return problems


def self_check(source_dir):
    """The checker must still see links: a known broken file, a broken anchor and a link in
    code (not a link) in a made-up page beside the top README."""
    page = os.path.join(source_dir, "self-check.md")
    text = ("# A `Title`\n[good](README.md) [bad](no/such/file.md) [here](#a-title)\n"
            "[nowhere](#no-such-heading)\n```\n[in code](missing.md)\n```\n`[span](missing.md)`\n")
    problems = check_text(source_dir, page, text, {})
    expected = ["no/such/file.md", "#no-such-heading"]
    if len(problems) != 2 or any(e not in p for e, p in zip(expected, problems)):
        return ["check_links.py self-check failed: " + "; ".join(problems or ["nothing found"])]
    return []


def main(arguments):
    if len(arguments) != 1:
        raise SystemExit(__doc__)
    source_dir = os.path.abspath(arguments[0])
    problems = self_check(source_dir)
    anchor_cache = {}
    count = 0
    for path in source_files(source_dir, (".md",)):
        count += 1
        problems += check_text(source_dir, path, read(path), anchor_cache)
    return report(problems, f"{count} Markdown file(s), ")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
