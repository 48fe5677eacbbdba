"""polyvol on Dask: many files as a dataframe, grids larger than one
machine as a dask array of independently computed blocks, and the cells of
a decomposed OpenFOAM case one processor directory a task.

Both run on whatever scheduler is active: the threads of this process by
default, or a dask.distributed cluster (``Client(...)``; docs/python.md shows
``dask scheduler`` / ``dask worker`` and batch systems)."""

import functools
import math
import os

import numpy as np

import dask
import dask.array as da
import dask.dataframe as dd
import pandas as pd

import polyvol
from . import _arrays
from . import _grid

# The dataframe's columns: the keys of `polyvol measure --json` (a key a file
# does not have is None in its row).
COLUMNS = (
    "file", "exit_code", "error", "warning", "format", "encoding", "gzip", "notes", "vertices", "faces",
    "triangles", "vertices_welded", "edges", "boundary_edges", "holes", "nonmanifold_edges", "misoriented_edges",
    "unbalanced_edges", "unbalanced_example", "facet_normals_against_winding", "degenerate_triangles",
    "components", "closed_2_cycle", "euler_characteristic", "cavities", "inside_out_shells", "shells", "method",
    "accuracy", "density", "volume", "volume_error_bound", "mass", "area", "area_relative_error", "centroid",
    "first_moments", "second_moments", "inertia", "inertia_origin", "moments_accuracy", "moments_relative_error",
    "edge_length", "edge_length_relative_error", "overlap_checked", "winding_volume", "overlapping_shells",
    "crossing_pairs", "self_crossing_checked", "self_crossing_pairs", "self_crossing_example",
    "self_crossing_resolved", "turned_outward_faces", "principal_moments", "principal_axes",
    "principal_moment_error", "principal_axis_angle_bound", "bounds", "size", "unit", "mass_unit",
    "length_factor", "weld_tolerance", "welded_points_moved", "weld_largest_move", "parts",
)


# Column types: numbers as float64 (NaN where a file has none), counts as
# nullable integers, the rest (text, flags, lists) as objects.
FLOATS = ("density", "length_factor", "volume", "volume_error_bound", "mass", "area", "area_relative_error",
          "moments_relative_error", "edge_length", "edge_length_relative_error", "winding_volume",
          "principal_moment_error")
COUNTS = ("vertices", "faces", "triangles", "vertices_welded", "edges", "boundary_edges", "holes",
          "facet_normals_against_winding", "nonmanifold_edges", "misoriented_edges", "unbalanced_edges",
          "degenerate_triangles", "components", "euler_characteristic", "cavities", "inside_out_shells",
          "overlapping_shells", "crossing_pairs", "self_crossing_pairs", "turned_outward_faces")


def _typed(frame):
    for c in FLOATS:
        frame[c] = pd.to_numeric(frame[c], errors="coerce").astype("float64")
    for c in COUNTS:
        frame[c] = pd.to_numeric(frame[c], errors="coerce").astype("Int64")
    frame["exit_code"] = frame["exit_code"].astype("int64")
    return frame


def _rows(paths, options):
    rows = [polyvol.measure_file(p, **options) for p in paths]
    return _typed(pd.DataFrame([{c: r.get(c) for c in COLUMNS} for r in rows], columns=list(COLUMNS)))


def _meta():
    frame = pd.DataFrame({c: pd.Series(dtype=object) for c in COLUMNS})
    frame["exit_code"] = 0
    return _typed(frame.iloc[:0])


def measure_files(paths, files_per_partition=16, **options):
    """A dask.dataframe with one row per file: the keys of `polyvol measure
    --json` as columns (COLUMNS), in the order of ``paths``. A file that
    cannot be read or measured gets its exit_code (2 or 3) and error in its
    row; nothing raises. options: density, method, accuracy, allow_open,
    solid (as polyvol.measure_file). Each partition measures
    ``files_per_partition`` files on one worker."""
    paths = [os.fsdecode(p) for p in paths]
    parts = [dask.delayed(_rows)(paths[i:i + files_per_partition], options)
             for i in range(0, len(paths), files_per_partition)]
    if not parts:
        return dd.from_pandas(_meta(), npartitions=1)
    return dd.from_delayed(parts, meta=_meta(), verify_meta=False)


@functools.lru_cache(maxsize=8)
def _read(path):
    """A mesh file read once per worker process: its arrays and declared unit."""
    mesh = polyvol.load(path)
    return _arrays.mesh(mesh), mesh.unit or ""


class _Body:
    """A body's arrays as one value of the graph (a tuple would read as a task)."""

    def __init__(self, arrays):
        self.arrays = arrays


