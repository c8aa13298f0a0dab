"""A parameter study from Python: the rigid cylinder of examples/hertz_rigid_circle.in pressed
into an elastic block, solved for a range of contact penalties. Prints the contact force and the
peak pressure against Hertz's solution for each, and plots the force against the penalty and
the pressure of the stiffest penalty against the Hertz curve.

    python examples/python/penalty_study.py [output.png]
"""

import pathlib
import sys

import numpy as np

import hertz

HERE = pathlib.Path(__file__).resolve().parent
INPUT = HERE.parent / "hertz_rigid_circle.in"
R = 10.0  # the cylinder's radius (circlecontactsegment 1)
CONTACT = 4  # the contact condition's record number


def hertz_solution(force, young, poisson, radius):
    """Half-width a and peak pressure p0 of a rigid cylinder pressed by `force` per unit
    length into an elastic half-space (plane strain)."""
    e_star = young / (1 - poisson**2)
    a = np.sqrt(4 * force * radius / (np.pi * e_star))
    p0 = np.sqrt(force * e_star / (np.pi * radius))
    return a, p0


def study(penalties):
    """Per penalty: (penalty, contact force of the full cylinder, the last step's contact)."""
    model = hertz.read(INPUT)
    rows = []
    for penalty in penalties:
        model.set_contact(CONTACT, penalty=penalty)
        contact = model.solve().steps[-1].contact
        # Half model (x >= 0): the full cylinder carries twice the force.
        rows.append((penalty, 2 * contact["force"].sum(), contact))
    return model, rows


def main(png=None):
    model, rows = study([1e4, 1e5, 1e6, 1e7])
    material = model.materials[1]
    print(f"{'penalty':>10} {'force F':>12} {'p0':>10} {'Hertz p0':>10} {'error':>8}")
    for penalty, force, contact in rows:
        _, p0_ref = hertz_solution(force, material["E"], material["nu"], R)
        p0 = contact["pressure"].max()
        print(f"{penalty:10.0e} {force:12.6f} {p0:10.4f} {p0_ref:10.4f} {100 * (p0 / p0_ref - 1):+7.2f}%")
    if png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
        left.semilogx([r[0] for r in rows], [r[1] for r in rows], "o-")
        left.set_xlabel("penalty")
        left.set_ylabel("contact force F (per unit length)")
        left.set_title("Force against the penalty")
        penalty, force, contact = rows[-1]
        a, p0 = hertz_solution(force, material["E"], material["nu"], R)
        x = np.linspace(0, a, 200)
        right.plot(x, p0 * np.sqrt(1 - (x / a) ** 2), "k-", label="Hertz")
        closed = contact["active"]
        right.plot(contact["x"][closed], contact["pressure"][closed], "o", ms=4, label=f"hertz, penalty {penalty:.0e}")
        right.set_xlabel("x")
        right.set_ylabel("contact pressure")
        right.set_title("Pressure under the cylinder")
        right.legend()
        fig.tight_layout()
        fig.savefig(png, dpi=100)
    return model, rows


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
