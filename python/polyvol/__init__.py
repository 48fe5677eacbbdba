"""polyvol: exact volume, area, centroid and inertia of polyhedra from their
boundary meshes; the exact volume of solids in every cell of a grid; volumes
of chains in R^n, of plane polygons and of implicit solids.

Units are those of the coordinates: volumes in units³, areas in units²,
moments in units⁴, second moments and inertia in units⁵ (times the density).
Mass properties come with their guarantee: "correctly rounded" (the exact
value for the coordinates as given, rounded once to the nearest double) or
a rigorous error bound; grid cells are exact up to the rounding of their
terms (docs/grid.md); implicit volumes carry an error estimate, not a bound.
Meshes are read exactly as the ``polyvol`` command reads them
(docs/python.md).

    >>> import polyvol
    >>> m = polyvol.load("part.stl")
    >>> p = polyvol.mass_properties(m)
    >>> p.volume, p.centroid, p.inertia
"""

import math as _math
import os as _os
import warnings as _warnings

import numpy as _np

from . import _arrays
from ._errors import DeviceError, ExpressionError, ImplicitError, NotASolidError, ReadError
from ._polyvol import __version__
from . import _polyvol as _core

__all__ = [
    "Mesh", "load", "load_bytes", "measure_file", "orient", "mass_properties", "volume", "check", "solid", "overlap", "self_crossings",
    "grid", "Grid", "chain_volume", "polygon_area", "load_chain", "load_polygons", "implicit",
    "CellMesh", "load_cells", "cell_volumes", "cells", "Cells", "write_foam_field", "write_grdecl_keyword",
    "devices", "ReadError", "ImplicitError", "ExpressionError", "NotASolidError", "DeviceError", "__version__",
]


def _plain(value):
    """Plain Python values as the CLI's JSON holds them (NaN and infinity as None)."""
    if isinstance(value, _np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, _np.generic):
        value = value.item()
    if isinstance(value, float) and not _math.isfinite(value):
        return None
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, _Result):
        return value.to_dict()
    return value


class _Result:
    """A result: its fields as attributes, to_dict() with the CLI's JSON keys."""

    _fields = ()

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def to_dict(self):
        """The fields as plain Python values, under the keys of the CLI's --json."""
        return {k: _plain(getattr(self, k)) for k in self._fields}

    def __repr__(self):
        shown = []
        for k in self._fields:
            v = getattr(self, k)
            if isinstance(v, _np.ndarray):
                v = _np.array2string(v, precision=17, separator=", ").replace("\n", "")
            elif isinstance(v, list) and len(v) > 4:
                v = f"[{len(v)} items]"
            shown.append(f"{k}={v}")
        return f"{type(self).__name__}({', '.join(shown)})"


# ---- meshes ------------------------------------------------------------------

class Mesh:
    """A mesh as read from a file (polyvol.load) or made from arrays
    (Mesh(vertices, faces)). ``vertices`` and the face arrays are read-only
    numpy views of the C++ arrays (no copy)."""

    def __init__(self, vertices=None, faces=None, *, _core_mesh=None):
        if _core_mesh is None:
            v, idx, offsets = _arrays.mesh(vertices, faces)
            _core_mesh = _core.mesh_from_arrays(v, idx, offsets)
        self._core = _core_mesh

    @property
    def vertices(self):
        """(n, 3) float64: the coordinates exactly as read (float32 widened exactly)."""
        return self._core.vertices

    @property
    def is_triangle_mesh(self):
        return self._core.offsets is None

    @property
    def faces(self):
        """(m, 3) uint32 vertex indices, counter-clockwise seen from outside.
        A mesh with other polygons has face_offsets and face_indices instead."""
        if self._core.offsets is not None:
            raise ValueError("this mesh has faces that are not triangles: use face_offsets and face_indices")
        return self._core.indices.reshape(-1, 3)

    @property
    def face_offsets(self):
        """(m + 1,) uint32: face f is face_indices[face_offsets[f]:face_offsets[f + 1]]."""
        if self._core.offsets is None:
            return _np.arange(0, self._core.indices.size + 1, 3, dtype=_np.uint32)
        return self._core.offsets

    @property
    def face_indices(self):
        """The faces' vertex indices, one face after the other (see face_offsets)."""
        return self._core.indices

    format = property(lambda self: self._core.format, doc='"stl", "obj", "off", "ply", "3mf", "amf" or "unknown" (arrays)')
    encoding = property(lambda self: self._core.encoding, doc='"ascii", "binary_le", "binary_be", "zip", "xml"')
    gzip = property(lambda self: self._core.gzip, doc="whether the file was gzip-compressed")
    notes = property(lambda self: self._core.notes, doc="quirks met while reading")
    vertices_in_file = property(lambda self: self._core.vertices_in_file,
                                doc="vertices as the file lists them (STL: three per facet, before welding)")
    unit = property(lambda self: self._core.unit or None,
                    doc='the length unit the file declares ("mm", "cm", "m", "in", "ft", "micron": 3MF, AMF), or None')
    coordinate_error = property(lambda self: self._core.coordinate_error,
                                doc="a bound on |coordinate - the file's value| (3MF transforms), 0 when exact")
    face_count = property(lambda self: self._core.face_count)
    triangle_count = property(lambda self: self._core.triangle_count, doc="fan triangles of the faces")

    def __repr__(self):
        return (f"Mesh(format={self.format!r}, vertices={self.vertices.shape[0]}, faces={self.face_count}, "
                f"triangles={self.triangle_count})")


