"""The volume of bodies in every cell of a mesh of polyhedral cells (an
OpenFOAM case, a .vtu, an Eclipse .grdecl corner-point grid):
polyvol/cells.hpp, as `polyvol cells` gives it."""

import numpy as np

from . import _polyvol as _core
from . import _arrays

CellMesh = _core.CellMesh
CellMesh.__doc__ = """A mesh of polyhedral cells in OpenFOAM's form (polyvol/cell_mesh.hpp):
``points`` (n, 3), faces as ``face_offsets`` and ``face_points``, ``owner``
and ``neighbour`` per face (-1 on the boundary), ``cell_count``,
``format``, ``encoding``, ``unit`` (metres for OpenFOAM; a GRDECL file's
unit keyword), ``location``, ``notes``. Corner-point grids also give
``grid_dims`` (I, J, K), ``grid_index`` (each cell's i + I (j + J k): only
active cells are cells) and ``fault_faces``; ``cells_tile`` is False for a
grid with faults (its cells may overlap or leave gaps)."""


def load_cells(path, cell_zone=None, *, map_axes=True):
    """A mesh of cells: an OpenFOAM case directory or its constant/polyMesh
    (ASCII or binary, .gz files), a VTK .vtu unstructured grid (every
    encoding VTK writes), or an Eclipse .grdecl corner-point grid; with
    cell_zone, that OpenFOAM cellZone's cells only (``case_index`` their
    numbers in the case; write_foam_field writes 0 in the others).
    map_axes=False keeps a corner-point grid in its own axes (its MAPAXES,
    applied by default, not applied). Raises ReadError naming the file and
    the line, byte or cell."""
    mesh = _core.read_polymesh(str(path), bool(map_axes))
    return mesh if cell_zone is None else _core.cell_zone(mesh, str(cell_zone))


def cell_volumes(mesh):
    """Each cell's volume, correctly rounded (float64, one per cell), and the
    cells' exact total rounded once. ValueError names a cell whose faces do
    not close."""
    return _core.cell_volumes(mesh)


def write_foam_field(mesh, name, values, time="0"):
    """Writes the values (one per cell) as the dimensionless volScalarField
    CASE/<time>/<name>, keeping the boundaryField of one that exists.
    Returns the path written."""
    values = np.ascontiguousarray(values, dtype=np.float64).reshape(-1)
    return _core.write_foam_field(mesh, str(name), values, str(time))


def write_grdecl_keyword(mesh, path, keyword, values):
    """Writes the values (one per active cell of a corner-point grid) as the
    GRDECL keyword `keyword` over every cell of the grid, I fastest,
    inactive cells 0: an include file for reservoir tools."""
    values = np.ascontiguousarray(values, dtype=np.float64).reshape(-1)
    _core.write_grdecl_keyword(mesh, str(path), str(keyword), values)


