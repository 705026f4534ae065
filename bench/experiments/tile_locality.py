#!/usr/bin/python3
"""How local is a segmentation? The question behind tiles (issue 21, item 3): does a tile,
its core plus a halo of width H, give the untiled run's depths and texels on its core?

    PYTHONPATH=build/python /usr/bin/python3 bench/experiments/tile_locality.py MESH
        [--scale 0.04] [--halos 2,4,8] [--disc auto]

The core is the half of the faces whose centroid lies below the median along the longest
side of the bounding box; the tile adds every face whose centroid lies within H of it along
that axis (H in multiples of r, the untiled run's radius, which the tile is given as
`radius=`). For each halo, with the rim removal (the default) and without it (keep_rims):
the largest difference of a core vertex's depth, the core faces whose foreground status
differs, how many of the untiled texels' core parts the tile gives exactly (as face sets),
and the global Otsu threshold of each run. Prints a Markdown table; changes no file.
"""

import argparse
import json
import sys
import time

import numpy as np

import geotex


def threshold(seg):
    """The global Otsu threshold of the first orientation (the JSON report's)."""
    return json.loads(seg.to_json())["depth"][0]["global_threshold"]


def pieces(labels, faces):
    """The texels' parts on `faces`, as a set of frozensets of face ids."""
    groups = {}
    for f, label in zip(faces, labels):
        if label >= 0:
            groups.setdefault(int(label), []).append(int(f))
    return {frozenset(g) for g in groups.values()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--scale", type=float, default=0.04)
    ap.add_argument("--halos", default="2,4,8", help="halo widths, multiples of r")
    ap.add_argument("--disc", default="auto")
    a = ap.parse_args()
    V, F = geotex.read_mesh(a.mesh)
    extent = V.max(axis=0) - V.min(axis=0)
    axis = int(np.argmax(extent))
    radius = a.scale * float(extent[axis])
    along = V[F].mean(axis=1)[:, axis]
    cut = float(np.median(along))
    core = np.nonzero(along < cut)[0]
    print(f"{a.mesh}: {len(F):,} faces, r = {radius:.5g}, core: {len(core):,} faces below "
          f"the median along axis {'xyz'[axis]}\n")
    print("| rims | halo | tile faces | core depth max diff | core faces changed | "
          "core texel parts equal | threshold tile / whole | seconds whole, tile |")
    print("|---|---|---|---|---|---|---|---|")
    for keep_rims in (False, True):
        t = time.perf_counter()
        whole = geotex.segment(V, F, radius=radius, disc=a.disc, keep_rims=keep_rims)
        t_whole = time.perf_counter() - t
        whole_label = np.asarray(whole.texel_of_face)
        whole_depth = np.asarray(whole.vertex_depth["positive"])
        whole_parts = pieces(whole_label[core], core)
        for halo in [float(h) for h in a.halos.split(",")]:
            kept = np.nonzero(along < cut + halo * radius)[0]
            used = np.unique(F[kept].ravel())  # ascending: the tile keeps the vertex order
            index = -np.ones(len(V), dtype=np.int64)
            index[used] = np.arange(len(used))
            t = time.perf_counter()
            tile = geotex.segment(V[used], index[F[kept]].astype(np.int32), radius=radius,
                                  disc=a.disc, keep_rims=keep_rims)
            t_tile = time.perf_counter() - t
            if len(tile.V) != len(used):
                sys.exit("tile_locality: the repair changed the tile's vertices")
            # Back to the whole mesh's face ids through the repair's source faces.
            label = -np.ones(len(F), dtype=np.int64)
            label[kept[np.asarray(tile.source_face)]] = np.asarray(tile.texel_of_face)
            core_vertices = np.nonzero(V[used][:, axis] < cut)[0]
            diff = np.abs(np.asarray(tile.vertex_depth["positive"])[core_vertices] -
                          whole_depth[used[core_vertices]])
            changed = int(np.sum((label[core] >= 0) != (whole_label[core] >= 0)))
            equal = len(whole_parts & pieces(label[core], core))
            print(f"| {'kept' if keep_rims else 'removed'} | {halo:g} r | {len(kept):,} | "
                  f"{diff.max():.3g} | {changed:,} | {equal} of {len(whole_parts)} | "
                  f"{threshold(tile):.5g} / {threshold(whole):.5g} | "
                  f"{t_whole:.1f}, {t_tile:.1f} |", flush=True)


if __name__ == "__main__":
    main()