def load(path):
    """Reads a mesh file: STL (ASCII, binary), OBJ, OFF, PLY, 3MF, AMF, any of
    them gzip-compressed; the format is chosen by content, as the CLI does.
    Raises ReadError (a ValueError) with .path, .line or .offset and .message.
    path: a str, bytes or os.PathLike (names that are not UTF-8 work)."""
    return Mesh(_core_mesh=_core.load(_os.fsencode(path)))


def load_bytes(data, name="memory"):
    """Reads a mesh from bytes; ``name`` appears in errors and its extension is a hint."""
    return Mesh(_core_mesh=_core.load_bytes(bytes(data), name))


def measure_file(path, *, density=1.0, method="cone", accuracy="correctly-rounded", allow_open=False, solid=False,
                 orient=False, signed=False, weld_tolerance=0.0, units=None, to=None, scale=1.0, mass_unit="kg"):
    """Everything `polyvol measure --json FILE` reports for one file, as a dict
    with its keys (the library's report, polyvol/report.hpp, whose keys the
    CLI prints too): format and counts, topology and shells, the mass
    properties with their guarantees (of the solid when shells overlap),
    and exit_code with error or warning when the file cannot be read (2) or
    measured (3). Never raises for a bad file.
    solid=True looks for a surface crossing itself at any size (--solid);
    orient=True winds the faces consistently and outward first (--orient).
    A shell that is inside out is turned outward (turned_outward_faces) unless
    signed=True (--signed). weld_tolerance > 0 merges the points within it
    first (--weld-tolerance; the report says what moved). units gives the
    coordinates' unit ("mm", "cm", "m", "in", "ft", "micron"; 3MF and AMF
    files state theirs), to the unit of the figures, scale multiplies every
    coordinate first (--units, --to, --scale); a conversion widens the
    guarantees by its rounding (keys unit, length_factor). density: a number,
    or a text with its unit ('2700kg/m3', '1.24g/cm3'; figures then in
    metres unless to= says otherwise), the mass then in mass_unit (kg, g,
    lb), as --density and --mass-unit."""
    if not isinstance(density, str):
        density = float(density)
    report = _core.measure_file_report(_os.fsencode(path), method, accuracy, density, mass_unit, bool(allow_open),
                                       bool(solid), bool(orient), bool(signed), float(weld_tolerance), units or "",
                                       to or "", float(scale))
    report["file"] = _os.fsdecode(path)
    return FileReport(report)


class FileReport(dict):
    """One file's report (polyvol/report.hpp): a dict with the keys of
    `polyvol measure --json` (report_json declares them once), each also an
    attribute: r["volume"] is r.volume."""

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None


class Orientation(_Result):
    """What orient() did: faces_flipped, shells, undecided (shells left as wound:
    their outward side could not be decided, or non-manifold edges cut them open)."""

    _fields = ("orientable", "faces_flipped", "shells", "undecided")


