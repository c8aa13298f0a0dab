"""The crushed tube of examples/crushed_tube.in from Python: a neo-Hookean tube crushed flat
between two rigid plates, its bore in self-contact. Prints the plate force at each step and
how many bore nodes touch, and draws the deformed tube at three stages (the bore closing) beside
the force against the plates' travel.

    python examples/python/crushed_tube.py [output.png]
"""

import pathlib
import sys

import numpy as np

import hertz

HERE = pathlib.Path(__file__).resolve().parent
INPUT = HERE.parent / "crushed_tube.in"
BORE = 5  # the self-contact condition
PLATE = 1  # the boundary condition moving the top plate


def main(png=None):
    model = hertz.read(INPUT)
    result = model.solve()
    top, bottom = len(model.nodes) - 2, len(model.nodes) - 1  # the plates' reference nodes
    travel, force, below, touching = [], [], [], []
    for step in result.steps:
        c = step.contact
        touching.append(int(np.sum((c["condition"] == BORE) & (c["active"] == 1))))
        travel.append(-step.displacement[top, 1])
        force.append(-step.reaction[top, 1])
        below.append(step.reaction[bottom, 1])
        print(
            f"step {step.step:2d}: travel {travel[-1]:.3f}, force {force[-1]:9.2f}, "
            f"bore nodes touching {touching[-1]}"
        )
    if png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection

        quads = model.elements["Quad1PlaneStrain"]
        row_of = {label: k for k, label in enumerate(model.node_labels)}
        rows = np.vectorize(row_of.get)(quads["connectivity"])
        stages = [len(result.steps) // 2, 3 * len(result.steps) // 4, len(result.steps) - 1]
        fig, axes = plt.subplots(1, 4, figsize=(18, 4.2))
        for ax, k in zip(axes, stages):
            step = result.steps[k]
            x = model.nodes[:, :2] + step.displacement[:, :2]
            ax.add_collection(PolyCollection(x[rows], facecolor="#c9d6e8", edgecolor="#34495e", linewidth=0.4))
            c = step.contact
            on = (c["condition"] == BORE) & (c["active"] == 1)
            ax.plot(c["x"][on], c["y"][on], "o", color="#c0392b", markersize=2.5, label="bore in contact")
            ax.set_xlim(-1.9, 1.9)
            ax.set_ylim(-1.1, 1.1)
            ax.set_aspect("equal")
            ax.set_title(f"plates moved {travel[k]:.2f} each")
            ax.legend(loc="upper right", fontsize=8)
        axes[3].plot(travel, force, "o-", color="#2c3e50", markersize=3)
        axes[3].set_xlabel("travel of each plate")
        axes[3].set_ylabel("plate force per unit length")
        axes[3].set_title("force against travel (bore closes: the force climbs)")
        fig.tight_layout()
        fig.savefig(png, dpi=110)
        print(f"wrote {png}")
    return np.array(travel), np.array(force), np.array(below), touching


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
