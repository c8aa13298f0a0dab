#!/usr/bin/env python3
"""An elastic ball of linear tetrahedra dropped on a rigid floor: the 3D impact of BENCHMARKS.md
("Dynamics: impacts over many steps").

A unit ball (E = 1, ν = 0.3, ρ = 1) 0.002 above the floor at V (0.0005), meshed by Gmsh (the
`gmsh` Python module) with the size HMIN within 0.12 of the lower pole growing to HMAX, converted
by `hertz import`; the surface below 30° from the pole in contact by multipliers
(node-to-segment against `planecontactsegment`); Newmark's trapezoidal rule, steps of DT until
1.3 Hertz impact times after the touch. Prints the node count, the contact nodes and the step
count.

    python3 tools/dropped_ball_3d.py --hertz target/release/hertz --out ball3d.in
    hertz run -q --vtu binary ball3d.in

(Defaults: HMIN 0.007, HMAX 0.053, DT 0.06: 34 821 nodes, 104 463 unknowns, 552 steps.)
`--explicit` writes `NlDEIDynamic` (central differences, lumped mass) with a penalty from the
mesh instead; each output step DT is taken in substeps of the stable step.
"""
import argparse
import math
import subprocess
from pathlib import Path

R, GAP, E, NU, RHO = 1.0, 0.002, 1.0, 0.3, 1.0


def mesh(path, hmin, hmax):
    import gmsh

    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("ball")
    ball = gmsh.model.occ.addSphere(0, 0, R + GAP, R)
    gmsh.model.occ.synchronize()
    field = gmsh.model.mesh.field
    size = field.add("MathEval")
    pole = f"Sqrt(x*x + y*y + (z - {GAP})*(z - {GAP}))"
    field.setString(size, "F", f"Min({hmax}, {hmin} + 0.25*Max(0, {pole} - 0.12))")
    field.setAsBackgroundMesh(size)
    for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{option}", 0)
    surface = [t for _, t in gmsh.model.getBoundary([(3, ball)])]
    gmsh.model.addPhysicalGroup(3, [ball], 1, "ball")
    gmsh.model.addPhysicalGroup(2, surface, 2, "surface")
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(str(path))
    gmsh.finalize()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--hertz", default="hertz", help="the hertz binary (for `hertz import`)")
    p.add_argument("--out", default="ball3d.in")
    p.add_argument("--hmin", type=float, default=0.007)
    p.add_argument("--hmax", type=float, default=0.053)
    p.add_argument("--dt", type=float, default=0.06)
    p.add_argument("--speed", type=float, default=0.0005)
    p.add_argument("--law", default="n2slagrangianmultipliercontact")
    p.add_argument("--explicit", action="store_true",
                   help="NlDEIDynamic (central differences) with a penalty from the mesh")
    a = p.parse_args()
    V = a.speed
    if a.explicit:
        a.law = "n2spenaltycontact"
    out = Path(a.out)
    msh, fragment = out.with_suffix(".msh"), out.with_name(out.stem + "_mesh.in")
    mesh(msh, a.hmin, a.hmax)
    subprocess.run([a.hertz, "import", str(msh), "-o", str(fragment)], check=True,
                   stdout=subprocess.DEVNULL)
    nodes, nelem = [], None
    for line in fragment.open():
        if line.startswith("# Counts record:"):
            nelem = int(line.split("nelem")[1].split()[0])
        elif line.startswith("Node "):
            t = line.split()
            nodes.append((int(t[1]), float(t[4]), float(t[5]), float(t[6])))
    centre = R + GAP
    contact = [k for k, x, y, z in nodes
               if abs(math.sqrt(x * x + y * y + (z - centre) ** 2) - R) < 1e-6
               and z - centre < -R * math.cos(math.pi / 6)]
    e_star = E / (1 - NU * NU)
    mass = RHO * 4 / 3 * math.pi * R**3
    impact = 2.87 * (mass * mass / (R * e_star * e_star * V)) ** 0.2
    nsteps = round((GAP / V + 1.3 * impact) / a.dt)
    records = [
        "ball3d.out",
        "Elastic ball of tetrahedra dropped on a rigid floor",
        f"NlDEIDynamic nsteps {nsteps} deltat {a.dt} dumpcoef 0" if a.explicit else
        f"NonLinearDynamic nsteps {nsteps} deltat {a.dt} ddtScheme 2 rtolf 1e-8 manrmsteps 1 "
        "maxiter 30",
        "domain 3d",
        "OutputManager tstep_step 50",
        f"ndofman {len(nodes)} nelem {nelem} ncrosssect 1 nmat 1 nbc 1 nic 1 nltf 1 nset 4 "
        "ncontactseg 1",
        f'@include "{fragment.name}"',
        f"Set 3 nodes {len(contact)} " + " ".join(map(str, contact)),
        f"Set 4 nodes {len(nodes)} " + " ".join(str(k) for k, *_ in nodes),
        "planecontactsegment 1 point 3 0 0 0 normal 3 0 0 1",
        "SimpleCS 1 material 1 set 1",
        f"IsoLE 1 d {RHO} E {E} n {NU} tAlpha 0",
        f"{a.law} 1 loadTimeFunction 1 slaveset 3 segmentset 1 1",
        f"InitialCondition 1 conditions 1 v {-V} set 4 dofs 1 3",
        "ConstantFunction 1 f(t) 1",
    ]
    out.write_text("\n".join(records) + "\n")
    print(f"{len(nodes)} nodes ({3 * len(nodes)} unknowns), {len(contact)} contact nodes, "
          f"{nsteps} steps; Hertz's impact time {impact:.4f}")


if __name__ == "__main__":
    main()