def orient(mesh, faces=None):
    """A copy of the mesh with its faces wound consistently within each shell,
    outer shells outward and cavities inward by nesting (`--orient`), and an
    Orientation saying what changed. Raises ValueError when a shell cannot be
    oriented (an edge shared by three or more faces, a Möbius strip)."""
    v, idx, offsets = _arrays.mesh(mesh, faces)
    core, report = _core.orient(v, idx, offsets)
    if not report["orientable"]:
        raise ValueError("orient: a shell is not orientable (an edge used twice in one direction that no flip "
                         "fixes, or by three or more faces)")
    return Mesh(_core_mesh=core), Orientation(**report)


# ---- mass properties -----------------------------------------------------------

class MassProperties(_Result):
    """Mass properties of a mesh (the cone rule's sums, measure.hpp); ``accuracy``
    is the volume's guarantee, "correctly-rounded" or "error-bound", as in the
    CLI's JSON:
    volume, mass = density * volume, area, centroid (3,), first_moments (3,),
    second_moments (3, 3) = density * ∫x_i x_j about the origin, inertia (3, 3)
    about the centroid, inertia_origin (3, 3), principal_moments (3,)
    increasing with principal_axes (3, 3) (row k the unit axis of moment k,
    right-handed), edge_length, bounds (xmin, ymin, zmin, xmax, ymax, zmax)
    of the vertices the faces use; unit (the lengths' unit, or None when not
    known), mass_unit (with a density with a unit), length_factor (the
    coordinates' factor to unit) and density (mass per unit³ used); and the
    guarantees: volume_correctly_rounded (else volume_error_bound, absolute),
    moments_correctly_rounded (else moments_relative_error), area_relative_error,
    edge_length_relative_error, principal_moment_error (absolute, each
    moment), principal_axis_angle_bound (radians, each axis; inf where
    moments are equal)."""

    _fields = ("method", "accuracy", "unit", "mass_unit", "length_factor", "density", "volume",
               "volume_error_bound", "mass", "area", "area_relative_error", "centroid", "bounds", "first_moments",
               "second_moments", "inertia", "inertia_origin", "moments_accuracy", "moments_relative_error",
               "principal_moments", "principal_axes", "principal_moment_error", "principal_axis_angle_bound",
               "edge_length", "edge_length_relative_error")


def _solid_verdict(verdict, name=""):
    """Raises NotASolidError for a refused mesh; warns the policy's notes."""
    status, message, notes = verdict
    for note in notes:
        _warn((name + ": " if name else "") + note)
    if status != "ok":
        raise NotASolidError((name + ": " if name else "") + message, status, message)


def _policy(signed, allow_open, orient, weld_tolerance, solid=True):
    return {"signed": bool(signed), "allow_open": bool(allow_open), "orient": bool(orient),
            "weld_tolerance": float(weld_tolerance), "solid": bool(solid)}


def _units(mesh, units, to, mass_unit):
    """The units keywords for the bindings: the file's own unit when the mesh has one."""
    declared = mesh.unit if isinstance(mesh, Mesh) else None
    return {"declared": declared or "", "units": units or "", "to": to or "", "mass_unit": mass_unit}


