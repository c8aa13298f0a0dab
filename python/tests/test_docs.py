"""The documentation's examples run: every Python block of docs/python.md prints what the page
shows after it, and the parameter study of examples/python/penalty_study.py converges to Hertz's
solution and draws its plot."""

import contextlib
import importlib.util
import io
import os
import re

import pytest

from conftest import EXAMPLES, ROOT


def doc_blocks():
    text = (ROOT / "docs" / "python.md").read_text()
    return re.findall(r"```(\w*)\n(.*?)```", text, re.S)


def run_example(name, png):
    """Load examples/python/NAME.py and run its main(png) quietly; its return value."""
    pytest.importorskip("matplotlib")
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / "python" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    with contextlib.redirect_stdout(io.StringIO()):
        return module, module.main(png)


def test_every_python_block_of_the_guide_prints_what_it_shows():
    blocks = doc_blocks()
    ran = 0
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for k, (lang, code) in enumerate(blocks):
            if lang != "python":
                continue
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                exec(compile(code, f"docs/python.md block {k}", "exec"), {})
            ran += 1
            if k + 1 < len(blocks) and blocks[k + 1][0] == "":
                assert out.getvalue() == blocks[k + 1][1], f"block {k}"
    finally:
        os.chdir(cwd)
    assert ran >= 3


def test_the_penalty_study_converges_to_hertz_and_plots(tmp_path):
    png = tmp_path / "study.png"
    study, (model, rows) = run_example("penalty_study", png)
    forces = [r[1] for r in rows]
    # The penalty's error in the force falls about tenfold per decade of penalty.
    steps = [abs(b - a) for a, b in zip(forces, forces[1:])]
    assert steps[0] > 5 * steps[1] > 25 * steps[2]
    material = model.materials[1]
    penalty, force, contact = rows[-1]
    a, p0 = study.hertz_solution(force, material["E"], material["nu"], study.R)
    assert abs(contact["pressure"].max() / p0 - 1) < 0.01
    # The contact zone's edge lies within one element (h = 0.04) of Hertz's half-width.
    closed = contact["x"][contact["pressure"] > 0]
    assert abs(closed.max() - a) < 0.04
    assert png.stat().st_size > 10_000


def test_the_plastic_zone_lies_below_the_imprint_and_is_drawn(tmp_path):
    """examples/python/plastic_zone.py: the imprint the command's test measures (0.0945), the
    largest plastic strain under the contact (within its half-width, 1.48, and no deeper than
    it) and kept after lift-off, and a figure."""
    png = tmp_path / "zone.png"
    _, (imprint, kappa, (x, y)) = run_example("plastic_zone", png)
    assert abs(imprint - 0.0945) < 5e-4
    assert kappa > 0.02 and 0 <= x < 1.48 and -1.48 < y < 0
    assert png.stat().st_size > 10_000


def test_the_crushed_tube_closes_its_bore_and_is_drawn(tmp_path):
    """examples/python/crushed_tube.py: the two plates carry equal and opposite forces at every
    step; no bore node touches until the plates have moved 0.6 (the bore, 1.2 across, closes
    with the walls' thickening), and at the end every bore node but the three at each crease
    does (42 of 48); a figure."""
    png = tmp_path / "tube.png"
    _, (travel, force, below, touching) = run_example("crushed_tube", png)
    assert abs(force - below).max() < 1e-8 * abs(force).max()
    assert all(t == 0 for d, t in zip(travel, touching) if d < 0.55)
    assert touching[-1] == 42
    assert force[-1] > 10 * force[len(force) // 2]
    assert png.stat().st_size > 10_000
