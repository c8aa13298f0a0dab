#!/usr/bin/env python3
"""Render the deformed outer surface of a hertz .vtu file (ASCII, 3D cells: hexahedra, wedges,
tetrahedra) as an SVG, coloured by a component of the cell stress; Python's standard library only.

Usage: render_vtu.py IN.vtu OUT.svg [--scale S] [--view AZIMUTH ELEVATION] [--component K]
                     [--title TEXT]
  --scale      displacement magnification (default 1)
  --view       viewing direction in degrees (default 35 25)
  --component  stress component 0..5 = xx yy zz yz xz xy (default 2: zz)

Orthographic view, faces drawn back to front (painter's algorithm), Lambert shading on top of a
blue-white-red colour map centred on zero."""
import math
import sys
import xml.etree.ElementTree as ET

# Faces of the VTK cells hertz writes, as local node indices (turned outward when drawn).
FACES = {
    12: [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)],
    13: [(0, 2, 1), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)],
    10: [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)],
}
NAMES = ["xx", "yy", "zz", "yz", "xz", "xy"]


def arrays(path):
    root = ET.parse(path).getroot()
    out = {}
    for da in root.iter("DataArray"):
        out[da.get("Name")] = (int(da.get("NumberOfComponents", "1")), da.text.split())
    return out


def vectors(entry, conv=float):
    k, vals = entry
    vals = [conv(v) for v in vals]
    return [vals[i:i + k] for i in range(0, len(vals), k)] if k > 1 else vals


def colour(t):
    """Blue (t = -1), white (0), red (1)."""
    t = max(-1.0, min(1.0, t))
    if t < 0:
        c = (1 + t, 1 + t, 1.0)
    else:
        c = (1.0, 1 - t, 1 - t)
    return c


def main(argv):
    args = {"--scale": ["1"], "--view": ["35", "25"], "--component": ["2"], "--title": [""]}
    pos = []
    i = 0
    while i < len(argv):
        if argv[i] in args:
            n = len(args[argv[i]])
            args[argv[i]] = argv[i + 1:i + 1 + n]
            i += 1 + n
        else:
            pos.append(argv[i])
            i += 1
    if len(pos) != 2:
        sys.exit(__doc__)
    src, out = pos
    scale = float(args["--scale"][0])
    az, el = (math.radians(float(v)) for v in args["--view"])
    comp = int(args["--component"][0])
    a = arrays(src)
    xs = vectors(a["coordinates"])
    us = vectors(a["displacement"])
    pts = [[x[j] + scale * u[j] for j in range(3)] for x, u in zip(xs, us)]
    conn = [int(v) for v in a["connectivity"][1]]
    offs = [int(v) for v in a["offsets"][1]]
    types = [int(v) for v in a["types"][1]]
    stress = vectors(a["stress"])
    dot = lambda p, q: p[0] * q[0] + p[1] * q[1] + p[2] * q[2]

    def normal(nodes):
        q = [pts[n] for n in nodes]
        e1 = [q[1][k] - q[0][k] for k in range(3)]
        e2 = [q[-1][k] - q[0][k] for k in range(3)]
        return (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0])

    # Faces met once are on the outside.
    seen = {}
    start = 0
    for c, (end, t) in enumerate(zip(offs, types)):
        cell = conn[start:end]
        start = end
        centre = [sum(pts[n][k] for n in cell) / len(cell) for k in range(3)]
        for f in FACES.get(t, []):
            nodes = tuple(cell[k] for k in f)
            # Whatever the cell's handedness, order the face outward from the cell's centre.
            if dot(normal(nodes), [sum(pts[n][k] for n in nodes) / len(nodes) - centre[k]
                                   for k in range(3)]) < 0:
                nodes = nodes[::-1]
            key = tuple(sorted(nodes))
            seen[key] = None if key in seen else (nodes, c)
    faces = [v for v in seen.values() if v is not None]
    # View: x' to the right, y' up, depth along the view direction d.
    d = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
    right = (-math.sin(az), math.cos(az), 0.0)
    up = (d[1] * right[2] - d[2] * right[1], d[2] * right[0] - d[0] * right[2],
          d[0] * right[1] - d[1] * right[0])
    proj = [(dot(p, right), dot(p, up), dot(p, d)) for p in pts]
    lo = [min(p[k] for p in proj) for k in range(2)]
    hi = [max(p[k] for p in proj) for k in range(2)]
    W, M, BAR = 720, 30, 80
    s = (W - 2 * M - BAR) / max(hi[0] - lo[0], hi[1] - lo[1])
    H = int(2 * M + s * (hi[1] - lo[1])) + 30
    X = lambda p: M + s * (p[0] - lo[0])
    Y = lambda p: H - M - s * (p[1] - lo[1])
    vmax = max(abs(stress[c][comp]) for _, c in faces) or 1.0
    light = (0.3 * d[0] + 0.5 * up[0], 0.3 * d[1] + 0.5 * up[1], 0.3 * d[2] + 0.5 * up[2])
    ln = math.sqrt(dot(light, light))
    drawn = []
    for nodes, c in faces:
        nrm = normal(nodes)
        nn = math.sqrt(dot(nrm, nrm)) or 1.0
        # Outward normal: the face is seen when it points towards the viewer.
        if dot(nrm, d) <= 0:
            continue
        shade = 0.55 + 0.45 * abs(dot(nrm, light)) / (nn * ln)
        r, g, b = colour(stress[c][comp] / vmax)
        fill = "#%02x%02x%02x" % tuple(int(255 * v * shade) for v in (r, g, b))
        depth = sum(proj[n][2] for n in nodes) / len(nodes)
        path = " ".join(f"{X(proj[n]):.1f},{Y(proj[n]):.1f}" for n in nodes)
        drawn.append((depth, f'<polygon points="{path}" fill="{fill}"/>'))
    drawn.sort(key=lambda t: t[0])
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           'font-family="sans-serif" font-size="13">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           '<g stroke="#333" stroke-width="0.25" stroke-linejoin="round">']
    svg += [p for _, p in drawn]
    svg.append("</g>")
    # Colour bar.
    bx, by, bh = W - BAR + 10, M + 20, H - 2 * M - 60
    for k in range(40):
        t = 1 - 2 * k / 39
        r, g, b = colour(t)
        svg.append(f'<rect x="{bx}" y="{by + k * bh / 40:.1f}" width="16" height="{bh / 40 + 0.5:.1f}" '
                   f'fill="#{int(255 * r):02x}{int(255 * g):02x}{int(255 * b):02x}"/>')
    for v, yy in ((vmax, by), (0.0, by + bh / 2), (-vmax, by + bh)):
        svg.append(f'<text x="{bx + 20}" y="{yy + 4:.1f}">{v:.3g}</text>')
    svg.append(f'<text x="{bx - 4}" y="{by - 8}">stress {NAMES[comp]}</text>')
    title = args["--title"][0]
    if title:
        svg.append(f'<text x="{M}" y="{H - 10}">{title}</text>')
    svg.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(svg) + "\n")
    print(f"wrote {out}: {len(drawn)} faces, |stress {NAMES[comp]}| up to {vmax:.4g}")


if __name__ == "__main__":
    main(sys.argv[1:])