def mass_properties(mesh, faces=None, *, density=1.0, method="cone", accuracy="correctly-rounded",
                    second_moments=True, edge_length=True, signed=False, allow_open=False, orient=False,
                    weld_tolerance=0.0, solid=True, units=None, to=None, mass_unit="kg"):
    """Volume, mass, area, centroid, moments, inertia and edge length of the
    solid a closed mesh means (a polyvol.Mesh, an object with .vertices and
    .faces, or vertices and faces arrays), as `polyvol measure` takes it:
    inside-out shells turned outward (a warning says so; signed=True keeps
    their signed sums), overlapping and self-crossing shells resolved (the
    solid's volume, mass, moments and area: winding number >= 1; edge
    length the shells' sum), an open or misoriented surface refused with
    NotASolidError (allow_open=True measures it about the origin;
    orient=True winds the faces first; weld_tolerance merges points first;
    solid=False keeps the shells' sums where they overlap: ∫ winding number).

    Units (`--units`, `--to`, `--density`, `--mass-unit`): units is the
    coordinates' unit ("mm", "cm", "m", "in", "ft", "micron"; a Mesh read
    from 3MF or AMF states its own), to the unit of the figures (default:
    the coordinates'; metres with a density with a unit). density is a
    number (mass per unit³) or a text with its unit, '2700kg/m3' or
    '1.24g/cm3': the mass is then in mass_unit ("kg", "g" or "lb"). A
    conversion that is not exact widens each guarantee by its rounding.

    method: "cone" (det/6 per fan triangle), "prism", "pyramid" or "vtnb"
    (Franklin's vertex-edge-face formula); it chooses the volume only.
    accuracy: "correctly-rounded" (the exact value rounded once: volume,
    mass, moments, centroid, inertia) or "fast" (double sums with a rigorous
    bound). Area and edge length always carry a relative bound."""
    v, idx, offsets = _arrays.mesh(mesh, faces)
    if not isinstance(density, str):
        density = float(density)
    verdict, p, u = _core.measure_solid(v, idx, offsets, method, accuracy, density, second_moments, edge_length,
                                        _policy(signed, allow_open, orient, weld_tolerance, solid),
                                        _units(mesh, units, to, mass_unit))
    if u["warning"]:
        _warn(u["warning"])
    _solid_verdict(verdict)
    nan3 = _np.full(3, _np.nan)
    return MassProperties(
        method=p.method, accuracy="correctly-rounded" if p.volume_correctly_rounded else "error-bound",
        unit=u["unit"], mass_unit=u["mass_unit"], length_factor=u["length_factor"], density=u["density"],
        volume=p.volume, volume_correctly_rounded=p.volume_correctly_rounded, volume_error_bound=p.volume_error_bound,
        mass=p.mass, area=p.area, area_relative_error=p.area_relative_error, centroid=p.centroid,
        bounds=u["bounds"], first_moments=p.first_moments,
        second_moments=p.second_moments, inertia=p.inertia, inertia_origin=p.inertia_origin,
        moments_correctly_rounded=p.moments_correctly_rounded,
        moments_accuracy="correctly-rounded" if p.moments_correctly_rounded else "error-bound",
        moments_relative_error=p.moments_relative_error,
        principal_moments=u.get("principal_moments", nan3),
        principal_axes=u.get("principal_axes", _np.full((3, 3), _np.nan)),
        principal_moment_error=u.get("principal_moment_error", _np.nan),
        principal_axis_angle_bound=u.get("principal_axis_angle_bound", nan3),
        edge_length=p.edge_length, edge_length_relative_error=p.edge_length_relative_error)


def volume(mesh, faces=None, *, method="cone", accuracy="correctly-rounded", signed=False, allow_open=False,
           orient=False, weld_tolerance=0.0, units=None, to=None):
    """The volume of the solid the mesh means, correctly rounded by default,
    with mass_properties' policy (signed=True: an inside-out surface keeps
    its negative volume) and units (in to³ from coordinates in units)."""
    return mass_properties(mesh, faces, method=method, accuracy=accuracy, second_moments=False, edge_length=False,
                           signed=signed, allow_open=allow_open, orient=orient,
                           weld_tolerance=weld_tolerance, units=units, to=to).volume


# ---- topology --------------------------------------------------------------------

class Shell(_Result):
    """An edge-connected component: signed_volume (correctly rounded; None
    for an open shell, whose volume depends on the origin), faces,
    boundary_edges, unbalanced_edges, euler_characteristic, genus (None
    unless defined), winding_of_others (the other shells' winding number at
    a point of it) and role: "solid", "cavity", "inside-out", "nested", "open",
    "crossing" (crosses another shell: solid() resolves it) or "undecided"."""

    _fields = ("role", "signed_volume", "faces", "boundary_edges", "unbalanced_edges", "euler_characteristic",
               "genus", "winding_of_others")


class Topology(_Result):
    """What `polyvol check` reports. ``closed`` is True when the surface is a
    closed 2-cycle (no unbalanced edge: its volume does not depend on the
    origin); ``misoriented_edges`` counts edges used twice in one direction;
    ``holes`` the boundary loops."""

    _fields = ("closed_2_cycle", "faces", "triangles", "vertices", "vertices_welded", "edges", "boundary_edges",
               "holes", "nonmanifold_edges", "misoriented_edges", "unbalanced_edges", "unbalanced_example",
               "degenerate_triangles", "euler_characteristic", "components", "cavities", "inside_out_shells",
               "shells", "self_crossing_checked", "self_crossing_pairs", "self_crossing_example", "ready",
               "repairs", "solid_volume", "winding_volume", "overlapping_shells", "crossing_pairs")

    def to_dict(self):
        d = super().to_dict()
        for key in ("unbalanced_example", "self_crossing_example", "solid_volume", "winding_volume",
                    "overlapping_shells", "crossing_pairs"):  # the CLI writes them only when there is one
            if d[key] is None:
                del d[key]
        return d


