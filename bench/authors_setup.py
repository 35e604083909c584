#!/usr/bin/env python3
"""The authors' set-up side by side (issue 16): octree subdivision with the root cells on
the surface's bounding box (`qmesh subdivide --root box --init X --remove-outside`)
against the authors' own program (`../shared/peers/cgal_hexa_subdivision -init X`),
round-robin (bench/measure.py), on bunny, armadillo and S3 at levels 5-7.

Prints a Markdown table: volumes, hexahedra with hanging vertices ("generic"), face and
volume query-replaces for both tools, the step time (qmesh's subdivision and removal;
the peer's `Subdivision` + `Remove outside`), whole-process wall time and peak memory,
and the ratios peer/qmesh (above 1: qmesh is faster or smaller).

With --transitions, both tools then make the mesh conformal with the authors' 325 + 5
transition patterns (`subdivide --conformal` / `-create-transitions`): the table gives
the cells of each kind, volume replacements and darts of both, and the transitions step
(qmesh's `transitions.seconds`, pattern loading included / the peer's `Create
transitions TOTAL`), then the same without loading the patterns (qmesh's `load_seconds`
/ the peer's `Load transition patterns` subtracted), and qmesh's step once more with
the same patterns compiled once before the table (`qmesh patterns compile`, its time
printed above the table) in the same round-robin.

Step times are medians over the runs of each tool's own report.

With --marching-cubes, qmesh's `marching-cubes SURFACE --root box --init X --levels L`
with the authors' marching-cubes patterns against the peer's `-marching-cubes`: the same
octree, so the same crossed cells; the table gives both tools' counts, the march step
(qmesh's `seconds`: split, replace, surface / the peer's `Compute marching cube
TOTAL`), wall time and memory.

usage: bench/authors_setup.py [--runs N] [--levels 5,6,7] [--init X] [--transitions | --marching-cubes]
                              [--out DIR] [SURFACE...]"""
import argparse
import json
import os
import re
import sys

from common import DATA, MEASURE, Q, ROOT, median, sh
PEER = os.path.join(os.path.dirname(DATA), "peers", "cgal_hexa_subdivision")
SURFACES = ["bunny.off", "armadillo.obj", "cgal_mesh3.off"]


def peer_figures(text):
    """The peer's counts and step seconds from its stdout."""
    num = r"([0-9.eE+-]+)"
    def get(pattern, cast=float, last=False):
        found = re.findall(pattern, text)
        if not found:
            sys.exit(f"peer output without {pattern!r}:\n{text}")
        return cast(found[-1] if last else found[0])
    return {
        "volumes": get(r"\(TOTAL=(\d+)\)", int),
        "generic": get(r"#generic=(\d+)", int),
        "fqr": get(r"#faces-replaced: (\d+)", int, last=True),
        "vqr": get(r"#volumes-replaced: (\d+)", int, last=True),
        "step": get(r"Subdivision: " + num + "s") + get(r"Remove outside: " + num + "s"),
    }


def peer_transitions(text):
    """The peer's cells, volume replacements, darts and step after its transitions."""
    after = text.split("Create transitions TOTAL:")
    if len(after) < 2:
        sys.exit(f"peer output without its transitions:\n{text}")
    kinds = re.search(r"#prisms=(\d+) #pyramids=(\d+) #tetrahedra=(\d+) #hexahedra=(\d+) #generic=(\d+)", after[1])
    prism, pyramid, tet, hexa, other = (int(x) for x in kinds.groups())
    return {
        "cells": {"hex": hexa, "prism": prism, "pyramid": pyramid, "tet": tet, "other": other},
        "vqr": int(re.search(r"#volumes-replaced: (\d+)", after[1]).group(1)),
        "darts": int(re.search(r"#Darts=(\d+)", after[1]).group(1)),
        "step": float(re.match(r"\s*([0-9.eE+-]+)s", after[1]).group(1)),
        "load": float(re.search(r"Load transition patterns: ([0-9.eE+-]+)s", after[0]).group(1)),
    }


