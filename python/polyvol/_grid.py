"""polyvol.grid: the exact volume of one or many solids in every cell of a
rectilinear grid (include/polyvol/grid.hpp, docs/grid.md)."""

import os
import warnings

import numpy as np

from . import _arrays
from . import _polyvol as _core


class Grid:
    """Per-cell results of polyvol.grid. Arrays are in C order (i, j, k) with k
    fastest, cell (i, j, k) = [x[i], x[i+1]] × [y[j], y[j+1]] × [z[k], z[k+1]]:

    volumes          (nx, ny, nz) for one mesh, (bodies, nx, ny, nz) for several:
                     each body's exact volume per cell (up to the rounding of its
                     terms: about 2^-50 × cell volume per surface sheet above)
    fractions        volumes / cell volumes, clamped to [0, 1] (each cell is within
                     a few ulps of its volume; not clamped for signed=True)
    union            (nx, ny, nz): the union's volume per cell (several meshes;
                     for one mesh, its volumes), exact in every cell, contact
                     cells included; None when undefined (union_error says why)
    intersection     (nx, ny, nz) when asked for
    cell_class       (nx, ny, nz) uint8: 0 empty, 1 full, 2 cut, 3 contact (several meshes,
                     or one with union=True)
    first_moments    (..., 3) when moments=True: ∫x, ∫y, ∫z of each cell's part
    wetted_area, surface_normal, union_wetted_area, union_surface_normal
                     with surface=True: each surface's area in each cell and ∫ n dA
    edges            (x, y, z): the plane coordinates (of the block, for a block)
    block            ((i0, i1), (j0, j1), (k0, k1)): where these cells lie in the whole grid
    summary          totals and cell counts (the CLI's JSON keys)
    """

    def __init__(self, edges, arrays, summary, bodies, block, signed=False):
        self.edges = edges
        self.signed = signed
        self.block = block
        self.bodies = bodies
        self.summary = summary
        self.union_error = summary.get("union_error")
        one = bodies == 1
        squeeze = (lambda a: a[0]) if one else (lambda a: a)
        self.volumes = squeeze(arrays["volumes"])
        self.first_moments = squeeze(arrays["first_moments"]) if "first_moments" in arrays else None
        self.wetted_area = squeeze(arrays["wetted_area"]) if "wetted_area" in arrays else None
        self.surface_normal = squeeze(arrays["surface_normal"]) if "surface_normal" in arrays else None
        if one:  # one body: the union and the intersection are the body
            self.union = self.intersection = self.volumes
            self.union_wetted_area, self.union_surface_normal = self.wetted_area, self.surface_normal
            self.cell_class = arrays.get("cell_class")
        else:
            self.union = arrays.get("union")
            self.union_wetted_area = arrays.get("union_wetted_area")
            self.union_surface_normal = arrays.get("union_surface_normal")
            self.intersection = arrays.get("intersection")
            self.cell_class = arrays.get("cell_class")

    @property
    def shape(self):
        return tuple(len(e) - 1 for e in self.edges)

    @property
    def cell_volumes(self):
        """(x[i+1]-x[i]) * (y[j+1]-y[j]) * (z[k+1]-z[k]) in double, as the library forms it."""
        dx, dy, dz = (np.diff(e) for e in self.edges)
        return (dx[:, None, None] * dy[None, :, None]) * dz[None, None, :]

    @property
    def fractions(self):
        """Volume fractions (volumes / cell volumes), per body, clamped to [0, 1] unless signed."""
        f = self.volumes / self.cell_volumes
        return f if self.signed else np.clip(f, 0.0, 1.0)

    def to_npy(self, path, what="volumes"):
        """Writes one array (volumes, union, intersection, fractions, ...) as .npy."""
        np.save(path, np.asarray(getattr(self, what)))

    def to_vti(self, path):
        """Writes the per-cell arrays as VTK XML: ImageData (.vti) for a uniform
        grid, RectilinearGrid (.vtr) otherwise (the path's extension is kept)."""
        arrays = []
        vol = self.volumes if self.bodies > 1 else self.volumes[None]
        for b in range(self.bodies):
            suffix = "" if self.bodies == 1 else f"_{b}"
            arrays.append(("volume" + suffix, np.ascontiguousarray(vol[b]).reshape(-1), 1))
            fraction = self.fractions if self.bodies == 1 else self.fractions[b]
            arrays.append(("fraction" + suffix, np.ascontiguousarray(fraction).reshape(-1), 1))
        if self.bodies > 1 and self.union is not None:
            arrays.append(("union_volume", np.ascontiguousarray(self.union).reshape(-1), 1))
        if self.intersection is not None:
            arrays.append(("intersection_volume", np.ascontiguousarray(self.intersection).reshape(-1), 1))
        if self.cell_class is not None:  # written as UInt8, as the CLI writes it
            arrays.append(("cell_class", np.ascontiguousarray(self.cell_class, dtype=np.float64).reshape(-1), 1))
        _core.write_vtk(str(path), *self.edges, arrays, _uniform(self.edges) and not str(path).endswith(".vtr"))

    def to_dict(self):
        """The summary under the CLI's JSON keys."""
        return dict(self.summary)

    def __repr__(self):
        return (f"Grid(shape={self.shape}, bodies={self.bodies}, volume={self.summary['body_volumes']}, "
                f"union_volume={self.summary['union_volume']})")