def _block(bodies, factors, edges, block, field, options):
    """One block's cells of one field, computed from the bodies alone (each
    body's coordinates × its factor into the grid's unit, as polyvol.grid does)."""
    meshes = [_read(b)[0] if isinstance(b, str) else b.arrays for b in bodies]
    meshes = [(v * f if f != 1 else v, i, o) for (v, i, o), f in zip(meshes, factors)]
    return np.asarray(getattr(polyvol.grid(meshes, edges=edges, block=block, **options), field))


def _assemble(blocks, counts, axis):
    """The blocks (an array of dask arrays, one per block) joined along the
    grid's three axes, which start at `axis` in each block."""
    return da.concatenate(
        [da.concatenate([da.concatenate([blocks[i, j, k] for k in range(counts[2])], axis=axis + 2)
                         for j in range(counts[1])], axis=axis + 1) for i in range(counts[0])], axis=axis)


def grid(mesh, dims=None, bounds=None, chunks=(256, 256, 256), *, cells=None, cell_size=None, what="volumes",
         union=None, intersection=False, moments=False, units=None, to=None, device=None):
    """The exact per-cell values of polyvol.grid as a dask.array whose blocks
    are computed independently, each from the mesh alone (polyvol.grid's
    block=: only the triangles that reach the block's columns are clipped, and
    the projected area of the surface above it in those columns is summed
    cell by cell as in the whole grid), with the bits the whole grid has; no
    worker ever holds the whole grid.

    mesh: a polyvol.Mesh, (vertices, faces), a path (each worker reads the
    file itself: only the path travels), or a list of them (several bodies).
    dims, bounds, cells, cell_size: the grid, as polyvol.grid chooses it.
    chunks: cells per block along each axis. what: "volumes" ((nx, ny, nz),
    or (bodies, nx, ny, nz)), "fractions" (the same shape, polyvol.Grid's:
    clamped to [0, 1]), "union", "intersection", "cell_class" or
    "first_moments" (a trailing axis of 3). units, to: the grid's unit, as
    polyvol.grid takes them (bounds and cell_size in it; a body in another
    unit converted into it). device: where each block's cells are computed,
    as polyvol.grid takes it (default: each worker's POLYVOL_DEVICE, else
    the CPU); the same bits everywhere. Store with ``.to_zarr(path)``."""
    fields = ("volumes", "fractions", "union", "intersection", "cell_class", "first_moments")
    if what not in fields:
        raise ValueError(f"what must be one of {', '.join(fields)}, not {what!r}")
    meshes = mesh if isinstance(mesh, list) else [mesh]
    paths = [os.fsdecode(m) if isinstance(m, (str, bytes)) or hasattr(m, "__fspath__") else None for m in meshes]
    read = [_read(p) if p else (_arrays.mesh(m), "") for p, m in zip(paths, meshes)]
    declared = [u if p else _grid._declared_units([m])[0] for (_, u), p, m in zip(read, paths, meshes)]
    local, _, factors = _grid._in_common_unit(declared, [a for a, _ in read], units, to)
    x, y, z = _grid._axes(local, dims, cells, cell_size, bounds)  # the planes need the bodies' box, once
    edges = (x, y, z)
    shape = tuple(len(e) - 1 for e in edges)
    chunks = tuple(int(c) for c in chunks)
    # each body travels once: as its path, or as one node of the graph that the blocks share
    # (a path's body is converted on the worker: its factor travels with it)
    bodies = [p if p else dask.delayed(_Body(a), pure=True, traverse=False) for p, a in zip(paths, local)]
    factors = [f if p else 1.0 for p, f in zip(paths, factors)]
    # the union's crossings only where asked for: each block repeats them
    wants_union = what in ("union", "intersection", "cell_class") if union is None else bool(union)
    options = {"union": wants_union, "intersection": intersection or what == "intersection",
               "moments": moments or what == "first_moments", "device": device}
    lead = (len(meshes),) if len(meshes) > 1 and what in ("volumes", "fractions", "first_moments") else ()
    tail = (3,) if what == "first_moments" else ()
    dtype = np.uint8 if what == "cell_class" else np.float64
    counts = [math.ceil(n / c) for n, c in zip(shape, chunks)]
    blocks = np.empty(counts, dtype=object)
    for index in np.ndindex(*counts):
        block = tuple((b * c, min(n, (b + 1) * c)) for b, c, n in zip(index, chunks, shape))
        part = dask.delayed(_block, pure=True)(bodies, factors, edges, block, what, options)
        blocks[index] = da.from_delayed(part, shape=lead + tuple(hi - lo for lo, hi in block) + tail, dtype=dtype)
    return _assemble(blocks, counts, len(lead))


