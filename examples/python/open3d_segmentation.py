#!/usr/bin/python3
"""Segments a mesh with geotex and shows it in Open3D, each face coloured by its texture.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/open3d_segmentation.py MESH \
        [--scale 0.04] [--orientation positive|negative|both] [--screenshot picture.png]

With --screenshot, or without a display, it renders into a PNG instead of opening a window
(under xvfb-run where there is no screen); where Open3D cannot render at all (no display, and
Debian's Open3D has no headless renderer), it writes the coloured mesh as PLY beside the
PNG's name. Needs Debian's python3-open3d (a large package: Open3D is not
a dependency of geotex).
"""

import argparse
import os
import sys

import numpy as np
import open3d as o3d

import geotex

BACKGROUND = (0.75, 0.75, 0.75)


def texture_colours(num_textures):
    """One colour per texture: evenly spaced hues, fully saturated."""
    hues = np.arange(num_textures) / max(num_textures, 1)
    k = (np.array([5, 3, 1])[None, :] + hues[:, None] * 6) % 6
    return 1 - np.clip(np.minimum(k, 4 - k), 0, 1)  # HSV to RGB with S = V = 1


def coloured_mesh(seg):
    """An Open3D mesh with one colour per face. Open3D colours vertices, so each face gets its
    own three corners (3 #F vertices)."""
    V, F = np.asarray(seg.V), np.asarray(seg.F)
    colours = np.vstack([texture_colours(seg.num_textures), BACKGROUND])
    face_colour = colours[seg.texture_of_face]  # -1, the background, takes the last row
    mesh = o3d.geometry.TriangleMesh(
        o3d.utility.Vector3dVector(V[F].reshape(-1, 3)),
        o3d.utility.Vector3iVector(np.arange(3 * len(F), dtype=np.int32).reshape(-1, 3)),
    )
    mesh.vertex_colors = o3d.utility.Vector3dVector(np.repeat(face_colour, 3, axis=0))
    mesh.compute_vertex_normals()
    return mesh


def render_png(mesh, path, size=(800, 800)):
    """A picture without a window: a hidden window of the legacy viewer where there is a display
    (an X server, Xvfb included), else Open3D's headless renderer where it was built with one.
    Raises RuntimeError when neither works."""
    if os.environ.get("DISPLAY"):
        vis = o3d.visualization.Visualizer()
        if vis.create_window(width=size[0], height=size[1], visible=False):
            vis.add_geometry(mesh)
            vis.poll_events()
            vis.update_renderer()
            if os.path.exists(path):
                os.remove(path)  # the test of success below: Open3D 0.16 returns nothing
            vis.capture_screen_image(path, do_render=True)
            vis.destroy_window()
            if os.path.exists(path):
                return
    renderer = o3d.visualization.rendering.OffscreenRenderer(*size)
    material = o3d.visualization.rendering.MaterialRecord()
    material.shader = "defaultLit"
    renderer.scene.set_background([1, 1, 1, 1])
    renderer.scene.add_geometry("mesh", mesh, material)
    box = mesh.get_axis_aligned_bounding_box()
    centre, extent = box.get_center(), box.get_max_extent()
    renderer.setup_camera(45.0, centre, centre + [0, 0, 1.8 * extent], [0, 1, 0])
    o3d.io.write_image(path, renderer.render_to_image())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh")
    ap.add_argument("--scale", type=float, default=0.04)
    ap.add_argument("--orientation", default="positive")
    ap.add_argument("--screenshot", help="PNG to write instead of opening a window")
    a = ap.parse_args()

    try:
        V, F = geotex.read_mesh(a.mesh)
        seg = geotex.segment(V, F, scale=a.scale, orientation=a.orientation)
    except geotex.Error as e:
        sys.exit(f"open3d_segmentation: {e}")
    print(f"{a.mesh}: {seg.num_texels} texels in {seg.num_textures} textures")
    for k, texels in enumerate(seg.texture_texels):
        faces = sum(len(seg.texel_faces[i]) for i in texels)
        print(f"  texture {k} ({seg.texture_orientation[k]}): {len(texels)} texels, {faces} faces")
    mesh = coloured_mesh(seg)

    if a.screenshot is None and os.environ.get("DISPLAY"):
        o3d.visualization.draw_geometries([mesh], window_name=f"geotex: {a.mesh}")
        return
    png = a.screenshot or os.path.splitext(os.path.basename(a.mesh))[0] + "-textures.png"
    try:
        render_png(mesh, png)
        print(f"wrote {png}")
    except RuntimeError:  # no display and no headless renderer (Debian's Open3D has none)
        ply = os.path.splitext(png)[0] + ".ply"
        o3d.io.write_triangle_mesh(ply, mesh)
        print(f"cannot render without a display here; wrote the coloured mesh to {ply} "
              "(open it in MeshLab or Open3D, or run under xvfb-run for a PNG)")


if __name__ == "__main__":
    main()