def _uniform(edges):
    """Equal spacing on every axis up to 1e-9 relative (GridAxes::uniform): a VTK ImageData."""
    return all(np.allclose(np.diff(e), (e[-1] - e[0]) / (len(e) - 1), rtol=1e-9, atol=0) for e in edges)


def _bodies(meshes):
    """(positions, indices, offsets) per body: one mesh (or (vertices, faces)
    pair of arrays), or a list of them."""
    if isinstance(meshes, tuple) and len(meshes) == 2 and isinstance(meshes[0], np.ndarray):
        return [_arrays.mesh(meshes)]
    if isinstance(meshes, (list, tuple)):
        if not meshes:
            raise ValueError("grid: no meshes")
        return [_arrays.mesh(m) for m in meshes]
    return [_arrays.mesh(meshes)]


def _declared_units(meshes):
    """The unit each body's mesh declares ("" for arrays and files that state none)."""
    listed = meshes if isinstance(meshes, (list, tuple)) and not (
        len(meshes) == 2 and isinstance(meshes[0], np.ndarray)) else [meshes]
    return [(getattr(m, "unit", None) or "") if hasattr(m, "_core") else "" for m in listed]


def _in_common_unit(declared, bodies, units, to):
    """The bodies' arrays in one unit (polyvol/units.hpp's common_unit), that
    unit (None when no body's is known) and each body's factor."""
    error, unit, factors, notes = _core.common_unit(declared, units or "", to or "")
    if error:
        hint = ": units= gives it (mm, cm, m, in, ft or micron)" if "not known" in error else ""
        raise ValueError(f"grid: {error}{hint}")
    out = []
    for i, ((v, idx, offsets), f, note) in enumerate(zip(bodies, factors, notes)):
        if note:
            warnings.warn(f"polyvol.grid: body {i}: {note}", stacklevel=4)
        out.append((v * f if f != 1 else v, idx, offsets))
    return out, unit, factors


def axes(meshes, dims=None, cells=None, cell_size=None, bounds=None):
    """The grid planes (x, y, z) polyvol.grid uses for these arguments."""
    return _axes(_bodies(meshes), dims, cells, cell_size, bounds)


