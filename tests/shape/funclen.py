#!/usr/bin/env python3
"""Functions longer than a limit in C files: a function's body runs from a
line that opens it at the left margin ("{" alone or ending a signature that
starts at column 0) to the next "}" at the left margin, the house layout.
  funclen.py LIMIT FILE...   prints FILE:LINE: NAME N lines, exit 1 if any"""
import re
import sys

limit = int(sys.argv[1])
over = 0
for path in sys.argv[2:]:
    lines = open(path, encoding="utf-8", errors="replace").read().split("\n")
    start = name = None
    for i, line in enumerate(lines):
        if start is None:
            if line.startswith("{") or (re.match(r"^[A-Za-z_].*\)\s*\{\s*$", line)
                                        and not re.match(r"^(struct|enum|union|typedef)\b", line)):
                j = i if not line.startswith("{") else i - 1
                while j > 0 and "(" not in lines[j]:
                    j -= 1
                m = re.search(r"([A-Za-z_]\w*)\s*\(", lines[j])
                name = m.group(1) if m else "?"
                if re.match(r"^(static\s+)?(const\s+)?(struct|enum|union)\s+\w+\s*(\w+\s*)?(=\s*)?\{?$", lines[j]) or "=" in lines[j].split("(")[0]:
                    continue
                start = i
        elif line.startswith("}"):
            n = i - start - 1
            if n > limit:
                print("%s:%d: %s %d lines" % (path, start + 1, name, n))
                over += 1
            start = None
sys.exit(1 if over else 0)