def cells(mesh, bodies=(), *, units=None, mesh_units=None, signed=False, orient=False, weld_tolerance=0.0,
          union=False, intersection=False, surface=False):
    """The volume of each body in every cell of ``mesh`` (a CellMesh, or a
    path for load_cells), correctly rounded, as `polyvol cells` gives it.

    bodies: a mesh or a list of them (polyvol.Mesh, or objects with
    .vertices and .faces), each the solid it means as mass_properties takes
    it (NotASolidError for an open or misoriented one; signed, orient,
    weld_tolerance as there). units: the bodies' unit (it overrides, with a
    warning, one a Mesh states, as --units does); mesh_units: the mesh's
    (OpenFOAM: metres); a body in another unit is converted, each
    coordinate rounded once (a warning says so).

    Returns Cells: ``cell_volumes`` (cells,), ``volumes`` and ``fractions``
    (bodies, cells), ``cell_class`` (bodies, cells: 0 empty, 1 full, 2 cut),
    ``inside_mesh`` per body (the exact sum of its cells rounded once: for a
    body inside the mesh, its volume bit for bit; where ``cells_tile`` is
    False, a grid with faults, the body in the region the cells cover, each
    point once), ``cells_sum`` (the cells' values added exactly, rounded
    once), ``in_overlaps`` (cells_sum − inside_mesh: the body counted more
    than once where cells overlap; 0 where they tile, NaN where the covered
    region is not decided), ``body_volumes``, ``full_cells``, ``cut_cells``,
    ``empty_cells`` per body, ``total`` (the cells' volumes added),
    ``covered_volume`` (the region they cover: ``total`` where they tile) and
    ``unit``.

    union=True (two bodies or more): also ``union_volumes`` (cells,) and
    ``union_inside_mesh``, the bodies' union per cell, correctly rounded
    (a boolean per cell where two bodies come near it: slow there); intersection=True
    (two bodies): ``intersection_volumes`` and ``intersection_inside_mesh``,
    within 2 ulp of each cell's volume. Otherwise these are None.
    surface=True: ``wetted_area`` (bodies, cells), ``surface_normal``
    (bodies, cells, 3: ∫ n dA of the body's surface in the cell) and
    ``surface_bound`` (bodies, cells: it holds for the area and each
    component; NaN for a body whose shells overlap), as `polyvol cells
    --surface` gives them."""
    from . import Mesh, _policy, _solid_verdict, _warn, Cells  # noqa: E402 (defined before this module is imported)
    if not isinstance(mesh, CellMesh):
        mesh = load_cells(mesh)
    own, total = _core.cell_volumes(mesh)
    covered = total if mesh.cells_tile else _core.covered_volume(mesh)
    unit = mesh_units or mesh.unit
    if isinstance(bodies, Mesh) or hasattr(bodies, "vertices"):
        bodies = [bodies]
    if union and len(bodies) < 2:
        raise ValueError("union=True needs two bodies or more")
    if intersection and len(bodies) != 2:
        raise ValueError("intersection=True needs exactly two bodies")
    results = []
    for i, body in enumerate(bodies):
        name = f"body {i}" if len(bodies) > 1 else "body"
        p, ix, off = _arrays.mesh(body)
        declared = (body.unit or "") if isinstance(body, Mesh) else ""
        verdict, r, notes = _core.body_in_cells(mesh, p, ix, off, _policy(signed, False, orient, weld_tolerance),
                                                declared, units or "", unit, own, bool(surface))
        for note in notes:
            _warn(f"{name}: {note}")
        _solid_verdict(verdict, name)
        results.append(r)
    joined = met = None
    if union or intersection:
        joined = _core.union_in_cells(mesh, [r["body"] for r in results], own)
    if intersection:
        met = _core.intersection_in_cells(results[0], results[1], joined)
    n = len(own)
    volumes = np.array([r["volumes"] for r in results]).reshape(len(results), n)
    with np.errstate(divide="ignore", invalid="ignore"):
        fractions = np.clip(np.where(own > 0, volumes / own, 0.0), 0.0, 1.0)
    return Cells(unit=unit, cell_volumes=own, total=total, covered_volume=covered, volumes=volumes, fractions=fractions,
                 cell_class=np.array([r["cell_class"] for r in results], dtype=np.uint8).reshape(len(results), n),
                 inside_mesh=[r["inside_mesh"] for r in results], cells_sum=[r["cells_sum"] for r in results],
                 in_overlaps=[r["in_overlaps"] for r in results],
                 cells_tile=mesh.cells_tile, body_volumes=[r["volume"] for r in results],
                 full_cells=[r["full_cells"] for r in results], cut_cells=[r["cut_cells"] for r in results],
                 empty_cells=[r["empty_cells"] for r in results],
                 union_volumes=joined["volumes"] if joined else None,
                 union_inside_mesh=joined["inside_mesh"] if joined else None,
                 intersection_volumes=met[0] if met else None, intersection_inside_mesh=met[1] if met else None,
                 wetted_area=_per_body(results, "wetted_area", surface, (n,)),
                 surface_normal=_per_body(results, "surface_normal", surface, (n, 3)),
                 surface_bound=_per_body(results, "surface_bound", surface, (n,)))


def _per_body(results, key, asked, shape):
    """One array per body stacked (NaN where a body has none: its shells overlap); None unless asked."""
    if not asked:
        return None
    return np.array([r[key] if key in r else np.full(shape, np.nan) for r in results]).reshape((len(results),) + shape)
