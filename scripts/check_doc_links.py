#!/usr/bin/env python3
"""Checks the relative links of README.md and docs/**/*.md: every `[text](path)` and `[text](path#anchor)` must name
a file or directory that exists, and an anchor must be produced by a heading of the target page (GitHub's rule:
lower case, punctuation other than `-` and `_` dropped, spaces to `-`, repeats numbered -1, -2, ...).

  scripts/check_doc_links.py [--repo DIR]     exit 1 and list each broken link as FILE:LINE: LINK: why

Links inside fenced code blocks and inline code are not links; http(s) and mailto links are not checked.
"""
import argparse
import glob
import os
import re
import sys

LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^()\s]+)(?:\s+"[^"]*")?\)')
HEADING = re.compile(r'^(#{1,6})\s+(.*?)\s*#*\s*$')
FENCE = re.compile(r'^\s*(```|~~~)')


def lines_outside_code(text):
    """(line number, line with inline code removed) of every line outside fenced blocks."""
    fenced = False
    for number, line in enumerate(text.split('\n'), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, re.sub(r'`[^`]*`', '', line)


def slug(heading):
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading)  # a link in a heading counts by its text
    text = text.strip().lower()
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def anchors(path):
    seen, found = {}, set()
    with open(path) as f:
        for _, line in lines_outside_code(f.read()):
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else '%s-%d' % (base, n))
    return found


def broken_links(repo):
    pages = [os.path.join(repo, 'README.md')] + sorted(glob.glob(os.path.join(repo, 'docs', '**', '*.md'),
                                                                 recursive=True))
    problems, cache = [], {}
    for page in pages:
        with open(page) as f:
            text = f.read()
        for number, line in lines_outside_code(text):
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r'^(https?:|mailto:)', target):
                    continue
                path, _, anchor = target.partition('#')
                full = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                where = '%s:%d: %s' % (os.path.relpath(page, repo), number, target)
                if not os.path.exists(full):
                    problems.append('%s: no such file' % where)
                    continue
                if anchor:
                    if not full.endswith('.md') or os.path.isdir(full):
                        problems.append('%s: an anchor on a page that is not markdown' % where)
                        continue
                    if full not in cache:
                        cache[full] = anchors(full)
                    if anchor not in cache[full]:
                        problems.append('%s: no heading makes the anchor #%s' % (where, anchor))
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--repo', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = ap.parse_args()
    problems = broken_links(args.repo)
    for p in problems:
        print(p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