def _axes(bodies, dims, cells, cell_size, bounds):
    if sum(a is not None for a in (dims, cells, cell_size)) > 1:
        raise ValueError("give at most one of dims, cells and cell_size")
    d = [0, 0, 0]
    if dims is not None:
        d = [int(n) for n in dims]
        if len(d) != 3 or min(d) < 1 or max(d) > 2 ** 20:
            raise ValueError(f"dims must be three cell counts from 1 to 2^20, not {tuple(dims)}")
    if cells is not None and not 1 <= int(cells) <= 2 ** 20:
        raise ValueError(f"cells must be from 1 to 2^20, not {cells}")
    if cell_size is not None and not float(cell_size) > 0:
        raise ValueError(f"cell_size must be > 0, not {cell_size}")
    b = None
    if bounds is not None:
        b = [float(v) for v in bounds]
        if len(b) != 6:
            raise ValueError("bounds must be (xmin, ymin, zmin, xmax, ymax, zmax)")
    return _core.grid_axes(bodies, 128 if cells is None else int(cells), 0.0 if cell_size is None else float(cell_size),
                           d, b)


def _check_memory(block, bodies, moments, surface, several, intersection, max_memory):
    """MemoryError when the grid's arrays would exceed max_memory (the CLI's
    --max-memory rule): per cell 8 bytes a body, 24 more with moments, 32
    with surface; 9 for the union and classes, 8 for the intersection."""
    cells = 1
    for lo, hi in block:
        cells *= hi - lo
    per_cell = 8 * bodies + (24 * bodies if moments else 0) + (32 * (bodies + several) if surface else 0)
    per_cell += (9 if several else 0) + (8 if several and intersection else 0)
    need = per_cell * cells
    if max_memory is None:
        max_memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") * 3 // 4
    if need > max_memory:
        raise MemoryError(f"polyvol.grid: {cells} cells need about {need / 2**30:.3g} GiB for their arrays, more "
                          f"than max_memory ({max_memory / 2**30:.3g} GiB): polyvol.dask.grid computes a grid in "
                          "blocks, or choose fewer cells")


