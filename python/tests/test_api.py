"""The Python module against the command line on the same inputs, and each entry of its API."""

import math
import re
import subprocess

import numpy as np
import pytest

import hertz
from conftest import EXAMPLES, ROOT

EXAMPLE_INPUTS = sorted(EXAMPLES.glob("*.in")) + sorted((EXAMPLES / "gmsh").glob("*.in"))

# Lines of the .out file that carry the wall clock (they differ between any two runs).
CLOCK = re.compile(r"^(Starting analysis on|Finishing analysis on|Real time consumed|User time consumed)")


def read_outfile(path, steps):
    """Per output step: {(node label, dof): reaction text} and {(node label, dof): d text}; the
    step is the header's "solution step number", else the step at its time."""
    reactions, displacements = {}, {}
    time = None
    node = None
    for line in path.read_text().splitlines():
        m = re.match(r"Output for time\s+([-+0-9.eE]+)(?:, solution step number (\d+))?", line)
        if m:
            if m.group(2):
                time = int(m.group(2))
            else:
                time = next(s.step for s in steps if s.time == float(m.group(1)))
            reactions[time], displacements[time] = {}, {}
            continue
        m = re.match(r"Node\s+\d+\s+\(\s*(\d+)\):", line)
        if m:
            node = int(m.group(1))
            continue
        m = re.match(r"\s+dof (\d+)\s+d\s+(\S+)", line)
        if m and node is not None:
            displacements[time][(node, int(m.group(1)))] = m.group(2)
            continue
        m = re.match(r"\s*Node\s+(\d+) iDof\s+(\d+) reaction\s+(\S+)", line)
        if m:
            reactions[time][(int(m.group(1)), int(m.group(2)))] = m.group(3)
    return reactions, displacements


def read_csv(path):
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    return [dict(zip(header, row.split(","))) for row in lines[1:]]


@pytest.mark.parametrize("path", EXAMPLE_INPUTS, ids=lambda p: p.name)
def test_every_example_equals_the_command_line(path, tmp_path, hertz_cli):
    cli_dir, py_dir = tmp_path / "cli", tmp_path / "py"
    subprocess.run([hertz_cli, "run", "-q", "-o", cli_dir, path], check=True, capture_output=True)
    model = hertz.read(path)
    result = model.solve()
    assert result.converged and len(result.steps) == len(model.step_times)
    written = result.write(py_dir)
    # The same files, and the same contents but for the wall clock.
    assert sorted(p.name for p in cli_dir.iterdir()) == sorted(p.name for p in written)
    for p in written:
        cli = [l for l in (cli_dir / p.name).read_text().splitlines() if not CLOCK.match(l)]
        py = [l for l in p.read_text().splitlines() if not CLOCK.match(l)]
        assert cli == py, p.name
    labels = model.node_labels
    row = {int(n): i for i, n in enumerate(labels)}
    # Reactions and displacements as the .out file prints them, to its last digit.
    out = next(p for p in written if p.suffix == ".out")
    reactions, displacements = read_outfile(out, result.steps)
    by_time = {s.step: s for s in result.steps}
    checked = 0
    for time, values in reactions.items():
        step = by_time[time]
        for (node, dof), text in values.items():
            assert f"{step.reaction[row[node], dof - 1]:.4e}" == text, (time, node, dof)
            checked += 1
    for time, values in displacements.items():
        step = by_time[time]
        for (node, dof), text in values.items():
            if dof <= step.displacement.shape[1]:
                assert f"{step.displacement[row[node], dof - 1]:.8e}" == text, (node, dof)
    # Contact pressures, gaps and forces equal the CSV's (which round-trip exactly).
    csv = [p for p in written if p.name.endswith(".contact.csv")]
    if csv:
        rows = read_csv(csv[0])
        for step in result.steps:
            mine = [r for r in rows if int(r["step"]) == step.step]
            c = step.contact
            assert len(mine) == len(c["node"])
            for k, r in enumerate(mine):
                assert int(r["node"]) == c["node"][k]
                for col in ("pressure", "force", "x", "y", "z"):
                    assert float(r[col]) == c[col][k], (col, k)
                assert bool(int(r["active"])) == c["active"][k]
            checked += len(mine)
    # The summed reactions of every boundary condition, as the step CSV gives them.
    steps_csv = read_csv(next(p for p in written if p.name.endswith(".steps.csv")))
    for step, r in zip(result.steps, steps_csv):
        assert int(r["iterations"]) == step.iterations
        for key, text in r.items():
            m = re.fullmatch(r"bc(\d+)\.r(\d)", key)
            if not m:
                continue
            bc = model.boundary_conditions[int(m.group(1))]
            nodes = model.sets[bc["set"]]["nodes"]
            col = model.dof_ids.index(int(m.group(2)))
            parts = [step.reaction[row[int(n)], col] for n in nodes]
            assert abs(sum(parts) - float(text)) <= 1e-12 * sum(map(abs, parts)), key
    assert checked > 0 or not reactions


