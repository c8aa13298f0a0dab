"""Models built from arrays: nodes, connectivity and sets as numpy arrays, the other records as
(keyword, parameters) pairs in OOFEM's names. The builder lays them out as the records of an
OOFEM input in memory and reads that with the library's reader, so a built model passes every
check a file does (an error names the record it built)."""

import numbers

import numpy as np

from ._hertz import read_string

_DOMAINS = {"2dPlaneStress", "PlaneStrain", "3d", "2dTruss", "1dTruss"}

# The coordinates each domain's nodes need (a truss's may carry more, in its plane).
_COORDS = {
    "2dPlaneStress": (2, 3),
    "PlaneStrain": (2, 3),
    "3d": (3,),
    "2dTruss": (2, 3),
    "1dTruss": (1, 2, 3),
}


def _labels(values, what):
    """Node, element or set labels as int64: integers, or floats that are integers (what
    np.loadtxt returns); anything else (5.9, 1e30, a string) is an error naming `what`."""
    a = np.asarray(values)
    if a.dtype.kind in "iu":
        if a.dtype.kind == "u" and a.size and a.max() > np.iinfo(np.int64).max:
            raise ValueError(f"{what}: label {a.max()} is too large")
        return a.astype(np.int64)
    flat = a.ravel()
    out = np.empty(flat.shape, dtype=np.int64)
    for k, v in enumerate(flat):
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
            raise ValueError(f"{what}: labels are integers, not {v!r}")
        if v != v or v in (float("inf"), float("-inf")) or int(v) != v:
            raise ValueError(f"{what}: labels are integers, not {v!r}")
        if not -(2**63) <= int(v) < 2**63:
            raise ValueError(f"{what}: label {int(v)} is too large")
        out[k] = int(v)
    return out.reshape(a.shape)


def _value(v):
    """One parameter value as OOFEM text: numbers as themselves (floats round-trip exactly),
    sequences and arrays as a count and the values."""
    if isinstance(v, (bool, np.bool_)):
        return "1" if v else "0"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        return repr(float(v))
    if isinstance(v, str):
        if any(c in v for c in "\n\r") or not v.isprintable():
            raise ValueError(f"{v!r}: a parameter is one line of printable text")
        return v
    a = np.asarray(v).ravel()
    return " ".join([str(a.size)] + [_value(x.item()) for x in a])


def _params(params):
    """`key value` pairs; a value True alone is a flag, None is left out."""
    out = []
    for key, v in (params or {}).items():
        if v is None or v is False:
            continue
        out.append(key if v is True else f"{key} {_value(v)}")
    return " ".join(out)


def _record(keyword, number, params):
    text = f"{keyword} {number}" if number is not None else keyword
    p = _params(params)
    return f"{text} {p}" if p else text


def _pairs(items, what):
    """(keyword, parameters) pairs from a list of pairs or of single-key dicts."""
    out = []
    for k, item in enumerate(items or []):
        if isinstance(item, dict) and len(item) == 1:
            item = next(iter(item.items()))
        if not (isinstance(item, (tuple, list)) and len(item) == 2 and isinstance(item[0], str)):
            raise TypeError(f"{what} {k + 1}: expected (keyword, parameters), not {item!r}")
        out.append((item[0], item[1] or {}))
    return out


# The parameters that refer to a set by its number.
_SET_KEYS = {"set", "slaveset", "masterset", "edgeset", "boundaryset"}


def _set_numbers(sets):
    """Set name -> number of the sets given a "name" (text, unique, not a number)."""
    numbers = {}
    for number, spec in sets.items():
        name = spec.get("name") if isinstance(spec, dict) else None
        if name is None:
            continue
        if (
            not isinstance(name, str)
            or not name
            or '"' in name
            or not name.isprintable()
            or _is_number(name)
        ):
            raise ValueError(
                f"set {number}: a name is one line of text, without quotes and not a number, "
                f"not {name!r}"
            )
        if name in numbers:
            raise ValueError(f"set {number}: the name {name!r} is set {numbers[name]}'s already")
        numbers[name] = number
    return numbers


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _named_sets(keyword, params, numbers):
    """`params` with each set given by name (a str under a set key) replaced by its number."""
    out = dict(params)
    for key, v in params.items():
        if key in _SET_KEYS and isinstance(v, str):
            if v not in numbers:
                known = ", ".join(repr(n) for n in numbers) or "none"
                raise KeyError(f"{keyword}: {key} {v!r} names no set (named: {known})")
            out[key] = numbers[v]
    return out


def from_arrays(*args, **kwargs):
    """A `hertz.Model` from arrays: `input_from_arrays`'s text, read by the library's reader
    (named `name` in messages)."""
    return read_string(input_from_arrays(*args, **kwargs), kwargs.get("name", "model"))


