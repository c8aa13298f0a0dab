#!/usr/bin/env python3
"""Write an OOFEM input with every node and every rigid contact segment's reference point
(`point`, `centerpoint`) moved by D along each axis: a model far from the origin, as a mesh in
a machine's coordinates is (BENCHMARKS.md, "Contact models far from the origin").

    python3 tools/moved.py IN.in OUT.in D
"""
import sys


def moved_line(line, d):
    tokens = line.split()
    low = line.lstrip().lower()
    keys = ["coords"] if low.startswith("node ") else (
        ["point", "centerpoint"] if "contactsegment" in low else [])
    changed = False
    for key in keys:
        for i, t in enumerate(tokens):
            if t.lower() == key:
                n = int(tokens[i + 1])
                for k in range(n):
                    tokens[i + 2 + k] = repr(float(tokens[i + 2 + k]) + d)
                changed = True
                break
    return " ".join(tokens) + "\n" if changed else line


def main():
    src, dst, d = sys.argv[1], sys.argv[2], float(sys.argv[3])
    with open(src) as f:
        lines = [moved_line(line, d) for line in f]
    with open(dst, "w") as f:
        f.writelines(lines)


if __name__ == "__main__":
    main()