WEDGE = (EXAMPLES / "wedge_on_brick.in").read_text()


def test_read_string_reads_as_read_does():
    a = hertz.read(EXAMPLES / "wedge_on_brick.in").solve()
    b = hertz.read_string(WEDGE, name="wedge").solve()
    assert np.array_equal(a.steps[-1].reaction, b.steps[-1].reaction)
    assert np.array_equal(a.steps[-1].contact["pressure"], b.steps[-1].contact["pressure"])


def test_model_arrays_describe_the_input():
    m = hertz.read(EXAMPLES / "wedge_on_brick.in")
    assert m.dim == 3
    assert m.nodes.shape == (14, 3) and m.nodes[12].tolist() == [0.8, 0.3, 1.5]
    assert m.node_labels.tolist() == list(range(1, 15))
    assert m.elements["LSpace"]["connectivity"].tolist() == [[5, 7, 8, 6, 1, 3, 4, 2]]
    assert m.elements["LWedge"]["labels"].tolist() == [2]
    assert m.sets[5]["nodes"].tolist() == [12, 13, 14]
    assert m.sets[1]["boundaries"].tolist() == [[1, 1]]
    assert m.materials[1] == {"law": "IsoLE", "E": 1000.0, "nu": 0.3}
    assert m.contacts[5] == {"law": "multipliers", "penalty": None, "friction": None}
    assert m.boundary_conditions[4]["values"] == [0.0, 0.0, -0.01]


def test_a_bad_record_raises_input_error_with_file_and_line():
    text = WEDGE.replace("IsoLE 1 d 0 E 1000", "IsoLE 1 d 0 E -1000")
    line = 1 + text.splitlines().index(next(l for l in text.splitlines() if "E -1000" in l))
    with pytest.raises(hertz.InputError) as e:
        hertz.read_string(text, name="bad_wedge.in")
    assert e.value.line == line
    assert e.value.file == "bad_wedge.in"
    assert f"bad_wedge.in:{line}:" in str(e.value) and "E -1000" in e.value.record
    with pytest.raises(hertz.InputError) as e:
        hertz.read(ROOT / "no" / "such.in")
    assert e.value.line is None and "such.in" in str(e.value)
    assert issubclass(hertz.InputError, hertz.HertzError)


def nonconverging():
    """The large-deflection cantilever, unloaded at t = 1 and loaded at t = 2, with two Newton
    iterations allowed: step 1 converges at once, step 2 cannot."""
    text = (ROOT / "tests" / "data" / "cantilever_nlgeo.in").read_text()
    text = text.replace("nsteps 1", "nsteps 2").replace("maxiter MAXITER", "maxiter 2")
    text = text.replace("ConstantFunction 1 f(t) 1.0", "PiecewiseLinFunction 1 npoints 2 t 2 1 2 f(t) 2 0 1")
    return hertz.read_string(text, name="cantilever_nlgeo.in")


def test_a_step_that_cannot_converge_raises_solve_error_with_the_steps_before():
    with pytest.raises(hertz.SolveError) as e:
        nonconverging().solve()
    msg = str(e.value)
    assert "step 2" in msg and "did not converge" in msg
    partial = e.value.result
    assert not partial.converged and partial.message == msg
    assert [s.step for s in partial.steps] == [1]
    assert np.all(partial.steps[0].displacement == 0.0)


