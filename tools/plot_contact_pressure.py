#!/usr/bin/env python3
"""Plot the contact pressure of a Hertz half model from hertz's .contact.csv against Hertz's
p(x) = p0 sqrt(1 - x^2/a^2), as an SVG (no plotting libraries needed).
Usage: plot_contact_pressure.py CSV RADIUS E_STAR OUT.svg"""
import csv
import math
import sys

path, radius, e_star, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
rows = [r for r in csv.DictReader(open(path))]
last = max(int(r["step"]) for r in rows)
pts = [(float(r["x"]), float(r["pressure"]), float(r["force"])) for r in rows if int(r["step"]) == last]
force = 2 * sum(p[2] for p in pts)
a = math.sqrt(4 * force * radius / (math.pi * e_star))
p0 = math.sqrt(force * e_star / (math.pi * radius))
data = [(x, p) for x, p, f in pts if f > 0 and x <= 1.6 * a]
W, H, M = 640, 400, 60
xmax, pmax = 1.6 * a, 1.15 * p0
sx = lambda x: M + (W - 2 * M) * x / xmax
sy = lambda p: H - M - (H - 2 * M) * p / pmax
svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="13">',
       f'<rect width="{W}" height="{H}" fill="white"/>',
       f'<line x1="{M}" y1="{H - M}" x2="{W - M}" y2="{H - M}" stroke="black"/>',
       f'<line x1="{M}" y1="{M}" x2="{M}" y2="{H - M}" stroke="black"/>']
for k in range(5):
    x = xmax * k / 4
    svg.append(f'<text x="{sx(x):.1f}" y="{H - M + 18}" text-anchor="middle">{x:.2f}</text>')
    p = pmax * k / 4
    svg.append(f'<text x="{M - 6}" y="{sy(p) + 4:.1f}" text-anchor="end">{p:.1f}</text>')
curve = " ".join(f"{sx(a * t / 200):.1f},{sy(p0 * math.sqrt(max(0.0, 1 - (t / 200) ** 2))):.1f}" for t in range(201))
svg.append(f'<polyline points="{curve}" fill="none" stroke="#1f77b4" stroke-width="2"/>')
for x, p in data:
    svg.append(f'<circle cx="{sx(x):.1f}" cy="{sy(p):.1f}" r="3.5" fill="#d62728"/>')
svg.append(f'<text x="{W / 2}" y="{H - 15}" text-anchor="middle">x (distance from the centre of contact)</text>')
svg.append(f'<text x="18" y="{H / 2}" text-anchor="middle" transform="rotate(-90 18 {H / 2})">contact pressure</text>')
svg.append(f'<text x="{W - M}" y="{M - 25}" text-anchor="end" fill="#1f77b4">Hertz: p0 = {p0:.2f}, a = {a:.3f}</text>')
svg.append(f'<text x="{W - M}" y="{M - 8}" text-anchor="end" fill="#d62728">hertz nodes (node-to-segment penalty), F = {force:.3f}</text>')
svg.append("</svg>")
open(out, "w").write("\n".join(svg) + "\n")
print(f"F = {force:.4f}, a = {a:.4f}, p0 = {p0:.4f}, {len(data)} nodes -> {out}")
