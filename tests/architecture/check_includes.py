#!/usr/bin/env python3
"""The module borders of docs/architecture.md, checked over the include lines.

A module (src/<m>/, a static library polyvol_<m> declared in CMakeLists.txt
with its DEPS) may include
  * its own headers;
  * the foundation's headers (src/core/, src/exact/): internal, not
    installed, shared by every module that depends on them;
  * the public headers (include/polyvol/) of itself and of the modules it
    depends on, directly or not;
  * a module's internal interface (INTERFACES below) when it depends on
    that module: a header another module above it needs, which includes
    only public, foundation and interface headers, so nothing private
    comes along.
No public type is defined in two public headers. The command line (cli/),
the Python bindings (python/) and the benchmarks
(bench/) include only public headers and their own; Python never includes
cli/. The tests (tests/<m>/) and fuzz targets are white-box and may include
the private headers of what they test.

Prints every violation and exits 1 when there is one.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])

FOUNDATION = {"core", "exact"}
# Internal interfaces: headers of a module that the modules above it include.
INTERFACES = {
    "measure": {"measure/sums.hpp"},                           # the cone sums, for boolean
    "topology": {"topology/welded.hpp", "topology/parts.hpp"},  # welded polygons and shells, for boolean
    "device": {"device/opencl.hpp"},                           # OpenCL's entry points and devices, for grid
    "boolean": {"boolean/level_pieces.hpp",                    # the union's boundary pieces, for grid
                "boolean/prepared_body.hpp"},                  # one body against many cells, for cells
}
# The module that implements each public header.
PUBLIC_OWNER = {
    "mesh.hpp": "core", "units.hpp": "core", "cell_mesh.hpp": "core", "cell_class.hpp": "core",
    "cell_mesh_io.hpp": "io", "cells.hpp": "cells",
    "chain.hpp": "core",  # plain arrays, as mesh.hpp
    "io.hpp": "io", "parse_options.hpp": "io", "chain_io.hpp": "io", "grid_io.hpp": "io",
    "measure.hpp": "measure", "soup.hpp": "measure",
    "topology.hpp": "topology",
    "simplicial.hpp": "simplicial",
    "boolean.hpp": "boolean",
    "grid.hpp": "grid", "device.hpp": "device",
    "solid.hpp": "solid",
    "report.hpp": "report", "number_text.hpp": "report",
    "implicit.hpp": "implicit",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def module_deps():
    """polyvol_module(name DEPS ... PRIVATE_DEPS ...) from CMakeLists.txt, closed transitively."""
    text = (ROOT / "CMakeLists.txt").read_text()
    direct = {}
    for m in re.finditer(r"polyvol_module\((\w+)([^)]*)\)", text):
        words = m.group(2).split()
        deps = set()
        for w in words:
            if w.startswith("polyvol_"):
                deps.add(w[len("polyvol_"):])
        direct[m.group(1)] = deps
    closed = {}

    def close(name, seen=()):
        if name in closed:
            return closed[name]
        if name in seen:
            raise SystemExit(f"CMakeLists.txt: a dependency cycle through {name}")
        out = set()
        for d in direct.get(name, ()):
            out |= {d} | close(d, seen + (name,))
        closed[name] = out
        return out

    for name in direct:
        close(name)
    return closed


def sources(folder):
    for p in sorted((ROOT / folder).rglob("*")):
        if p.suffix in {".hpp", ".cpp", ".h"}:
            yield p


def main():
    deps = module_deps()
    modules = set(deps)
    errors = []
    unknown = sorted(p.name for p in (ROOT / "include/polyvol").glob("*.hpp") if p.name not in PUBLIC_OWNER)
    for name in unknown:
        errors.append(f"include/polyvol/{name}: no owning module in tests/architecture/check_includes.py")

    def check_module_file(path, m):
        rel = path.relative_to(ROOT)
        reach = deps[m] | {m}
        text = path.read_text(errors="replace")
        is_interface = str(path.relative_to(ROOT / "src")) in INTERFACES.get(m, set())
        for inc in INCLUDE.findall(text):
            top, _, rest = inc.partition("/")
            if top == "polyvol":
                owner = PUBLIC_OWNER.get(rest)
                if owner is not None and owner not in reach:
                    errors.append(f"{rel}: includes {inc}, of {owner}, which {m} does not depend on")
            elif top in modules:
                if top == m and not is_interface:
                    continue
                if top not in reach:
                    errors.append(f"{rel}: includes {inc}, of {top}, which {m} does not depend on")
                elif top in FOUNDATION:
                    continue
                elif inc not in INTERFACES.get(top, set()):
                    what = "interface header" if is_interface else "module"
                    errors.append(f"{rel}: {what} includes {inc}, a private header of {top}")

    for m in sorted(modules):
        for path in sources(f"src/{m}"):
            check_module_file(path, m)

    # The front ends: public headers and their own files only.
    for folder in ("cli", "python", "bench"):
        for path in sources(folder):
            rel = path.relative_to(ROOT)
            for inc in INCLUDE.findall(path.read_text(errors="replace")):
                top = inc.partition("/")[0]
                if top in modules or inc.startswith("../src/") or inc.startswith("src/"):
                    errors.append(f"{rel}: includes {inc}, a private header of the library")
                if folder == "python" and (top == "cli" or inc.startswith("../cli/") or top in {"output", "commands"}):
                    errors.append(f"{rel}: includes {inc}: Python binds the library, not the command line")
    # A public type is defined in one header (two definitions of one name in
    # namespace polyvol break the one-definition rule when both are linked).
    defined = {}
    for path in sorted((ROOT / "include/polyvol").glob("*.hpp")):
        for name in re.findall(r"^(?:enum class|struct|class)\s+(\w+)\s*(?::[^{;]*)?\{", path.read_text(), re.M):
            if name in defined:
                errors.append(f"include/polyvol/{path.name}: {name} is also defined in {defined[name]}")
            defined[name] = f"include/polyvol/{path.name}"
    for e in errors:
        print(e)
    checked = sum(1 for m in modules for _ in sources(f"src/{m}"))
    print(f"{len(errors)} border violations in {checked} module files and the front ends")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
