"""The edit of this folder's rules, made from the mesh of one part: a flange on a planar
ring face of a nut (2025 §7.3). A part of a surface model is one volume (its closed
surface); the extend target glues a second volume, the flange, onto the ring's
triangles (a non-manifold surface model: two parts share those faces); the replace
target is the flanged nut as one closed part again."""
import math

from meshfiles import Points, outward


def _sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def _normal(p):
    """Newell normal of a polygon (unnormalised)."""
    n = [0.0, 0.0, 0.0]
    for a, b in zip(p, p[1:] + p[:1]):
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return n


def flanged(coords, faces, ring, thickness=0.15, widen=0.3):
    """The extend and replace targets for the part (`coords`, its outward `faces`) and
    the indices `ring` of the faces of one planar ring on its boundary.

    The flange is the ring pushed out along its normal by `thickness` (relative to the
    ring's outer radius), the outer boundary widened by `widen`. Returns (points,
    extend_target, replace_target): the extend target is [part, flange] (two volumes
    sharing the ring), the replace target [flanged part] (one volume)."""
    pts = Points()
    for c in coords:  # the part's points keep their indices
        pts.id(c)
    part = [[pts.id(coords[v]) for v in f] for f in faces]
    ring_faces = [part[i] for i in ring]
    ring_vertices = sorted({v for f in ring_faces for v in f})
    n = [sum(c) for c in zip(*(_normal([pts.coords[v] for v in f]) for f in ring_faces))]
    length = math.sqrt(sum(c * c for c in n))
    n = [c / length for c in n]
    centre = [sum(pts.coords[v][i] for v in ring_vertices) / len(ring_vertices) for i in range(3)]

    def radial(v):
        d = _sub(pts.coords[v], centre)
        along = sum(d[i] * n[i] for i in range(3))
        return [d[i] - along * n[i] for i in range(3)]

    radius = {v: math.sqrt(sum(c * c for c in radial(v))) for v in ring_vertices}
    r_in, r_out = min(radius.values()), max(radius.values())
    moved = {}
    for v in ring_vertices:
        grow = widen * (radius[v] - r_in) / (r_out - r_in) if r_out > r_in else 0.0
        d = radial(v)
        scale = grow * r_out / radius[v] if radius[v] > 0 else 0.0
        moved[v] = pts.id([pts.coords[v][i] + thickness * r_out * n[i] + scale * d[i] for i in range(3)])
    directed = {(f[k], f[(k + 1) % len(f)]) for f in ring_faces for k in range(len(f))}
    rim = [(a, b) for a, b in directed if (b, a) not in directed]
    shared = [f[::-1] for f in ring_faces]                    # the ring, seen from the flange
    far = [[moved[v] for v in f] for f in ring_faces]        # the flange's outer face
    sides = [[a, b, moved[b], moved[a]] for a, b in sorted(rim)]
    flange = outward(pts, shared + far + sides)
    others = [f for i, f in enumerate(part) if i not in set(ring)]
    whole = outward(pts, others + far + sides)
    return pts.coords, [part, flange], [whole]
