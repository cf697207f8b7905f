#!/usr/bin/env python3
"""Where `lamina build --json` put each part: reads the run's JSON from
standard input only as far as the plate's parts (job.build.parts[], written
before any layer) and prints one line per part: NAME X Y, the numbers as
the JSON wrote them (so a job file given them places the part exactly
there). Stops reading after COUNT parts: the layers that follow (hundreds
of megabytes for a plate) are never read; lamina then ends on a broken pipe.

usage: lamina build JOB --json /dev/stdout -o /dev/null | plate_at.py COUNT
"""
import re
import sys

PART = re.compile(r'\{"part": (\d+), "name": "((?:[^"\\]|\\.)*)", .*?"at": \[([^,\]]+), ([^\]]+)\]')


def main():
    want = int(sys.argv[1])
    got = []
    for line in sys.stdin:
        m = PART.search(line)
        if m:
            got.append((m.group(2), m.group(3).strip(), m.group(4).strip()))
            if len(got) == want:
                break
    if len(got) != want:
        sys.exit("plate_at.py: found %d parts' places, wanted %d" % (len(got), want))
    for name, x, y in got:
        print(name, x, y)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