def _processor_cells(directory, bodies, units, options):
    """One processor directory's cells: their places in the whole case, their
    own volumes, and each body's volume and class in each (each body in its
    own unit: the file's, else units=)."""
    mesh = polyvol.load_cells(directory)
    if mesh.cell_count == 0:  # decomposePar leaves some processors empty on small meshes
        empty = np.zeros(0)
        return (np.zeros(0, dtype=np.uint64), empty, [empty for _ in bodies],
                [np.zeros(0, dtype=np.uint8) for _ in bodies], [None for _ in bodies], _mesh_unit(mesh, options))
    if mesh.case_index is None:
        raise polyvol.ReadError(f"{directory}: no constant/polyMesh/cellProcAddressing (decomposePar writes it)")
    results = [polyvol.cells(mesh, [b.arrays], units=u, **options) for b, u in zip(bodies, units)]
    own = results[0].cell_volumes if results else polyvol.cell_volumes(mesh)[0]
    index = np.array(mesh.case_index if mesh.case_index is not None else [], dtype=np.uint64)
    return (index, own, [r.volumes[0] for r in results], [r.cell_class[0] for r in results],
            [r.body_volumes[0] for r in results], _mesh_unit(mesh, options))


def _mesh_unit(mesh, options):
    return options.get("mesh_units") or mesh.unit


def cells(case, bodies=(), *, units=None, mesh_units=None, signed=False, orient=False, weld_tolerance=0.0):
    """polyvol.cells of a decomposed OpenFOAM case (CASE/processorN made by
    decomposePar), one processor directory a task on the active scheduler,
    each reading its own mesh: the values in the whole case's cell order
    (cellProcAddressing), each cell's bit for bit what polyvol.cells gives on
    the whole case (the face rule is one of positions, so each processor
    splits its faces as the whole case does).

    bodies, units, ...: as polyvol.cells (each body travels once, as one node
    of the graph). Returns Cells with ``cell_volumes``, ``volumes``,
    ``fractions``, ``cell_class`` for every cell of the case; ``cells_sum``
    (and ``inside_mesh``, which is it here) the cells' values added exactly,
    rounded once — the whole case's ``cells_sum``, not its exactly rounded
    ``inside_mesh``; ``total`` the cells' own volumes added the same way."""
    directories = polyvol._core.foam_processor_dirs(os.fspath(case))
    if not directories:
        raise ValueError(f"{case}: no processor*/constant/polyMesh: not a decomposed OpenFOAM case")
    if isinstance(bodies, polyvol.Mesh) or hasattr(bodies, "vertices"):
        bodies = [bodies]
    graph_bodies = [dask.delayed(_Body(_arrays.mesh(b)), pure=True, traverse=False) for b in bodies]
    body_units = [(b.unit if isinstance(b, polyvol.Mesh) else None) or units for b in bodies]
    options = {"mesh_units": mesh_units, "signed": signed, "orient": orient, "weld_tolerance": weld_tolerance}
    parts = dask.compute(*[dask.delayed(_processor_cells, pure=True)(d, graph_bodies, body_units, options)
                           for d in directories])
    n = sum(len(p[0]) for p in parts)
    own = np.zeros(n)
    volumes = np.zeros((len(bodies), n))
    cell_class = np.zeros((len(bodies), n), dtype=np.uint8)
    seen = np.zeros(n, dtype=bool)
    for index, part_own, part_volumes, part_class, _, _ in parts:
        if len(index) == 0:
            continue
        if index.max(initial=0) >= n or seen[index].any():
            raise polyvol.ReadError(f"{case}: the processors' cellProcAddressing do not number the cells 0..{n - 1} "
                                    "once each")
        seen[index] = True
        own[index] = part_own
        for b in range(len(bodies)):
            volumes[b, index] = part_volumes[b]
            cell_class[b, index] = part_class[b]
    if not seen.all():
        raise polyvol.ReadError(f"{case}: the processors' cellProcAddressing leave cells out")
    with np.errstate(divide="ignore", invalid="ignore"):
        fractions = np.clip(np.where(own > 0, volumes / own, 0.0), 0.0, 1.0)
    sums = [math.fsum(v) for v in volumes]  # exactly rounded sums, as ExactSum's
    body_volumes = next((list(p[4]) for p in parts if len(p[0]) > 0), [None for _ in bodies])
    total = math.fsum(own)
    return polyvol.Cells(unit=parts[0][5], cell_volumes=own, total=total, covered_volume=total, volumes=volumes,
                         fractions=fractions, cell_class=cell_class, inside_mesh=sums, cells_sum=sums,
                         in_overlaps=[0.0 for _ in bodies], cells_tile=True, body_volumes=body_volumes,
                         full_cells=[int((c == 1).sum()) for c in cell_class],
                         cut_cells=[int((c == 2).sum()) for c in cell_class],
                         empty_cells=[int((c == 0).sum()) for c in cell_class], union_volumes=None,
                         union_inside_mesh=None, intersection_volumes=None, intersection_inside_mesh=None,
                         wetted_area=None, surface_normal=None, surface_bound=None)
