#!/usr/bin/env python3
"""Tie the nodes of a surface set to one new master node: a body held by contact alone.

Kratos' "full Hertz" case as hertz runs it (BENCHMARKS.md, "A body held by contact alone"):
the nodes of the faces in element-boundary set SET (of an `hertz import`ed file of linear
tetrahedra) become `SlaveNode`s of a master node appended after the last node (at 0 0 1),
so a force on the master node loads the body, and supports on it hold the body sideways.
Prints the master's number, the tied nodes' count and the last node's number.

    python3 tools/tie_to_master.py mesh.in mesh_tied.in 4

(The Gmsh hemispheres: set 4 is the upper body's flat top face.)
"""
import sys

# Local node indices of a linear tetrahedron's faces 1-4 (OOFEM's LTRSpace numbering).
FACES = {1: [0, 2, 1], 2: [0, 1, 3], 3: [1, 2, 3], 4: [0, 3, 2]}


def main(src, out, face_set):
    lines = open(src).read().splitlines()
    sets, nodes_of = {}, {}
    for line in lines:
        t = line.split()
        if line.startswith("Set"):
            # `Set N elementboundaries COUNT v1 v2 ... [name "..."]`: the COUNT values.
            sets[int(t[1])] = [int(x) for x in t[4 : 4 + int(t[3])]]
        elif len(t) > 3 and t[2] == "nodes":
            nodes_of[int(t[1])] = [int(x) for x in t[4 : 4 + int(t[3])]]
    tied = set()
    pairs = sets[face_set]
    for element, face in zip(pairs[::2], pairs[1::2]):
        tied.update(nodes_of[element][i] for i in FACES[face])
    node_lines = [i for i, l in enumerate(lines) if l.lower().startswith("node ")]
    last = max(int(lines[i].split()[1]) for i in node_lines)
    master = last + 1
    result = []
    for i, line in enumerate(lines):
        t = line.split()
        if line.lower().startswith("node ") and int(t[1]) in tied:
            line = f"SlaveNode {' '.join(t[1:])} masterDofMan 1 {master} doftype 3 2 2 2"
        result.append(line)
        if i == node_lines[-1]:
            result.append(f"node {master} coords 3 0 0 1.0")
    open(out, "w").write("\n".join(result) + "\n")
    print(master, len(tied), last)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