def peer_march(text):
    """The peer's replacements, final darts and march step after its marching cubes."""
    after = text.split("Compute marching cube TOTAL:")
    if len(after) < 2:
        sys.exit(f"peer output without its marching cubes:\n{text}")
    fqr, vqr = re.search(r"#faces-replaced: (\d+), #volumes-replaced: (\d+)", after[1]).groups()
    return {
        "fqr": int(fqr), "vqr": int(vqr),
        "faces": int(re.search(r"#2-cells=(\d+)", after[1]).group(1)),
        "step": float(re.match(r"\s*([0-9.eE+-]+)s", after[1]).group(1)),
    }


def march_row(a, stem, src, level, patterns):
    out = os.path.join(a.out, f"{stem}_L{level}_mc.off")
    res = sh(
        sys.executable, MEASURE, str(a.runs),
        "qmesh", "--", Q, "marching-cubes", src, "--root", "box", "--init", str(a.init), "--levels", str(level),
        "--patterns",
        os.path.join(patterns, "marching-cubes"), "-o", out, "--json", "--force", "---",
        "peer", "--", PEER, "-patterns", patterns, "-lmax", str(level), "-init", str(a.init),
        "-marching-cubes", src,
    )
    q, p = [json.loads(line) for line in res.splitlines() if line.strip()]
    qo, po = q["output"], peer_march(p["output"])
    qo["seconds"] = median(q, lambda o: o["seconds"])
    po["step"] = median(p, lambda o: peer_march(o)["step"])
    print(f"| {stem} | {level} | {qo['hexahedra']:,} | {qo['faces_replaced']:,} | {qo['volumes_replaced']:,} "
          f"| {qo['polygons']:,} | {po['fqr']:,} | {po['vqr']:,} | {po['faces']:,} "
          f"| {qo['seconds']:.3f} | {po['step']:.3f} | {po['step'] / qo['seconds']:.1f} "
          f"{wall_and_memory(q, p)}", flush=True)


def transitions_row(a, stem, off, level, patterns, transitions, compiled):
    out = os.path.join(a.out, f"{stem}_L{level}_box.vtk")
    base = [Q, "subdivide", off, "--root", "box", "--init", str(a.init), "--levels", str(level),
            "--remove-outside", "--conformal", "-o", out, "--json", "--force", "--transition-patterns"]
    res = sh(
        sys.executable, MEASURE, str(a.runs),
        "qmesh", "--", *base, transitions, "---",
        "compiled", "--", *base, compiled, "---",
        "peer", "--", PEER, "-patterns", patterns, "-lmax", str(level), "-init", str(a.init),
        "-create-transitions", off,
    )
    q, c, p = [json.loads(line) for line in res.splitlines() if line.strip()]
    qo, po = q["output"], peer_transitions(p["output"])
    qt = qo["transitions"]
    if c["output"]["transitions"]["cell_types"] != qt["cell_types"]:
        sys.exit(f"{stem} L{level}: the compiled set gives other cells than its folders")
    q_step, q_load, c_step = (median(x, lambda o: o["transitions"][k])
                              for x, k in ((q, "seconds"), (q, "load_seconds"), (c, "seconds")))
    p_step, p_load = (median(p, lambda o: peer_transitions(o)[k]) for k in ("step", "load"))
    print(f"| {stem} | {level} | {cells(qt['cell_types'])} | {qt['volumes_replaced']:,} | {qo['darts']:,} "
          f"| {cells(po['cells'])} | {po['vqr']:,} | {po['darts']:,} "
          f"| {q_step:.3f} | {p_step:.3f} | {p_step / q_step:.1f} "
          f"| {q_step - q_load:.3f} | {p_step - p_load:.3f} | {(p_step - p_load) / (q_step - q_load):.1f} "
          f"| {c_step:.3f} | {p_step / c_step:.1f} "
          f"{wall_and_memory(q, p)}", flush=True)


def wall_and_memory(q, p):
    """The table's last columns: both processes' wall time and peak memory, and the
    ratios peer / qmesh."""
    return (f"| {q['seconds']:.2f} | {p['seconds']:.2f} | {p['seconds'] / q['seconds']:.1f} "
            f"| {q['peak_rss_bytes'] / 1e6:.0f} | {p['peak_rss_bytes'] / 1e6:.0f} "
            f"| {p['peak_rss_bytes'] / q['peak_rss_bytes']:.1f} |")


