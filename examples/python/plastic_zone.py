"""The plastic zone of examples/indentation.in from Python: a rigid cylinder pressed 0.15 into a
perfectly plastic block and lifted off. Prints the imprint and the largest equivalent plastic
strain kappa and where it lies, and draws kappa per element (the mean of its integration
points) under the deepest indentation and after lift-off, beside the contact pressure.

    python examples/python/plastic_zone.py [output.png]
"""

import pathlib
import sys

import numpy as np

import hertz

HERE = pathlib.Path(__file__).resolve().parent
INPUT = HERE.parent / "indentation.in"
DEEPEST = 9  # step 10: the cylinder at its deepest (0-based index into Result.steps)


def element_kappa(model, step):
    """Per element of the block: its centre (x, y) and the mean kappa of its points."""
    block = model.elements["Quad1PlaneStrainBB"]
    row_of = {label: k for k, label in enumerate(model.node_labels)}
    nodes = np.vectorize(row_of.get)(block["connectivity"])
    centres = model.nodes[nodes].mean(axis=1)[:, :2]
    points = step.points
    kappa = np.zeros(len(block["labels"]))
    count = np.zeros(len(block["labels"]))
    index = {label: k for k, label in enumerate(block["labels"])}
    for label, value in zip(points["element"], points["kappa"]):
        kappa[index[label]] += value
        count[index[label]] += 1
    return centres, kappa / np.maximum(count, 1)


def main(png=None):
    model = hertz.read(INPUT)
    result = model.solve()
    deepest, last = result.steps[DEEPEST], result.steps[-1]
    top = int(np.flatnonzero((model.nodes[:, 0] == 0) & (model.nodes[:, 1] == 0))[0])
    imprint = -last.displacement[top, 1]
    centres, kappa = element_kappa(model, deepest)
    worst = int(np.argmax(kappa))
    print(f"imprint on the axis after lift-off: {imprint:.4f}")
    print(
        f"largest kappa at the deepest step: {kappa[worst]:.4f} "
        f"at x = {centres[worst, 0]:.3f}, depth {-centres[worst, 1]:.3f}"
    )
    if png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        near = (centres[:, 0] < 3) & (centres[:, 1] > -2)
        fig, axes = plt.subplots(1, 3, figsize=(15, 4))
        for ax, step, title in [(axes[0], deepest, "at the deepest step"), (axes[1], last, "after lift-off")]:
            _, k = element_kappa(model, step)
            art = ax.tricontourf(centres[near, 0], centres[near, 1], k[near], levels=20)
            fig.colorbar(art, ax=ax, label="equivalent plastic strain")
            ax.set_aspect("equal")
            ax.set_xlabel("x")
            ax.set_ylabel("y")
            ax.set_title(f"kappa {title}")
        contact = deepest.contact
        closed = contact["active"]
        axes[2].plot(contact["x"][closed], contact["pressure"][closed], "o", ms=4)
        axes[2].set_xlabel("x")
        axes[2].set_ylabel("contact pressure")
        axes[2].set_title("Pressure at the deepest step")
        fig.tight_layout()
        fig.savefig(png, dpi=100)
    return imprint, kappa[worst], centres[worst]


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
