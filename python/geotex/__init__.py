"""geotex: the salient details (3D texels) of a mesh and their geometric textures.

    >>> import geotex
    >>> V, F = geotex.read_mesh("sphere.ply")
    >>> seg = geotex.segment(V, F, scale=0.04)
    >>> seg.num_texels, seg.num_textures, seg.texture_of_face

The C++ library does the work (the same calls as the `geotex` command, so the same results);
see the README, section "Python", and help(geotex.segment).
"""

from ._geotex import (
    Error,
    InputError,
    IoError,
    NumericalError,
    ParseError,
    ProcessingError,
    Segmentation,
    UsageError,
    read_mesh,
    segment,
)

__all__ = [
    "Error",
    "InputError",
    "IoError",
    "NumericalError",
    "ParseError",
    "ProcessingError",
    "Segmentation",
    "UsageError",
    "read_mesh",
    "segment",
]
