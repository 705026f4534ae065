"""geotex: the salient details (3D texels) of a mesh and their geometric textures.

    >>> import geotex
    >>> V, F = geotex.read_mesh("sphere.ply")
    >>> seg = geotex.segment(V, F, scale=0.04)
    >>> seg.num_texels, seg.num_textures, seg.texture_of_face
    >>> words = geotex.annotate(seg)            # the built-in dictionary
    >>> [t["label"] for t in words.textures]
    >>> turtle = words.to_turtle()
    >>> report = words.to_json()                # the text of `geotex annotate --json`

The C++ library does the work (the same calls as the `geotex` command, so the same results);
see the README, section "Python", and help(geotex.segment).
"""

from ._geotex import (
    Annotation,
    Error,
    InputError,
    IoError,
    NumericalError,
    ParseError,
    ProcessingError,
    Segmentation,
    UsageError,
    annotate,
    annotate_file,
    read_mesh,
    segment,
)

__all__ = [
    "Annotation",
    "Error",
    "InputError",
    "IoError",
    "NumericalError",
    "ParseError",
    "ProcessingError",
    "Segmentation",
    "UsageError",
    "annotate",
    "annotate_file",
    "read_mesh",
    "segment",
]
