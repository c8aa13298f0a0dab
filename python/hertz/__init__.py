"""hertz from Python: finite-element contact mechanics from OOFEM input files.

    import hertz
    model = hertz.read("examples/hertz_sphere.in")
    result = model.solve()
    result.steps[-1].reaction        # numpy array, n_nodes x DOFs per node

Everything is solved by the Rust library (the same reader and solver as the `hertz` command);
nothing is printed. See docs/python.md.
"""

from ._hertz import (
    HertzError,
    InputError,
    Model,
    OutputError,
    Result,
    SolveError,
    Step,
    read,
    read_string,
)
from ._build import from_arrays, input_from_arrays

__all__ = [
    "HertzError",
    "InputError",
    "Model",
    "OutputError",
    "Result",
    "SolveError",
    "Step",
    "from_arrays",
    "input_from_arrays",
    "read",
    "read_string",
]
