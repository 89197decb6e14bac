#!/usr/bin/env python3
"""Reports every C++ function whose body is longer than 60 lines (issue: "no function over 60 lines without a
reason in its comment").

usage: check_function_length.py [--max N] [PATH...]   (default: src/**/*.{cpp,hpp} and include/**/*.hpp of the repository)

A body's length is counted from the line of its opening brace to the line of its closing brace, both included.
A long function is excused when the line just before its signature, or any line of the comment block right above
the signature, contains `long-function:` followed by the reason. Exit status: 0 when nothing is reported,
1 when some function is too long and not excused, 2 for a bad argument.

The parser is deliberately small: comments, string and character literals and preprocessor lines are blanked,
then braces are matched at namespace and class level. A brace block is a function body when the text before it
(since the last `;` or block at that level) ends like a function signature: `)` followed only by qualifiers
(const, override, noexcept, ...), a trailing return type, or a constructor's initializer list. Blocks of
namespaces, classes, structs, unions and enums are searched for member functions; any other block (an
initializer such as `= {...}`) is skipped. Lambdas and local classes count as part of their enclosing function.
"""
import argparse
import os
import re
import sys

MAX_LINES = 60
MARKER = re.compile(r"long-function:\s*\S")
ACCESS = re.compile(r"\s*(?:(?:public|private|protected)\s*:(?!:)\s*)*")
CONTAINER = re.compile(r"\b(?:namespace|class|struct|union|enum)\b")
# `)` then qualifiers, an optional trailing return type, at the end of the header.
SIGNATURE_END = re.compile(
    r"\)\s*(?:(?:const|volatile|override|final|mutable|noexcept(?:\s*\([^()]*\))?|&&|&)\s*)*(?:->[^;{}]*)?$")
# A constructor's initializer list: `) : member(` or `) : member{`, the header then ending in `)` or `}`.
FUNCTION_NAME = re.compile(r"((?:[\w~]+::)*(?:operator\s*(?:\(\)|[^\s(]+)|[\w~]+))\s*\(")
INITIALIZER_LIST = re.compile(r"\)\s*(?:noexcept\s*)?:\s*[\w:]+\s*[({].*[)}]\s*$", re.S)


def blank(text, start, end, out):
    """Replaces text[start:end] in the list `out` by spaces, keeping newlines (so line numbers stay)."""
    for k in range(start, end):
        if text[k] != "\n":
            out[k] = " "


def strip_code(text):
    """The source with comments, string and character literals and preprocessor lines blanked."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True  # only whitespace since the last newline: a '#' here starts a directive
    while i < n:
        c = text[i]
        if c == "\n":
            line_start = True
            i += 1
            continue
        if line_start and c == "#":
            j = i
            while j < n and text[j] != "\n":  # a directive continues over backslash-newlines
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    continue
                if text.startswith("//", j):  # a comment ends the directive's text
                    break
                if text.startswith("/*", j):
                    k = text.find("*/", j + 2)
                    j = n if k < 0 else k + 2
                    continue
                j += 1
            blank(text, i, j, out)
            i = j
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(text, i, j, out)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(text, i, j, out)
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                i += 1
                continue
            close = ")" + m.group(1) + '"'
            j = text.find(close, i + m.end())
            j = n if j < 0 else j + len(close)
            blank(text, i, j, out)
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator: 1'000'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            blank(text, i, j, out)
            i = j
        else:
            i += 1
    return "".join(out)


def matching_brace(code, open_index):
    depth = 0
    for k in range(open_index, len(code)):
        if code[k] == "{":
            depth += 1
        elif code[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(code) - 1  # unbalanced (e.g. braces split over #if branches): to the end


def functions(code, start=0, end=None):
    """Yields (header_start, open_brace, close_brace) character indexes of the function bodies in code[start:end]."""
    end = len(code) if end is None else end
    header = start
    i = start
    while i < end:
        c = code[i]
        if c == ";":
            header = i + 1
        elif c == "}":  # the container's own closing brace (or stray): nothing more at this level
            header = i + 1
        elif c == "{":
            close = matching_brace(code, i)
            text = code[header:i]
            lead = ACCESS.match(text).end()
            head = " ".join(text[lead:].split())
            if SIGNATURE_END.search(head) or INITIALIZER_LIST.search(head):
                yield header + lead + (len(text[lead:]) - len(text[lead:].lstrip())), i, close
                header = close + 1
            elif CONTAINER.search(head):
                yield from functions(code, i + 1, close)
                header = close + 1
            # else: an initializer block; it stays part of the header (`: a_{1} {` is still a constructor)
            i = close
        i += 1


def excused(lines, signature_line):
    """True when the line above the signature, or the comment block right above it, carries the marker."""
    k = signature_line - 1  # 0-based index of the line just before the signature
    if k >= 0 and MARKER.search(lines[k]):
        return True
    while k >= 0:
        stripped = lines[k].strip()
        if not (stripped.startswith("//") or stripped.startswith("/*") or stripped.startswith("*")):
            return False
        if MARKER.search(lines[k]):
            return True
        k -= 1
    return False


def check_file(path, max_lines):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    code = strip_code(text)
    lines = text.split("\n")
    line_of = lambda index: code.count("\n", 0, index)  # 0-based
    reports = []
    for header, open_brace, close_brace in functions(code):
        length = line_of(close_brace) - line_of(open_brace) + 1
        if length <= max_lines:
            continue
        signature_line = line_of(header)
        if excused(lines, signature_line):
            continue
        head = " ".join(code[header:open_brace].split())
        m = FUNCTION_NAME.search(head)
        name = m.group(1) if m else head
        reports.append((path, signature_line + 1, name, length))
    return reports


def default_paths(root):
    paths = []
    for folder, suffixes in (("src", (".cpp", ".hpp")), ("include", (".hpp",))):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, folder)):
            dirnames.sort()
            paths += [os.path.join(dirpath, f) for f in sorted(filenames) if f.endswith(suffixes)]
    return paths


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--max", type=int, default=MAX_LINES, help="longest body allowed [lines] (default 60)")
    parser.add_argument("paths", nargs="*", help="files to check (default: src/**/*.{cpp,hpp}, include/**/*.hpp)")
    args = parser.parse_args(argv)
    if args.max < 1:
        parser.error("--max must be >= 1")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    paths = args.paths or default_paths(root)
    reports = []
    for path in paths:
        reports += check_file(path, args.max)
    for path, line, name, length in reports:
        shown = os.path.relpath(path, root) if not args.paths else path
        print("%s:%d: %s: body of %d lines (> %d) and no `long-function: <reason>` comment above it"
              % (shown, line, name, length, args.max))
    print("check_function_length: %d file(s), %d function(s) too long" % (len(paths), len(reports)))
    return 1 if reports else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