def test_an_observer_sees_every_iteration_and_step():
    reports = []
    model = hertz.read(EXAMPLES / "hertz_rigid_circle.in")
    result = model.solve(observer=reports.append)
    steps = [r for r in reports if r["kind"] == "step"]
    iterations = [r for r in reports if r["kind"] == "iteration"]
    assert [r["step"] for r in steps] == [s.step for s in result.steps]
    for s in result.steps:
        mine = [r["iteration"] for r in iterations if r["step"] == s.step]
        # Iteration 0 is the residual before the first solve.
        assert s.substeps == 1 and mine == list(range(s.iterations + 1))
    assert steps[-1]["iterations"] == result.steps[-1].iterations
    assert iterations[-1]["residual"] == steps[-1]["residual"]
    assert iterations[-1]["closed"] == int(result.steps[-1].contact["active"].sum())


def test_an_exception_in_the_observer_stops_the_analysis():
    def stop(report):
        if report["kind"] == "iteration" and report["iteration"] == 1:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        hertz.read(EXAMPLES / "hertz_rigid_circle.in").solve(observer=stop)


def test_a_keyboard_interrupt_stops_the_analysis():
    import signal

    def interrupt(report):
        if report["kind"] == "iteration":
            signal.raise_signal(signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        hertz.read(EXAMPLES / "hertz_rigid_circle.in").solve(observer=interrupt)


def same_answer(a, b):
    """Two results with equal displacements, reactions and contact forces, to the last bit."""
    for x, y in zip(a.steps, b.steps):
        assert np.array_equal(x.displacement, y.displacement)
        assert np.array_equal(x.reaction, y.reaction)
        assert np.array_equal(x.contact["force"], y.contact["force"])


def test_youngs_modulus_set_from_python_is_the_inputs():
    model = hertz.read(EXAMPLES / "cantilever.in")
    model.set_material(1, E=2000.0, nu=0.25)
    assert model.materials[1] == {"law": "IsoLE", "E": 2000.0, "nu": 0.25}
    text = (EXAMPLES / "cantilever.in").read_text().replace("E 1000 n 0.3", "E 2000 n 0.25")
    edited = hertz.read_string(text, name="cantilever.in")
    same_answer(model.solve(), edited.solve())
    before = hertz.read(EXAMPLES / "cantilever.in").solve().steps[-1].displacement
    after = model.solve().steps[-1].displacement
    assert not np.allclose(before, after)
    with pytest.raises(ValueError):
        model.set_material(1, E=-1.0)
    with pytest.raises(KeyError):
        model.set_material(7, E=1.0)


def test_a_prescribed_value_set_from_python_is_the_inputs():
    model = hertz.read(EXAMPLES / "wedge_on_brick.in")
    model.set_boundary_condition(4, [0.0, 0.0, -0.005])
    text = WEDGE.replace("values 3 0 0 -0.01", "values 3 0 0 -0.005")
    same_answer(model.solve(), hertz.read_string(text, name="wedge.in").solve())
    force = model.solve().steps[-1].contact["force"]
    full = hertz.read(EXAMPLES / "wedge_on_brick.in").solve().steps[-1].contact["force"]
    # Half the indentation, about half the force (the contact geometry is not linear).
    assert np.allclose(force, full / 2, rtol=1e-3)
    with pytest.raises(ValueError):
        model.set_boundary_condition(4, [0.0, 0.0])


def test_a_penalty_set_from_python_converges_to_the_multipliers_answer():
    model = hertz.read(EXAMPLES / "wedge_on_brick.in")
    exact = model.solve().steps[-1].contact["force"].sum()
    text = WEDGE.replace("n2slagrangianmultipliercontact 5", "n2spenaltycontact 5 penalty 1e3")
    pen = hertz.read_string(text, name="wedge_penalty.in")
    errors = []
    for p in (1e3, 1e4, 1e5):
        pen.set_contact(5, penalty=p)
        errors.append(abs(pen.solve().steps[-1].contact["force"].sum() - exact) / exact)
    # The penalty's error falls as 1/penalty.
    assert errors[0] > errors[1] > errors[2]
    assert errors[1] / errors[2] == pytest.approx(10, rel=0.05)
    with pytest.raises(ValueError):
        model.set_contact(5, penalty=1e3)


def wedge_conditions(floor, axis, side, indenter):
    """examples/wedge_on_brick.in's boundary and contact conditions, each on the set given (its
    number or its name)."""
    return [
        ("BoundaryCondition", {"loadTimeFunction": 2, "dofs": [3], "values": [0], "set": floor}),
        ("BoundaryCondition", {"loadTimeFunction": 2, "dofs": [1, 2], "values": [0, 0], "set": axis}),
        ("BoundaryCondition", {"loadTimeFunction": 2, "dofs": [2], "values": [0], "set": side}),
        (
            "BoundaryCondition",
            {"loadTimeFunction": 1, "dofs": [1, 2, 3], "values": [0, 0, -0.01], "set": indenter},
        ),
        (
            "n2slagrangianmultipliercontact",
            {"loadTimeFunction": 1, "nodeset": [9, 10, 11], "segmentset": [1]},
        ),
    ]


def wedge_from_arrays(text, sets, conditions, name):
    """examples/wedge_on_brick.in (read as `text`) built from its arrays, with `sets` and
    `conditions`."""
    return hertz.from_arrays(
        text.nodes,
        {
            "LSpace": text.elements["LSpace"]["connectivity"],
            "LWedge": text.elements["LWedge"]["connectivity"],
        },
        domain="3d",
        analysis=("StaticStructural", {"nsteps": 1, "deltat": 1, "rtolf": 1e-8, "maxiter": 25}),
        materials=[("IsoLE", {"d": 0, "E": 1000.0, "n": 0.3, "tAlpha": 0})],
        segments=[("linear3delementsurfacecontactsegment", {"boundaryset": 1})],
        conditions=conditions,
        functions=[
            ("PiecewiseLinFunction", {"npoints": 2, "t": [0, 1], "f(t)": [0, 1]}),
            ("ConstantFunction", {"f(t)": 1.0}),
        ],
        sets=sets,
        name=name,
    )


def test_a_model_built_from_arrays_gives_the_text_inputs_answer():
    text = hertz.read(EXAMPLES / "wedge_on_brick.in")
    sets = {n: {k: v for k, v in s.items() if len(v)} for n, s in text.sets.items()}
    built = wedge_from_arrays(text, sets, wedge_conditions(2, 3, 4, 5), "wedge_built")
    a, b = text.solve().steps[-1], built.solve().steps[-1]
    assert np.array_equal(a.reaction, b.reaction)
    assert np.array_equal(a.displacement, b.displacement)
    assert np.array_equal(a.contact["pressure"], b.contact["pressure"])
    assert a.contact["pressure"].min() > 0


def test_a_built_model_with_a_bad_record_names_it():
    with pytest.raises(hertz.InputError) as e:
        hertz.from_arrays(
            [[0.0], [1.0]],
            {"Truss1d": [[1, 2]]},
            domain="1dTruss",
            materials=[("IsoLE", {"d": 0, "E": 1.0, "n": 0.3, "tAlpha": 0})],
            cross_sections=[("SimpleCS", {"area": 1.0})],
            conditions=[("BoundaryCondition", {"loadTimeFunction": 3, "dofs": [1], "values": [0], "set": 1})],
            sets={1: {"nodes": [1]}},
            name="truss_built",
        )
    assert "BoundaryCondition 1" in e.value.record and e.value.file == "truss_built"


def test_writing_never_overwrites_the_input(tmp_path):
    src = tmp_path / "self.in"
    # The input names itself as its output file.
    src.write_text(WEDGE.replace("wedge_on_brick.out", "self.in", 1))
    before = src.read_text()
    with pytest.raises(hertz.HertzError):
        hertz.read(src).solve().write(tmp_path)
    assert src.read_text() == before


def test_points_carry_the_plastic_state():
    """A Mises bar cycled past yield (OOFEM's Mises01): the points' strain and stress at step 6
    are OOFEM's check values, and σ = (1 − ω) E (ε − ε_p) at every step (E = 1)."""
    model = hertz.read(ROOT / "tests" / "data" / "oofem" / "Mises01.in")
    result = model.solve()
    assert result.converged
    step = result.steps[5]
    points = step.points
    assert list(points["element"]) == [1] and list(points["gp"]) == [1]
    assert points["strain"][0, 0] == pytest.approx(4.0, abs=1e-4)
    assert points["stress"][0, 0] == pytest.approx(1.2423, abs=1e-4)
    assert points["kappa"][0] > 0 and 0 < points["damage"][0] < 0.1
    for s in result.steps:
        p = s.points
        elastic = p["strain"][0, 0] - p["plastic_strain"][0, 0]
        assert p["stress"][0, 0] == pytest.approx((1 - p["damage"][0]) * elastic, abs=1e-12)


def test_an_axisymmetric_model_from_arrays_is_the_file_s():
    """OOFEM's axisymm04 ring (four Axisymm3d, pressure 10 on the bore per radian) built from
    arrays gives the file's displacements and its check value u_r(node 1) = 0.820426459."""
    nodes = np.array([[4.0, 0.0], [4.0, 0.1], [4.1, 0.0], [4.1, 0.1], [4.2, 0.0], [4.2, 0.1]])
    model = hertz.from_arrays(
        nodes,
        {"Axisymm3d": [[1, 4, 2], [1, 3, 4], [3, 6, 4], [3, 5, 6]]},
        domain="2dPlaneStress",
        materials=[("IsoLE", {"d": 1.0, "E": 1000.0, "n": 0.0, "tAlpha": 0})],
        conditions=[
            ("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [2], "values": [0.0], "set": 1}),
            ("ConstantEdgeLoad", {"loadTimeFunction": 1, "components": [10.0, 0.0], "set": 2}),
        ],
        sets={1: {"nodes": [1, 3, 5]}, 2: {"boundaries": [[1, 3]]}},
        name="ring",
    )
    built = model.solve().steps[-1].displacement
    read = hertz.read(ROOT / "tests" / "data" / "oofem" / "axisymm04.in").solve().steps[-1].displacement
    assert np.allclose(built, read, rtol=0, atol=1e-15)
    assert built[0, 0] == pytest.approx(0.820426459, abs=1e-6)


def test_a_dynamic_step_carries_velocities_and_energies():
    """examples/rod_impact.in (a rod dropped on a floor at 0.1): before impact every node falls at
    0.1 exactly; the energies balance to round-off; after the rebound the rod rises at 0.1 within
    2 % and keeps its kinetic energy 5e-4 within 0.2 % (with the strain energy of its ringing)."""
    result = hertz.read(EXAMPLES / "rod_impact.in").solve()
    first, last = result.steps[0], result.steps[-1]
    assert first.velocity.shape == first.displacement.shape
    assert np.allclose(first.velocity[:, 1], -0.1, rtol=0, atol=1e-12)
    assert np.allclose(first.acceleration, 0.0, atol=1e-12)
    assert abs(last.energy["balance"]) < 1e-12
    kept = last.energy["kinetic"] + last.energy["internal"]
    assert kept == pytest.approx(5e-4, rel=2e-3)
    assert last.velocity[2:, 1].mean() == pytest.approx(0.1, rel=0.02)
    statics = hertz.read(EXAMPLES / "cantilever.in").solve().steps[-1]
    assert statics.velocity is None and statics.energy is None


def _bar(**changes):
    """The arguments of a two-bar truss model (nodes 1 and 3 held, node 2 pulled by 1)."""
    args = dict(
        nodes=[[0.0], [1.0], [2.0]],
        elements={"Truss1d": [[1, 2], [2, 3]]},
        domain="1dTruss",
        materials=[("IsoLE", {"d": 1.0, "E": 1.0, "n": 0.3, "tAlpha": 0})],
        cross_sections=[("SimpleCS", {"area": 1.0})],
        conditions=[
            ("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [1], "values": [0], "set": 1}),
            ("NodalLoad", {"loadTimeFunction": 1, "dofs": [1], "components": [1.0], "set": 2}),
        ],
        sets={1: {"nodes": [1, 3]}, 2: {"nodes": [2]}},
        name="bar",
    )
    args.update(changes)
    return args


def test_from_arrays_takes_integral_labels_and_refuses_the_rest():
    """Connectivity and set labels as floats that are integers (np.loadtxt's) are the integers;
    5.9, a label beyond 64 bits, a 2-column 3D node array and a newline in a parameter are
    errors that say what is wrong (they were truncated, an AttributeError, "degenerate
    geometry", and an injected record)."""
    u = hertz.from_arrays(**_bar()).solve().steps[-1].displacement
    assert u[1, 0] == pytest.approx(0.5, abs=1e-12)
    floats = _bar(elements={"Truss1d": np.array([[1.0, 2.0], [2.0, 3.0]])})
    floats["sets"] = {1: {"nodes": np.array([1.0, 3.0])}, 2: {"nodes": [2.0]}}
    assert np.array_equal(hertz.from_arrays(**floats).solve().steps[-1].displacement, u)
    for changes, message in [
        ({"sets": {1: {"nodes": [1, 3]}, 2: {"nodes": [5.9]}}}, "labels are integers"),
        ({"elements": {"Truss1d": [[1, 2], [2, 10**30]]}}, "too large"),
        ({"nodes": [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], "domain": "3d"}, "needs nodes with 3"),
        ({"name": "bar\nnode 99 coords 1 0"}, "one line"),
    ]:
        with pytest.raises(ValueError, match=message):
            args = _bar(**changes)
            if "name" in changes:
                args["description"] = args.pop("name")
            hertz.from_arrays(**args)


def test_a_dynamic_model_from_arrays_takes_initial_conditions():
    """The two-bar truss started at velocity 0.1 on its middle node (NonLinearDynamic, Newmark):
    the node oscillates with ω = √(2EA/L / (ρAL)) = √2 about rest, its speed at the start 0.1."""
    args = _bar(
        analysis=("NonLinearDynamic", {"nsteps": 4, "deltat": 0.01, "ddtScheme": 2, "rtolf": 1e-12}),
        conditions=[("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [1], "values": [0], "set": 1})],
        initial_conditions=[("InitialCondition", {"conditions": "1 v 0.1", "set": 2, "dofs": [1]})],
    )
    steps = hertz.from_arrays(**args).solve().steps
    omega = math.sqrt(2.0)
    for s in steps:
        assert s.displacement[1, 0] == pytest.approx(0.1 / omega * math.sin(omega * s.time), rel=1e-4)
    assert steps[0].energy["balance"] == pytest.approx(0.0, abs=1e-15)


def test_points_are_averaged_at_the_nodes():
    """A plate in uniform tension (plane stress, a 2 x 2 patch of bilinear quadrilaterals with a
    skewed middle node) has the exact stress E*eps at every node; the cantilever's nodal average
    at each node is the mean over its elements of each element's mean over its points."""
    text = """plate.out
uniform tension
LinearStatic nsteps 1
domain 2dPlaneStress
OutputManager
ndofman 9 nelem 4 ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 3
node 1 coords 2 0 0
node 2 coords 2 1 0
node 3 coords 2 2 0
node 4 coords 2 0 1
node 5 coords 2 1.2 0.9
node 6 coords 2 2 1
node 7 coords 2 0 2
node 8 coords 2 1 2
node 9 coords 2 2 2
PlaneStress2d 1 nodes 4 1 2 5 4 crossSect 1 mat 1
PlaneStress2d 2 nodes 4 2 3 6 5 crossSect 1 mat 1
PlaneStress2d 3 nodes 4 4 5 8 7 crossSect 1 mat 1
PlaneStress2d 4 nodes 4 5 6 9 8 crossSect 1 mat 1
SimpleCS 1 thick 1.0 material 1 set 1
IsoLE 1 d 0 E 200 n 0.25 tAlpha 0
BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2
BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 3
BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0.02 set 4
ConstantFunction 1 f(t) 1.0
Set 1 allelements
Set 2 nodes 2 4 7
Set 3 nodes 1 1
Set 4 nodes 3 3 6 9
"""
    text = text.replace("nset 3", "nset 4")
    step = hertz.read_string(text).solve().steps[-1]
    nodal = step.points["nodal_stress"]
    assert nodal.shape == (9, 6)
    exact = np.array([200 * 0.01, 0, 0, 0, 0, 0])
    assert np.abs(nodal - exact).max() < 1e-10
    assert np.abs(step.points["nodal_strain"][:, 1] + 0.25 * 0.01).max() < 1e-12

    m = hertz.read(EXAMPLES / "cantilever.in")
    p = m.solve().steps[-1].points
    labels = m.node_labels.tolist()
    around = {}
    for kind in m.elements.values():
        for e, conn in zip(kind["labels"], kind["connectivity"]):
            for n in conn:
                around.setdefault(int(n), []).append(int(e))
    for n, elements in around.items():
        means = [p["stress"][p["element"] == e].mean(axis=0) for e in elements]
        assert np.allclose(p["nodal_stress"][labels.index(n)], np.mean(means, axis=0), rtol=1e-12, atol=1e-12)


def test_records_are_addressed_by_their_set_name():
    # A Gmsh physical group's name names its set: the block's bottom is set 3, where boundary
    # condition 2 pushes it up.
    model = hertz.read(EXAMPLES / "gmsh" / "hertz_gmsh.in")
    bottom = model.set("bottom")
    assert bottom["name"] == "bottom"
    assert np.array_equal(bottom["nodes"], model.sets[3]["nodes"])
    assert model.boundary_conditions[2]["set"] == 3
    by_number = hertz.read(EXAMPLES / "gmsh" / "hertz_gmsh.in")
    model.set_boundary_condition("bottom", 0.03)
    by_number.set_boundary_condition(2, 0.03)
    assert model.boundary_conditions[2]["values"] == [0.03]
    same_answer(model.solve(), by_number.solve())
    with pytest.raises(KeyError, match='"top".*"bottom"'):
        model.set("top")
    with pytest.raises(KeyError, match="no load acts on set 3"):
        model.set_load("bottom", 1.0)
    # Built from arrays, a set's name stands for its number in the records that name a set.
    text = hertz.read(EXAMPLES / "wedge_on_brick.in")
    names = {2: "floor", 3: "axis", 4: "side", 5: "indenter"}
    sets = {n: {k: v for k, v in s.items() if len(v)} for n, s in text.sets.items()}
    for n, name in names.items():
        sets[n]["name"] = name
    conditions = wedge_conditions("floor", "axis", "side", "indenter")
    built = wedge_from_arrays(text, sets, conditions, "wedge_named")
    assert [built.boundary_conditions[k]["set"] for k in (1, 2, 3, 4)] == [2, 3, 4, 5]
    assert built.set("indenter")["name"] == "indenter"
    built.set_boundary_condition("indenter", [0.0, 0.0, -0.005])
    text.set_boundary_condition(4, [0.0, 0.0, -0.005])
    same_answer(text.solve(), built.solve())
    with pytest.raises(KeyError, match="'roof' names no set"):
        hertz.from_arrays(
            text.nodes,
            {"LSpace": text.elements["LSpace"]["connectivity"]},
            domain="3d",
            materials=[("IsoLE", {"d": 0, "E": 1.0, "n": 0.3, "tAlpha": 0})],
            conditions=[("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [3], "values": [0], "set": "roof"})],
            sets=sets,
        )
    sets[3]["name"] = "floor"
    with pytest.raises(ValueError, match="'floor' is set 2's already"):
        hertz.from_arrays(
            text.nodes,
            {"LSpace": text.elements["LSpace"]["connectivity"]},
            domain="3d",
            materials=[("IsoLE", {"d": 0, "E": 1.0, "n": 0.3, "tAlpha": 0})],
            sets=sets,
        )
