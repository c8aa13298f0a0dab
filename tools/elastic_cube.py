"""A linear elastic cube of n x n x n bricks (E = 1000, nu = 0.3), clamped at z = 0 and loaded
on z = 1 by a total force (1, 0, -1), written as an OOFEM input with the Python module:

    python tools/elastic_cube.py N out.in

(BENCHMARKS.md, "PETSc", uses N = 30.)"""

import sys

import numpy as np

import hertz

n = int(sys.argv[1])
g = np.linspace(0, 1, n + 1)
X, Y, Z = np.meshgrid(g, g, g, indexing="ij")
nodes = np.stack([X.ravel(), Y.ravel(), Z.ravel()], 1)


def label(i, j, k):
    return i * (n + 1) ** 2 + j * (n + 1) + k + 1


conn = []
for i in range(n):
    for j in range(n):
        for k in range(n):
            top = [label(i, j, k + 1), label(i, j + 1, k + 1), label(i + 1, j + 1, k + 1), label(i + 1, j, k + 1)]
            bottom = [label(i, j, k), label(i, j + 1, k), label(i + 1, j + 1, k), label(i + 1, j, k)]
            conn.append(top + bottom)
base = [label(i, j, 0) for i in range(n + 1) for j in range(n + 1)]
lid = [label(i, j, n) for i in range(n + 1) for j in range(n + 1)]
text = hertz.input_from_arrays(
    nodes,
    {"LSpace": conn},
    domain="3d",
    analysis=("LinearStatic", {"nsteps": 1}),
    materials=[("IsoLE", {"d": 0, "E": 1000.0, "n": 0.3, "tAlpha": 0})],
    conditions=[
        ("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [1, 2, 3], "values": [0, 0, 0], "set": 1}),
        ("NodalLoad", {"loadTimeFunction": 1, "dofs": [1, 2, 3], "components": [1.0 / len(lid), 0, -1.0 / len(lid)], "set": 2}),
    ],
    sets={1: {"nodes": base}, 2: {"nodes": lid}},
    name="block",
)
with open(sys.argv[2], "w") as f:
    f.write(text)