def cells(k):
    return f"{k['hex']:,} / {k['prism']:,} / {k['pyramid']:,} / {k['tet']:,} / {k['other']:,}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--levels", default="5,6,7")
    ap.add_argument("--init", type=int, default=1)
    ap.add_argument("--transitions", action="store_true")
    ap.add_argument("--marching-cubes", action="store_true")
    ap.add_argument("--out", default="/tmp/qmesh-authors-setup")
    ap.add_argument("surfaces", nargs="*")
    a = ap.parse_args()
    if not os.access(PEER, os.X_OK):
        sys.exit(f"{PEER} is missing (see ../shared/peers/README.md)")
    os.makedirs(a.out, exist_ok=True)
    sh("cargo", "build", "--release", "-q", "--manifest-path", os.path.join(ROOT, "Cargo.toml"))
    patterns = os.path.join(DATA, "patterns", "cgal")
    compiled = None
    transitions = ",".join(os.path.join(patterns, p) for p in ("hexa-325-patterns", "square-5-patterns"))
    if a.marching_cubes:
        print("| surface | level | qmesh hexahedra | #fqr | #vqr | surface polygons | peer #fqr | #vqr "
              "| faces (2-cells) | qmesh march s | peer march s | step ratio | qmesh wall s | peer wall s | wall ratio "
              "| qmesh MB | peer MB | memory ratio |")
        print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    elif a.transitions:
        compiled = os.path.join(a.out, "transitions.qps")
        c = json.loads(sh(Q, "patterns", "compile", transitions, "-o", compiled, "--json"))
        print(f"Compiled the {c['f_patterns']} + {c['v_patterns']} transition patterns once: "
              f"{c['seconds']:.3f} s, {c['bytes']:,} bytes.\n")
        print("| surface | level | qmesh hex / prism / pyramid / tet / other | #vqr | darts "
              "| peer hex / prism / pyramid / tet / other | #vqr | darts "
              "| qmesh transitions s | peer transitions s | step ratio | without loading: qmesh s | peer s | ratio "
              "| compiled set: qmesh s | step ratio | qmesh wall s | peer wall s | wall ratio "
              "| qmesh MB | peer MB | memory ratio |")
        print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    else:
        print("| surface | level | qmesh volumes | generic | #fqr | #vqr | peer volumes | generic | #fqr | #vqr "
          "| qmesh step s | peer step s | step ratio | qmesh wall s | peer wall s | wall ratio "
          "| qmesh MB | peer MB | memory ratio |")
        print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for name in a.surfaces or SURFACES:
        src = name if os.path.isabs(name) else os.path.join(DATA, "surface", name)
        stem = os.path.splitext(os.path.basename(src))[0]
        off = src
        if not src.endswith(".off"):  # the peer reads OFF only
            off = os.path.join(a.out, f"{stem}_surface.off")
            sh(Q, "convert", src, off, "--force", "-q")
        for level in [int(x) for x in a.levels.split(",")]:
            if a.marching_cubes:
                march_row(a, stem, off, level, patterns)
                continue
            if a.transitions:
                transitions_row(a, stem, off, level, patterns, transitions, compiled)
                continue
            out = os.path.join(a.out, f"{stem}_L{level}_box.vtk")
            res = sh(
                sys.executable, MEASURE, str(a.runs),
                "qmesh", "--", Q, "subdivide", off, "--root", "box", "--init", str(a.init),
                "--levels", str(level), "--remove-outside", "-o", out, "--json", "--force", "---",
                "peer", "--", PEER, "-patterns", patterns, "-lmax", str(level), "-init", str(a.init), off,
            )
            q, p = [json.loads(line) for line in res.splitlines() if line.strip()]
            qo, po = q["output"], peer_figures(p["output"])
            qo["seconds"] = median(q, lambda o: o["seconds"])
            po["step"] = median(p, lambda o: peer_figures(o)["step"])
            print(f"| {stem} | {level} | {qo['volumes']:,} | {qo['with_hanging_vertices']:,} "
                  f"| {qo['faces_replaced']:,} | {qo['volumes_replaced']:,} "
                  f"| {po['volumes']:,} | {po['generic']:,} | {po['fqr']:,} | {po['vqr']:,} "
                  f"| {qo['seconds']:.3f} | {po['step']:.3f} | {po['step'] / qo['seconds']:.1f} "
                  f"{wall_and_memory(q, p)}", flush=True)


main()