def check(mesh, faces=None, *, shells=True, self_crossings=True):
    """The topology report of `polyvol check`: edge counts, components,
    shells with their volumes and nesting (shells=False: the edge counts only),
    and for a closed surface whether it crosses itself (self_crossings=False:
    not looked for). ``closed``: a closed 2-cycle; ``nested_shells``: shells
    inside another solid shell. to_dict() has the keys of `polyvol check --json`."""
    v, idx, offsets = _arrays.mesh(mesh, faces)
    t = _core.topology(v, idx, offsets, shells)
    crossings = None
    if self_crossings and t.closed_2_cycle:
        s = _core.self_crossings(v, idx, offsets)
        crossings = s if s.status == "ok" else None
    core = getattr(mesh, "_core", None) if faces is None else None
    # Shells of a closed surface in several parts that cross one another are
    # "crossing" (as `polyvol check` says; solid() gives the solid they bound).
    crosses = None
    if t.closed_2_cycle and t.components_vertex_connected > 1:
        s = _core.solid_volume(v, idx, offsets, False)
        if s.status == "ok" and s.face_crosses.size:
            crosses = s.face_crosses
    # The verdict of `polyvol check`: a solid as it is, or the repairs it needs.
    _, repairs, solid_figures = _core.solid_repairs(v, idx, offsets)
    example = None
    if t.unbalanced_example is not None:
        e = t.unbalanced_example
        example = [[e[0], e[1], e[2]], [e[3], e[4], e[5]]]
    return Topology(
        closed=t.closed_2_cycle, closed_2_cycle=t.closed_2_cycle, faces=t.faces, triangles=t.triangles,
        vertices=core.vertices_in_file if core is not None else int(v.shape[0]),
        self_crossing_checked=crossings is not None,
        self_crossing_pairs=crossings.pairs if crossings is not None else None,
        self_crossing_example=list(crossings.example) if crossings is not None and crossings.example else None,
        vertices_welded=t.vertices_welded, edges=t.edges, boundary_edges=t.boundary_edges,
        holes=t.holes, nonmanifold_edges=t.nonmanifold_edges, misoriented_edges=t.misoriented_edges,
        unbalanced_edges=t.unbalanced_edges, unbalanced_example=example,
        degenerate_triangles=t.zero_area_triangles,  # those with a repeated vertex included
        euler_characteristic=t.euler_characteristic, components=t.components_edge_connected, cavities=t.cavities,
        inside_out_shells=t.inside_out_shells, nested_shells=t.nested_shells,
        ready=not repairs, repairs=list(repairs),
        **{k: solid_figures.get(k) for k in ("solid_volume", "winding_volume", "overlapping_shells", "crossing_pairs")},
        shells=[Shell(role="crossing" if crosses is not None and crosses[s.first_face] else s.role,
                      signed_volume=None if s.role == "open" else s.signed_volume,  # depends on the origin
                      faces=s.faces, boundary_edges=s.boundary_edges,
                      unbalanced_edges=s.unbalanced_edges, euler_characteristic=s.euler_characteristic,
                      genus=s.genus, winding_of_others=s.winding_of_others) for s in t.shells])


# ---- overlapping shells and booleans ------------------------------------------------

class SolidVolume(_Result):
    """The solid a mesh with overlapping shells bounds (winding number >= 1,
    what a slicer prints): volume correctly rounded, winding_volume (the sum
    of the shells' volumes, what mass_properties gives), the counts of
    overlapping shells and crossing triangle pairs, and of triangle pairs
    crossing within a shell (resolved); with moments, its
    first_moments and second_moments (correctly rounded), centroid (relative
    error < 2^-51) and inertia about the centroid (inertia_relative_error)."""

    _fields = ("status", "volume", "winding_volume", "shells", "overlapping_shells", "crossing_pairs",
               "self_crossing_checked", "self_crossing_pairs", "shells_crossing_themselves",
               "centroid", "first_moments", "second_moments", "inertia", "inertia_relative_error")


