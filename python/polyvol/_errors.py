"""The exceptions polyvol raises, with the position of the problem."""


class ReadError(ValueError):
    """A file could not be read as a mesh (or chain, or polygons).

    ``path`` is the file, ``line`` the 1-based line of a text format (None
    when not applicable), ``offset`` the byte offset of a binary format
    (None when not applicable; counted in the decompressed data for .gz) and
    ``message`` what was wrong or expected. ``str(e)`` says all of it.
    """

    def __init__(self, text, path=None, line=None, offset=None, message=None):
        super().__init__(text)
        self.path = path
        self.line = line
        self.offset = offset
        self.message = message if message is not None else text


class ImplicitError(ValueError):
    """The implicit solid could not be measured: ``code`` is "not_a_number"
    (F returned NaN at ``point``), "touches_box" (box="error" and F <= 0 at
    ``point`` on the box boundary) or "too_large" (the lattice is too fine)."""

    def __init__(self, text, code, point):
        super().__init__(text)
        self.code = code
        self.point = list(point)


class ExpressionError(ValueError):
    """An expression for F could not be parsed; ``position`` is the 0-based
    character where the problem is, or -1."""

    def __init__(self, text, position):
        super().__init__(text)
        self.position = position


class NotASolidError(ValueError):
    """A mesh does not bound a solid as polyvol takes it (polyvol/solid.hpp),
    the same refusal as the command line's exit 3: ``defect`` is "open"
    (unbalanced edges: a hole, or an edge of three or more faces),
    "misoriented" (closed, faces wound inconsistently: orient=True fixes it),
    "not_orientable" (orient=True could not), "bad_tolerance" (weld_tolerance
    refused), for grid "not_split" (a solid the grid cannot take yet: a shell
    crossing itself, cavities among overlapping shells); ``message`` says what and how to fix it. allow_open=True
    measures an open surface anyway (its figures then depend on the origin)."""

    def __init__(self, text, defect, message=None):
        super().__init__(text)
        self.defect = defect
        self.message = message if message is not None else text


class DeviceError(RuntimeError):
    """The device asked for (device="opencl" or "opencl:N", or POLYVOL_DEVICE)
    cannot do the work: absent, without IEEE double precision, a kernel that
    does not build (the driver's log is in the message), out of device
    memory. A machine without OpenCL is not an error: the CPU computes, and
    the summary's "device" says so."""
