"""Inputs as the compiled core takes them: (n, 3) C-contiguous float64
coordinates and uint32 indices. Arrays already in that form (and int32
indices, viewed as uint32 once checked non-negative) are passed on without a
copy; other numeric dtypes are converted when the conversion is exact, and
anything else raises TypeError."""

import numpy as np

_EXACT_INT = 2 ** 53


def coordinates(a, columns=3, name="vertices"):
    """``a`` as a C-contiguous float64 array of shape (n, columns)."""
    x = np.asarray(a)
    kind = x.dtype.kind
    if kind == "f":
        if x.dtype.itemsize > 8:
            y = x.astype(np.float64)
            if not np.array_equal(y, x, equal_nan=True):
                raise TypeError(f"{name}: {x.dtype} values that float64 cannot hold exactly")
            x = y
    elif kind in "iu":
        if x.size and (x.max() > _EXACT_INT or x.min() < -_EXACT_INT):
            raise TypeError(f"{name}: integers beyond 2^53 have no exact float64")
    else:
        raise TypeError(f"{name} must be a numeric array (float or integer), not {x.dtype}")
    if x.ndim != 2 or (columns is not None and x.shape[1] != columns):
        want = f"(n, {columns})" if columns is not None else "(n, dim)"
        raise ValueError(f"{name} must have shape {want}, not {x.shape}")
    return np.ascontiguousarray(x, dtype=np.float64)


def indices(a, vertex_count, name="faces"):
    """Integer indices as a C-contiguous uint32 array (same shape), each in
    [0, vertex_count)."""
    x = np.asarray(a)
    if x.dtype.kind not in "iu":
        raise TypeError(f"{name} must be an integer array, not {x.dtype}")
    if x.size:
        lo, hi = x.min(), x.max()
        if lo < 0 or hi >= vertex_count:
            bad = lo if lo < 0 else hi
            raise ValueError(f"{name}: index {bad} is out of range for {vertex_count} vertices")
    x = np.ascontiguousarray(x)
    if x.dtype in (np.int32, np.uint32):
        return x.view(np.uint32)
    return x.astype(np.uint32)


def faces(f, vertex_count):
    """(indices, offsets) of faces given as an (m, k) integer array (k >= 3)
    or a sequence of index sequences of any lengths >= 3 (offsets None when
    every face is a triangle)."""
    if isinstance(f, np.ndarray) and f.size == 0:
        return np.zeros(0, dtype=np.uint32), None
    if isinstance(f, np.ndarray) or (_rectangular(f) and len(f) > 0):
        x = np.asarray(f)
        if x.dtype.kind in "iu" and x.ndim == 2:
            if x.shape[1] < 3:
                raise ValueError(f"faces must have 3 or more vertices each, not shape {x.shape}")
            idx = indices(x, vertex_count).reshape(-1)
            if x.shape[1] == 3:
                return idx, None
            return idx, np.arange(0, idx.size + 1, x.shape[1], dtype=np.uint32)
        if x.dtype.kind not in "iuO":
            raise TypeError(f"faces must be integer indices, not {x.dtype}")
        if x.dtype.kind != "O":
            raise ValueError(f"faces must have shape (m, k), not {x.shape}")
    sizes = [len(face) for face in f]
    if not sizes:  # no faces: a mesh with nothing to measure
        return np.zeros(0, dtype=np.uint32), None
    if min(sizes) < 3:
        raise ValueError(f"faces must have 3 or more vertices each, not {min(sizes)}")
    flat = np.concatenate([np.asarray(face) for face in f])
    offsets = np.zeros(len(sizes) + 1, dtype=np.uint32)
    np.cumsum(sizes, out=offsets[1:])
    return indices(flat, vertex_count), offsets


def _rectangular(f):
    try:
        return len({len(face) for face in f}) <= 1
    except TypeError:
        return False


def mesh(m, f=None):
    """(positions, indices, offsets) of a polyvol.Mesh, of an object with
    .vertices and .faces (a trimesh.Trimesh), of a (vertices, faces) tuple,
    or of vertices and faces given apart."""
    if f is None:
        core = getattr(m, "_core", None)
        if core is not None:
            return core.vertices, core.indices, core.offsets
        if hasattr(m, "vertices") and hasattr(m, "faces"):
            m, f = m.vertices, m.faces
        elif isinstance(m, tuple) and len(m) == 2:
            m, f = m
        elif isinstance(m, tuple) and len(m) == 3:  # this function's own result
            v = coordinates(m[0])
            idx = indices(m[1], v.shape[0])
            offsets = None if m[2] is None else np.ascontiguousarray(m[2], dtype=np.uint32)
            return v, idx, offsets
        else:
            raise TypeError("expected a polyvol.Mesh, an object with .vertices and .faces, or (vertices, faces)")
    v = coordinates(m)
    idx, offsets = faces(f, v.shape[0])
    return v, idx, offsets