def solid(mesh, faces=None, *, moments=True, within_shells=True):
    """Volume (and mass properties) of the region where the winding number of
    the mesh's shells is >= 1, shells crossing themselves included
    (within_shells=False skips looking for those, about 3.5x what measuring
    costs, and then counts a shell's self-overlap by its winding number).
    Raises ValueError when it is undefined (an open mesh, a shell that crosses
    itself and also touches or folds onto itself)."""
    v, idx, offsets = _arrays.mesh(mesh, faces)
    s = _core.solid_volume(v, idx, offsets, moments, within_shells)
    if s.status != "ok":
        raise ValueError(f"no solid: {s.message}")
    return SolidVolume(status=s.status, volume=s.volume, winding_volume=s.winding_volume, shells=s.shells,
                       overlapping_shells=s.overlapping_shells, crossing_pairs=s.crossing_pairs,
                       self_crossing_checked=s.within_checked, self_crossing_pairs=s.self_crossing_pairs,
                       shells_crossing_themselves=s.shells_crossing_themselves,
                       centroid=s.centroid if moments else None, first_moments=s.first_moments if moments else None,
                       second_moments=s.second_moments if moments else None,
                       inertia=s.inertia if moments else None,
                       inertia_relative_error=s.inertia_relative_error if moments else None)


class BooleanVolumes(_Result):
    """Volumes of A, B, A∩B, A∪B, A−B, B−A (each correctly rounded, or
    within volume_error_bound when accuracy is "error-bound") and the areas
    of their boundaries (each within area_error_bound), in unit."""

    _fields = ("unit", "volume_a", "volume_b", "intersection", "union", "a_minus_b", "b_minus_a", "accuracy",
               "volume_error_bound", "area_a",
               "area_b", "area_intersection", "area_union", "area_a_minus_b", "area_b_minus_a", "area_error_bound",
               "triangles_a", "triangles_b", "candidate_pairs", "crossing_pairs", "rational_terms")


def overlap(a, b, *, signed=False, orient=False, weld_tolerance=0.0, units=None, to=None):
    """Volumes of the booleans of the solids two closed meshes mean, exactly,
    without building them (`polyvol overlap`): each operand as
    mass_properties takes it (inside-out shells turned outward, overlapping
    shells resolved: then the areas of A − B and B − A are NaN). Raises
    NotASolidError when an operand is not a solid (open, misoriented),
    ValueError for the rest (inside out with signed=True, coordinates out of
    range, a unit not known).

    units: the coordinates' unit of operands that state none (a Mesh read
    from 3MF or AMF states its own; B in another unit than A is converted
    into A's, each coordinate rounded once); to: the unit of the figures
    (`--units`, `--to`). accuracy is "correctly-rounded", or "error-bound"
    after a conversion that is not exact (each volume within
    volume_error_bound); unit names the figures' unit (None when not known)."""
    pa, ia, oa = _arrays.mesh(a)
    pb, ib, ob = _arrays.mesh(b)
    units_kw = {"declared_a": (a.unit or "") if isinstance(a, Mesh) else "",
                "declared_b": (b.unit or "") if isinstance(b, Mesh) else "",
                "error_a": a.coordinate_error if isinstance(a, Mesh) else 0.0,
                "error_b": b.coordinate_error if isinstance(b, Mesh) else 0.0,
                "units": units or "", "to": to or ""}
    va, vb, r, unit, notes = _core.overlap_solids(pa, ia, oa, pb, ib, ob, _policy(signed, False, orient, weld_tolerance),
                                                  units_kw)
    for note in notes:
        _warn(note)
    _solid_verdict(va, "A")
    _solid_verdict(vb, "B")
    if r.status != "ok":
        raise ValueError(f"no boolean volumes: {r.message}")
    return BooleanVolumes(accuracy="correctly-rounded" if r.volume_error_bound == 0 else "error-bound", unit=unit,
                          **{k: getattr(r, k) for k in BooleanVolumes._fields if k not in ("accuracy", "unit")})


class SelfCrossings(_Result):
    """Pairs of triangles of one body that share no vertex and cross."""

    _fields = ("pairs", "candidate_pairs", "example")


def self_crossings(mesh, faces=None):
    """Where a mesh's surface crosses itself (exact predicates): the number of
    crossing triangle pairs and one example as (face, face)."""
    v, idx, offsets = _arrays.mesh(mesh, faces)
    s = _core.self_crossings(v, idx, offsets)
    if s.status != "ok":
        raise ValueError("self_crossings: a coordinate is not finite or out of the predicates' range")
    return SelfCrossings(pairs=s.pairs, candidate_pairs=s.candidate_pairs,
                         example=list(s.example) if s.example is not None else None)


