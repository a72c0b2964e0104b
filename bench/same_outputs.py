#!/usr/bin/python3
"""Are two `align` output folders the same, wall-clock figures aside?

Usage: bench/same_outputs.py BEFORE AFTER

Every file of BEFORE must exist in AFTER with the same bytes. Where the bytes differ, JSON files
are compared again without their wall-clock figures (keys ending in `seconds` or `_s`, and
`peak_memory_mib`), and text files (report.html, the notes inside metrics.json) without the
timings they print (any "N.N s", the report's table of stage times and its bars). Prints one line
per folder and each file that still differs; exits 1 when one does (or AFTER holds other files),
2 on bad arguments. For a refactoring that must not change a result (issue 32's io/ split).
"""
import json
import os
import re
import sys

WALL_KEY = re.compile(r"(seconds|_s|peak_memory_mib)$")
# A row of the report's timing table (stage, seconds, bar); then any seconds printed ("in 7.5 s"
# in a note, "Took 4.84 s", a model's fit time): every figure in seconds is the clock's.
WALL_TEXT = [
    (re.compile(r"<tr><td>[a-z_]+</td><td>[0-9.]+ s</td><td class=\"bar-cell\">"
                r"<span class=\"bar\" style=\"width:[0-9.]+%\"></span></td></tr>"), ""),
    (re.compile(r"\b\d+(\.\d+)? s\b"), "N s"),
]


def without_wall_text(text):
    for pattern, replacement in WALL_TEXT:
        text = pattern.sub(replacement, text)
    return text


def without_wall_clock(value):
    if isinstance(value, dict):
        return {k: without_wall_clock(v) for k, v in value.items() if not WALL_KEY.search(k)}
    if isinstance(value, list):
        return [without_wall_clock(v) for v in value]
    if isinstance(value, str):
        return without_wall_text(value)
    return value


def embedded_json_without_wall_clock(text):
    """report.html embeds metrics.json: drop its wall-clock keys' values and objects."""
    text = re.sub(r'"(timings_s|peak_memory_mib)":\s*\{[^{}]*\}', r'"\1":{}', text)
    text = re.sub(r'"([A-Za-z_]*(seconds|_s))":\s*-?[0-9.eE+-]+', r'"\1":0', text)
    return without_wall_text(text)


def same(before, after):
    with open(before, "rb") as a, open(after, "rb") as b:
        x, y = a.read(), b.read()
    if x == y:
        return "bytes"
    if before.endswith(".json"):
        try:
            if without_wall_clock(json.loads(x)) == without_wall_clock(json.loads(y)):
                return "wall-clock"
        except ValueError:
            return None
    elif before.endswith((".html", ".txt", ".log")):
        if embedded_json_without_wall_clock(x.decode()) == embedded_json_without_wall_clock(
                y.decode()):
            return "wall-clock"
    return None


def main():
    if len(sys.argv) != 3 or not all(os.path.isdir(d) for d in sys.argv[1:]):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    before, after = sys.argv[1], sys.argv[2]
    counts = {"bytes": 0, "wall-clock": 0}
    differ = []
    seen = set()
    for root, _, files in os.walk(before):
        for name in sorted(files):
            path = os.path.join(root, name)
            rel = os.path.relpath(path, before)
            seen.add(rel)
            other = os.path.join(after, rel)
            verdict = same(path, other) if os.path.exists(other) else None
            if verdict:
                counts[verdict] += 1
            else:
                differ.append(rel if os.path.exists(other) else rel + " (missing)")
    for root, _, files in os.walk(after):
        for name in files:
            rel = os.path.relpath(os.path.join(root, name), after)
            if rel not in seen:
                differ.append(rel + " (only in " + after + ")")
    print(f"{before} -> {after}: {counts['bytes']} files byte for byte, "
          f"{counts['wall-clock']} the same but for wall-clock figures, {len(differ)} differ")
    for rel in differ:
        print("  differs:", rel)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
