#!/usr/bin/env python3
"""Lists the functions of src/ and app/ longer than a limit (100 lines by default).

A heuristic, not a parser: comments, strings and character literals are blanked, then each brace
that opens after a parameter list's `)` (and not after `if (...)`, `for (...)`, `while (...)`,
`switch (...)`, `catch (...)` or a lambda's `]`) opens a function body. Nested functions (the
member functions of a local class, lambdas written with a parameter list) count towards the
function they are in; only outermost bodies are reported, from the line of their `{` to the line
of their `}`.

Exit status 1 when a function over the limit is not in PENDING (the functions still to be split;
remove an entry once its function is short), 0 otherwise. A PENDING entry that is no longer over
the limit is reported too, so that the list only shrinks.

    scripts/long_functions.py            # from anywhere: the repository of this script
    scripts/long_functions.py --limit 80 --all
"""
import argparse
import pathlib
import re
import sys

# (file, a piece of the function's head) of the functions still over the limit.
PENDING: set[tuple[str, str]] = set()

COMMENT_LINE = re.compile(r"//[^\n]*")
COMMENT_BLOCK = re.compile(r"/\*.*?\*/", re.S)
STRING = re.compile(r'"(\\.|[^"\\\n])*"')
CHAR = re.compile(r"'(\\.|[^'\\\n])*'")
# A raw string R"delim( ... )delim", which may hold quotes and braces.
RAW_STRING = re.compile(r'R"([^(\s]*)\(.*?\)\1"', re.S)
BODY_HEAD = re.compile(r"\)\s*(const|override|noexcept|final|mutable|\s)*(->\s*[\w:<>&*\s]+)?$")
CONTROL = re.compile(r"\b(if|for|while|switch|catch)\s*\(")


def blank(text: str) -> str:
    """Comments, strings and character literals blanked, newlines kept (so lines still count)."""
    keep_lines = lambda m: "\n" * m.group(0).count("\n")
    text = RAW_STRING.sub(lambda m: '""' + keep_lines(m), text)
    text = COMMENT_BLOCK.sub(keep_lines, text)
    text = COMMENT_LINE.sub("", text)
    text = STRING.sub('""', text)
    return CHAR.sub("''", text)


def opens_function(head: str) -> bool:
    head = head.strip()
    if not head or head.endswith("]") or not BODY_HEAD.search(head):
        return False
    return not CONTROL.search(head.split("\n")[-1])


def long_functions(path: pathlib.Path, limit: int):
    """(lines, head) of every outermost function body of `path` longer than `limit` lines."""
    text = blank(path.read_text(encoding="utf-8", errors="replace"))
    found = []
    stack = []  # (is_function, line of the '{', head)
    head = ""
    line = 1
    for ch in text:
        if ch == "\n":
            line += 1
        if ch == "{":
            stack.append((opens_function(head), line, " ".join(head.split())[-80:]))
            head = ""
        elif ch == "}":
            if stack:
                is_function, first, name = stack.pop()
                if is_function and not any(f for f, _, _ in stack):
                    if line - first + 1 > limit:
                        found.append((line - first + 1, name))
            head = ""
        elif ch == ";":
            head = ""
        else:
            head += ch
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=int, default=100, help="longest allowed (lines)")
    parser.add_argument("--all", action="store_true",
                        help="list the pending functions too, not only the new ones")
    args = parser.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    files = sorted(list((root / "src").rglob("*.cpp")) + list((root / "app").glob("*.cpp")))
    over = []
    for path in files:
        rel = path.relative_to(root).as_posix()
        for n, head in long_functions(path, args.limit):
            pending = any(rel == f and piece in head for f, piece in PENDING)
            over.append((n, rel, head, pending))
    over.sort(key=lambda o: (-o[0], o[1]))
    new = [o for o in over if not o[3]]
    for n, rel, head, pending in over:
        if args.all or not pending:
            print(f"{rel}: {n} lines: {head}{'  (pending)' if pending else ''}")
    still = {(f, piece) for f, piece in PENDING
             if any(rel == f and piece in head for _, rel, head, _ in over)}
    for f, piece in sorted(PENDING - still):
        print(f"{f}: '{piece}' is no longer over {args.limit} lines: remove it from PENDING")
    print(f"{len(over)} function(s) over {args.limit} lines, {len(new)} not pending")
    return 1 if new else 0


if __name__ == "__main__":
    sys.exit(main())