# ---- grids ---------------------------------------------------------------------------

from ._grid import Grid, grid  # noqa: E402  (uses the helpers above)


def devices():
    """The OpenCL devices grid(device="opencl:N") can name, as
    `polyvol devices --json` lists them: {"opencl_runtime": bool, "note": why
    there are none or "", "devices": [{"index", "name", "platform", "vendor",
    "type", "version", "global_memory", "compute_units", "fp64", "usable",
    "reason"}]}. Never raises: a machine without OpenCL has an empty list."""
    return _core.devices()


# ---- chains, polygons, implicit solids ------------------------------------------------------

class ChainVolume(_Result):
    """Volume (signed) and centroid of a boundary chain in R^n: correctly
    rounded, or within error_bound (absolute) and centroid_error_bound."""

    def to_dict(self):
        d = super().to_dict()
        if d.get("traversal") is None:  # as `polyvol ndim`: only for a bounded result
            d.pop("traversal", None)
        return d

    _fields = ("dimension", "vertices", "vertices_welded", "simplices", "degenerate_simplices", "faces",
               "unmatched_faces", "boundary_faces", "misoriented_faces", "nonmanifold_faces", "components", "formula",
               "accuracy", "volume", "error_bound", "correctly_rounded", "centroid", "centroid_error_bound",
               "centroid_correctly_rounded", "traversal")


def _chain_result(d):
    d = dict(d)
    d["error_bound"] = d.pop("volume_error_bound")
    d["correctly_rounded"] = d.pop("volume_correctly_rounded")
    d["accuracy"] = "correctly-rounded" if d["correctly_rounded"] else "error-bound"
    if d["correctly_rounded"]:
        d["traversal"] = None  # the determinants' walk matters only for a bounded result
    return d


def chain_volume(points, simplices, formula="cone", accuracy="auto"):
    """Volume and centroid of the polyhedron in R^n bounded by an oriented
    chain of (n-1)-simplices: points (m, n), simplices (k, n) vertex indices
    (docs/chain-format.md). formula "cone" (2.1) or "prism" (2.2); accuracy
    "auto" (correctly rounded for n <= 3, a rigorous bound above), "bounded"
    or "exact". ``closed`` says whether the chain is a cycle."""
    p = _arrays.coordinates(points, columns=None, name="points")
    s = _arrays.indices(simplices, p.shape[0], name="simplices")
    if s.ndim != 2 or s.shape[1] != p.shape[1]:
        raise ValueError(f"simplices must have shape (k, {p.shape[1]}), not {s.shape}")
    return ChainVolume(**_chain_result(_core.chain_volume(p, s, formula, accuracy)))


class PolygonArea(_Result):
    """Area (signed: counter-clockwise outer loops positive, holes clockwise)
    and centroid of plane polygons, correctly rounded."""

    _fields = ("area", "correctly_rounded", "error_bound", "centroid", "centroid_correctly_rounded")


def polygon_area(loops, formula="cone"):
    """Area and centroid of polygons with holes: ``loops`` a list of (k, 2)
    arrays, each a closed loop (the last vertex joins the first); outer
    loops counter-clockwise, holes clockwise."""
    arrays = [_arrays.coordinates(loop, columns=2, name="loop") for loop in loops]
    points = _np.concatenate(arrays) if arrays else _np.zeros((0, 2))
    offsets = _np.zeros(len(arrays) + 1, dtype=_np.uint32)
    _np.cumsum([a.shape[0] for a in arrays], out=offsets[1:])
    idx = _np.arange(points.shape[0], dtype=_np.uint32)
    raw = _core.polygon_area(points, offsets, idx, formula)
    if raw["loops_wound_like_container"]:
        _warn(f"polygon_area: {raw['loops_wound_like_container']} loop(s) wound like the loop around them (a hole "
              "counter-clockwise inside a counter-clockwise outer loop, say): their area is added, not taken away")
    d = _chain_result(raw)
    return PolygonArea(area=d["volume"], correctly_rounded=d["correctly_rounded"], error_bound=d["error_bound"],
                       centroid=d["centroid"], centroid_correctly_rounded=d["centroid_correctly_rounded"],
                       closed=d["closed"])


