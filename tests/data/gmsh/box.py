"""Regenerate the Gmsh test meshes of tests/suite/gmsh.rs (pip install gmsh; python3 box.py).

Unit cube in hexahedra, tetrahedra (also 10-node ones) and prisms, and in 20-node hexahedra; unit square in quadrangles, triangles,
6-node triangles and 8-node quadrangles. Physical groups: the body (1), faces/edges x = 0 (2), y = 0 (3), z = 0 or
the bottom (4), the top (5)."""
import gmsh

def groups(dim):
    gmsh.model.occ.synchronize()
    tag = {1: "body"}
    gmsh.model.addPhysicalGroup(dim, [e[1] for e in gmsh.model.getEntities(dim)], 1, "body")
    eps = 1e-6
    def at(axis, value):
        lo = [-1, -1, -1]; hi = [2, 2, 2]
        lo[axis] = value - eps; hi[axis] = value + eps
        return [e[1] for e in gmsh.model.getEntitiesInBoundingBox(*lo, *hi, dim - 1)]
    top_axis = 2 if dim == 3 else 1
    for tag, name, axis, v in [(2, "x0", 0, 0.0), (3, "y0", 1, 0.0), (4, "bottom", top_axis, 0.0), (5, "top", top_axis, 1.0)]:
        if dim == 2 and name == "y0":
            continue
        gmsh.model.addPhysicalGroup(dim - 1, at(axis, v), tag, name)

def cube(name, kind):
    gmsh.model.add(name)
    if kind == "prism":
        gmsh.model.occ.addRectangle(0, 0, 0, 1, 1)
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.5)
        gmsh.model.occ.extrude([(2, 1)], 0, 0, 1, numElements=[2], recombine=True)
    else:
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
        gmsh.model.occ.synchronize()
        if kind in ("hex", "hex20"):
            for c in gmsh.model.getEntities(1):
                gmsh.model.mesh.setTransfiniteCurve(c[1], 3)
            for s in gmsh.model.getEntities(2):
                gmsh.model.mesh.setTransfiniteSurface(s[1])
                gmsh.model.mesh.setRecombine(2, s[1])
            gmsh.model.mesh.setTransfiniteVolume(1)
        else:
            gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.5)
    groups(3)
    gmsh.model.mesh.generate(3)
    if kind == "tet10":
        gmsh.model.mesh.setOrder(2)
    if kind == "hex20":
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.setOrder(2)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    gmsh.write(name + ".msh")

def square(name, kind):
    gmsh.model.add(name)
    gmsh.model.occ.addRectangle(0, 0, 0, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.model.mesh.setSize(gmsh.model.getEntities(0), 0.34)
    if not kind.startswith("tri"):
        gmsh.model.mesh.setRecombine(2, 1)
    groups(2)
    gmsh.model.mesh.generate(2)
    if kind in ("quad8", "tri6"):
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.model.mesh.setOrder(2)
    gmsh.write(name + ".msh")
    if name == "square_tri":
        # The same mesh in the other format: tests/suite/gmsh.rs compares the two conversions.
        gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
        gmsh.write(name + "_v22.msh")
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
cube("cube_hex", "hex")
cube("cube_tet", "tet")
cube("cube_tet10", "tet10")
cube("cube_hex20", "hex20")
cube("cube_prism", "prism")
square("square_tri", "tri")
gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
square("square_quad", "quad")
square("square_quad8", "quad8")
square("square_tri6", "tri6")
gmsh.finalize()
