#!/usr/bin/env python3
"""Writes the three flower-head surfaces of models/flower.cell: a closed bud, a half-open
and an open head of five petals, all with the same vertices and faces so that `blend`
can interpolate them (paper 000 section 5.2). Surface coordinates: y along the turtle's
heading (the stem), x and z across it. Run from this folder: python3 flower_heads.py"""
import math

RINGS, SEGMENTS, PETALS = 8, 40, 5


def head(opening, curl):
    """opening: angle of the petals from the stem axis at their base, degrees;
    curl: extra bend at the tips, degrees (positive opens further)."""
    points = [(0.0, 0.0, 0.0)]
    for i in range(1, RINGS + 1):
        s = i / RINGS
        for j in range(SEGMENTS):
            phi = 2 * math.pi * j / SEGMENTS
            lobe = 0.55 + 0.45 * abs(math.cos(PETALS * phi / 2))  # five rounded petals
            # Walk along the petal: the angle from the axis grows from opening to
            # opening + curl, so the profile is an arc.
            r = y = 0.0
            steps = 16
            for k in range(steps):
                t = (k + 0.5) / steps * s
                angle = math.radians(opening + curl * t * t)
                r += math.sin(angle) * s * lobe / steps
                y += math.cos(angle) * s * lobe / steps
            points.append((r * math.cos(phi), y, r * math.sin(phi)))
    faces = []
    ring = lambda i, j: 2 + (i - 1) * SEGMENTS + j % SEGMENTS  # 1-based OBJ index
    for j in range(SEGMENTS):
        faces.append((1, ring(1, j + 1), ring(1, j)))
    for i in range(1, RINGS):
        for j in range(SEGMENTS):
            faces.append((ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)))
    return points, faces


for name, opening, curl in [("bud", 12, -8), ("half_open", 45, 10), ("open", 75, 40)]:
    points, faces = head(opening, curl)
    with open(f"head_{name}.obj", "w") as out:
        out.write(f"# flower head, {name.replace('_', ' ')}: written by flower_heads.py\n")
        for p in points:
            out.write("v %.5f %.5f %.5f\n" % p)
        for f in faces:
            out.write("f " + " ".join(str(k) for k in f) + "\n")