def input_from_arrays(
    nodes,
    elements,
    *,
    domain,
    materials,
    cross_sections=(("SimpleCS", {}),),
    sets=None,
    conditions=(),
    initial_conditions=(),
    functions=(("ConstantFunction", {"f(t)": 1.0}),),
    segments=(),
    analysis=("StaticStructural", {"nsteps": 1}),
    name="model",
    description="built from arrays",
):
    """The OOFEM input text of a model given by arrays (write it to a file to run it with
    `hertz run`; `from_arrays` reads it at once).

    nodes: (n, dim) coordinates; node i has label i + 1.
    elements: element type (OOFEM keyword: "LSpace", "LTRSpace", "LWedge", "PlaneStress2d",
        "Quad1PlaneStrain", "TrPlaneStress2d", "TrPlaneStrain", "QPlaneStress2d", "QPlaneStrain",
        "QTrPlStr", "QTrPlaneStrain", "Truss1d", "Truss2d") -> (m, k) node labels in OOFEM's
        order, or -> dict with "connectivity" and further element parameters ("mat",
        "crossSect", "nlgeo"; default 1, 1, 0). Elements are numbered in that order from 1.
    domain: OOFEM's domain type ("3d", "2dPlaneStress", "PlaneStrain", "2dTruss", "1dTruss").
    materials, cross_sections, conditions (boundary conditions, loads and contact conditions,
        numbered together), initial_conditions (a dynamic analysis's `InitialCondition`s, e.g.
        ("InitialCondition", {"conditions": "1 v -0.1", "set": 2, "dofs": [2]})), functions
        (time functions), segments (contact segments):
        lists of (keyword, parameters), numbered from 1 in order, e.g.
        ("IsoLE", {"d": 0, "E": 1000.0, "n": 0.3, "tAlpha": 0}) or
        ("BoundaryCondition", {"loadTimeFunction": 1, "dofs": [1, 2], "values": [0, 0], "set": 2}).
        A list or array value is written with its count first, as OOFEM's arrays are; True
        alone is a flag.
    sets: set number -> dict of "nodes" (labels), "elements" (labels), "elementboundaries"
        or "boundaries" ((k, 2): element label, boundary number), "elementedges" ((k, 2)),
        and "name" (text, unique): a record's "set", "slaveset", "masterset", "edgeset" or
        "boundaryset" may then give the set's name in place of its number.
    analysis: (analysis keyword, parameters), e.g. ("StaticStructural", {"nsteps": 2}).
    name: the model's name in messages; outputs are named after it.
    """
    nodes = np.asarray(nodes, dtype=float)
    if nodes.ndim != 2 or nodes.shape[1] not in (1, 2, 3):
        raise ValueError(f"nodes must be an (n, 1|2|3) array, not of shape {nodes.shape}")
    if domain not in _DOMAINS:
        raise ValueError(f"domain must be one of {sorted(_DOMAINS)}, not {domain!r}")
    if nodes.shape[1] not in _COORDS[domain]:
        want = " or ".join(str(c) for c in _COORDS[domain])
        raise ValueError(
            f"domain {domain!r} needs nodes with {want} coordinates, not {nodes.shape[1]}"
        )
    lines = [f"{_value(str(name))}.out", _value(str(description))]
    kind, aparams = _pairs([analysis], "analysis")[0]
    lines.append(_record(kind, None, aparams))
    lines.append(f"domain {domain}")
    lines.append("OutputManager tstep_all dofman_all element_all")
    element_lines = []
    for etype, spec in elements.items():
        params = {"mat": 1, "crossSect": 1, "nlgeo": 0}
        if isinstance(spec, dict):
            spec = dict(spec)
            conn = spec.pop("connectivity")
            params.update(spec)
        else:
            conn = spec
        conn = _labels(conn, f"{etype} connectivity")
        if conn.ndim != 2:
            raise ValueError(f"{etype}: connectivity must be an (m, k) array")
        for row in conn:
            number = len(element_lines) + 1
            element_lines.append(_record(etype, number, {"nodes": row, **params}))
    materials = _pairs(materials, "material")
    cross_sections = _pairs(cross_sections, "cross section")
    conditions = _pairs(conditions, "condition")
    initial = _pairs(initial_conditions, "initial condition")
    functions = _pairs(functions, "function")
    segments = _pairs(segments, "segment")
    sets = dict(sets or {})
    if sorted(sets) != list(range(1, len(sets) + 1)):
        raise ValueError(f"sets must be numbered 1..{len(sets)}, not {sorted(sets)}")
    counts = (
        f"ndofman {len(nodes)} nelem {len(element_lines)} ncrosssect {len(cross_sections)} "
        f"nmat {len(materials)} nbc {len(conditions)} nic {len(initial)} nltf {len(functions)} "
        f"nset {len(sets)}"
    )
    if segments:
        counts += f" ncontactseg {len(segments)}"
    lines.append(counts)
    numbers = _set_numbers(sets)
    materials, cross_sections, conditions, initial, segments = (
        [(kw, _named_sets(kw, p, numbers)) for kw, p in group]
        for group in (materials, cross_sections, conditions, initial, segments)
    )
    for i, x in enumerate(nodes):
        lines.append(_record("node", i + 1, {"coords": x}))
    lines.extend(element_lines)
    for k, (kw, p) in enumerate(segments):
        lines.append(_record(kw, k + 1, p))
    for group in (cross_sections, materials, conditions, initial, functions):
        for k, (kw, p) in enumerate(group):
            lines.append(_record(kw, k + 1, p))
    for number in sorted(sets):
        spec, name = {}, None
        for key, v in sets[number].items():
            if key == "name":
                name = v
                continue
            key = "elementboundaries" if key == "boundaries" else key
            spec[key] = _labels(v, f"set {number} {key}")
        record = _record("Set", number, spec)
        if name is not None:
            record += f' name "{name}"'
        lines.append(record)
    return "\n".join(lines) + "\n"