def load_chain(path):
    """Reads a .chain file or `qconvex o Qt` output: (points (m, n), simplices (k, n))."""
    return _core.read_chain(_os.fsencode(path))


def load_polygons(path):
    """Reads the polygon text format (one loop per line): a list of (k, 2) arrays."""
    return _core.read_polygons(_os.fsencode(path))


class ImplicitVolume(_Result):
    """Volume of {F <= 0} in a box from a piecewise-linear approximation on a
    Kuhn triangulation: ``volume`` is the Richardson extrapolation of the
    lattices of spacing h and 2h, ``extrapolated_error_estimate`` its own
    estimated error (from the 4h lattice too; None where the lattices do not
    show the O(h²) regime, or a side has a cell count that is not a multiple
    of 4), ``error_estimate`` the estimated error of ``volume_pl``, the PL
    solid's volume at spacing h, which also bounds the extrapolation's
    comfortably in that regime (estimates, not bounds); ``clipped`` when the
    solid reaches the box (it is then clipped by it)."""

    _fields = ("expression", "dimension", "h", "spacing", "volume", "extrapolated_error_estimate", "volume_pl",
               "error_estimate", "boundary_simplices", "clipped", "box_rule", "formula", "streamed", "seconds", "fine",
               "volume_pl_2h", "volume_pl_4h", "coarse")


def implicit(f, dim, box, h=None, *, coarse_cells=0, error_estimate=True, box_rule="clip", seeds=None):
    """The volume of {x in box : F(x) <= 0} in R^dim (docs/implicit.md).

    f: an expression string in x, y, z or x1..xn (muparser syntax), or a
    Python callable taking a (k, dim) float64 array of points and returning
    k values (it is called with many points at once: a cube's corners, a
    lattice line). box: (lo, hi), each a number or dim numbers. h: the
    lattice spacing (None: the widest side / the default cell count).
    Raises ExpressionError, ImplicitError (NaN values, the box touched with
    box_rule="error")."""
    lo, hi = box
    lo = [float(x) for x in _np.atleast_1d(lo)]
    hi = [float(x) for x in _np.atleast_1d(hi)]
    s = [] if seeds is None else [float(x) for x in _np.asarray(seeds, dtype=_np.float64).reshape(-1)]
    if not isinstance(f, str) and not callable(f):
        raise TypeError("f must be an expression string or a callable")
    r = _core.implicit_volume(f, int(dim), lo, hi, 0.0 if h is None else float(h), int(coarse_cells),
                              bool(error_estimate), box_rule, s)
    fine, coarse = r["fine"], r["coarse"]
    return ImplicitVolume(expression=f if isinstance(f, str) else None, spacing=fine["spacing"], box_rule=box_rule,
                          formula="cone", streamed=True, dimension=r["dimension"], h=r["h"], volume=r["volume"],
                          error_estimate=r["error_estimate"] if error_estimate else None, volume_pl=fine["volume"],
                          extrapolated_error_estimate=(r["extrapolated_error_estimate"] if error_estimate and not
                                                       _math.isnan(r["extrapolated_error_estimate"]) else None),
                          volume_pl_2h=coarse["volume"] if coarse else None, volume_pl_4h=r["volume_pl_4h"],
                          clipped=r["clipped"],
                          boundary_simplices=fine["boundary_simplices"],
                          function_evaluations=fine["function_evaluations"] + (
                              coarse["function_evaluations"] if coarse else 0) + r["coarser_evaluations"],
                          seconds=r["seconds"], fine=fine, coarse=coarse)


def _warn(message):
    _warnings.warn(message, stacklevel=3)


class Cells(_Result):
    """Bodies in the cells of a mesh (`polyvol cells`): every volume correctly
    rounded; see polyvol.cells."""

    _fields = ("unit", "total", "covered_volume", "cell_volumes", "volumes", "fractions", "cell_class", "inside_mesh",
               "cells_sum", "in_overlaps", "cells_tile", "body_volumes", "full_cells", "cut_cells", "empty_cells", "union_volumes",
               "union_inside_mesh", "intersection_volumes", "intersection_inside_mesh", "wetted_area", "surface_normal",
               "surface_bound")


from ._cells import CellMesh, cell_volumes, cells, load_cells, write_foam_field, write_grdecl_keyword  # noqa: E402