def grid(meshes, dims=None, cells=None, cell_size=None, bounds=None, moments=False, *, union=None,
         intersection=False, surface=False, block=None, edges=None, signed=False, orient=False, weld_tolerance=0.0,
         max_memory=None, units=None, to=None, device=None):
    """The exact volume of each mesh in every cell of a grid, and with several
    meshes the union's (and on request the intersection's) volume per cell,
    exact in every cell (docs/grid.md).

    meshes: a mesh (polyvol.Mesh, an object with .vertices and .faces) or a
    list of them, each the solid it means as mass_properties takes it
    (inside-out shells turned outward unless signed=True, overlapping shells
    their union: winding number >= 1; open or misoriented surfaces raise
    NotASolidError). The grid: ``dims`` (nx, ny, nz),
    ``cells`` along the longest side (cubic cells, default 128) or
    ``cell_size``; ``bounds`` (xmin, ymin, zmin, xmax, ymax, zmax), default the
    meshes' box padded by a cell; or ``edges`` = (x, y, z) plane coordinates.
    moments: first moments per cell; surface: wetted area and ∫ n dA per cell;
    union (default: with several meshes) and intersection; block:
    ((i0, i1), (j0, j1), (k0, k1)) computes only those cells, with the bits
    the whole grid gives them (polyvol.dask.grid uses it). max_memory (bytes;
    default three quarters of this machine's memory): a grid whose arrays
    would need more raises MemoryError naming the estimate, before anything
    is allocated.

    units, to (`--units`, `--to`): the grid's unit is ``to``, else the first
    body's that is known (units gives the unit of meshes that state none; a
    Mesh read from 3MF or AMF states its own); cell_size, bounds and edges
    are in it, and so is every volume. A body in another unit is converted
    into it, each coordinate rounded once (a warning says so): its cells are
    exact for the coordinates so converted. summary["unit"] names it.

    device: where the cells are computed, "auto" (the CPU), "cpu", "opencl"
    or "opencl:N" (polyvol.devices() lists them); default the POLYVOL_DEVICE
    environment variable, else "auto". Every device gives the same bits;
    summary["device"] says where the cells were computed ("cpu (no OpenCL
    runtime ...)" when OpenCL was asked for and is absent). A device that
    cannot do the work raises polyvol.DeviceError."""
    from . import _policy, _solid_verdict  # noqa: E402 (defined before this module is imported)
    bodies = _bodies(meshes)
    bodies, unit, _ = _in_common_unit(_declared_units(meshes), bodies, units, to)
    solids = [_core.solid_parts(*b, _policy(signed, False, orient, weld_tolerance)) for b in bodies]
    for i, (verdict, _, _) in enumerate(solids):
        _solid_verdict(verdict, f"body {i}" if len(bodies) > 1 else "")
    parts = [s[1] for s in solids]
    if edges is None:
        x, y, z = _axes(bodies, dims, cells, cell_size, bounds)
    else:
        x, y, z = (_arrays.coordinates(np.asarray(e).reshape(-1, 1), columns=1, name="edges").reshape(-1)
                   for e in edges)
    shape = (len(x) - 1, len(y) - 1, len(z) - 1)
    whole = block is None
    if whole:
        block = tuple((0, n) for n in shape)
    block = tuple((int(lo), int(hi)) for lo, hi in block)
    if len(block) != 3 or any(not 0 <= lo < hi <= n for (lo, hi), n in zip(block, shape)):
        raise ValueError(f"block must be three ranges (lo, hi) of cells within the grid {shape}, not {block}")
    flat = [v for pair in block for v in pair]
    several = len(bodies) > 1
    _check_memory(block, len(bodies), moments, surface, several, intersection, max_memory)
    # the union (its crossings) by default with several bodies; union=True also gives one body's cell classes
    want_union = several if union is None else bool(union)
    device = str(device if device is not None else os.environ.get("POLYVOL_DEVICE", "auto"))
    error = None
    try:
        r = _core.grid_volumes(parts, x, y, z, flat, bool(moments), want_union, bool(intersection) and several,
                               bool(surface), device)
    except ValueError as e:
        if not (want_union and union is None and "the union is undefined" in str(e)):
            raise
        # asked by default only: give the bodies' cells, and say why there is no union
        error = str(e)
        warnings.warn(f"polyvol.grid: {error}; the union is not given", stacklevel=2)
        r = _core.grid_volumes(parts, x, y, z, flat, bool(moments), False, False, bool(surface), device)
    # a block is a grid of its own: its planes, with where it lies in the whole grid
    x, y, z = (e[lo:hi + 1] for e, (lo, hi) in zip((x, y, z), block))
    bshape = tuple(hi - lo for lo, hi in block)
    for body, (_, body_parts, solid_volume) in zip(r["bodies"], solids):
        body["mesh_volume"] = (solid_volume if solid_volume is not None
                               else _core.signed_volume(*body_parts[0], "cone", "correctly-rounded"))
    summary = {
        "unit": unit,
        "grid": {"dims": list(bshape), "bounds": [float(x[0]), float(y[0]), float(z[0]), float(x[-1]),
                                                  float(y[-1]), float(z[-1])],
                 "cells": bshape[0] * bshape[1] * bshape[2], "uniform": _uniform((x, y, z))},
        "bodies": r["bodies"],
        "body_volumes": [b["volume"] for b in r["bodies"]],
        "union_volume": None if np.isnan(r["union_volume"]) else r["union_volume"],
        "crossing_pairs": r["crossing_pairs"],
        "full_cells": r["full_cells"], "empty_cells": r["empty_cells"], "cut_cells": r["cut_cells"],
        "contact_cells": r["contact_cells"],
        "device": r["device"],
    }
    if summary["grid"]["uniform"]:
        summary["grid"]["spacing"] = [float(e[-1] - e[0]) / (len(e) - 1) for e in (x, y, z)]
    if not whole:
        summary["grid"]["block"] = [list(p) for p in block]
        summary["grid"]["whole_dims"] = list(shape)
    if not np.isnan(r["intersection_volume"]):
        summary["intersection_volume"] = r["intersection_volume"]
    if error is not None:
        summary["union_error"] = error
    return Grid((x, y, z), r, summary, len(bodies), block, signed=signed)
