#!/usr/bin/env python3
"""Checks that no include runs against the architecture's direction.

    core, automaton <- geometry <- world <- {kinematics, sensing, planning} <- robot <- nav <- sim
      <- scenario <- {io, render} <- runner <- app

and ompl (the library floornav::ompl) on top of them, so that no other library includes it.

A file of a module may include its own module's headers and those of modules below it, never a
module above it or beside it (kinematics/sensing/planning, io/render, core/automaton are
siblings). A source file's private headers ("name.hpp" without floornav/) must be its own
module's: no private header is reached across modules. Headers that modules share but users do
not get (internal/floornav/, never installed) follow the same layers, and no installed header
(include/) includes one. Exit status 1 lists every violation.
"""
import pathlib
import re
import sys

RANK = {"core": 0, "automaton": 0, "geometry": 1, "world": 2, "kinematics": 3, "sensing": 3,
        "planning": 3, "robot": 4, "nav": 5, "sim": 6, "scenario": 7, "io": 8, "render": 8, "runner": 9,
        "ompl": 10}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


# Private headers CMake generates into build/generated, by the module whose template makes them.
GENERATED = {"floornav_version.hpp": "io"}

def module_of(path: pathlib.Path, root: pathlib.Path):
    rel = path.relative_to(root).parts
    if rel[0] in ("include", "internal") and len(rel) > 3:
        return rel[2]
    if rel[0] == "src" and len(rel) > 2:
        return rel[1]
    return None  # umbrella headers, app/, tests/, python/: above everything


def main() -> int:
    root = pathlib.Path(__file__).resolve().parent.parent
    errors = []
    files = [p for d in ("include", "internal", "src") for p in (root / d).rglob("*")
             if p.suffix in (".hpp", ".cpp", ".h")]
    for path in sorted(files):
        mod = module_of(path, root)
        if mod is None:
            continue
        if mod not in RANK:
            errors.append(f"{path.relative_to(root)}: module '{mod}' has no place in the layers")
            continue
        for inc in INCLUDE.findall(path.read_text(encoding="utf-8", errors="replace")):
            if inc.startswith("floornav/"):
                parts = inc.split("/")
                other = parts[1] if len(parts) > 2 else None
                if path.parts[len(root.parts)] == "include" and (root / "internal" / inc).exists():
                    errors.append(f"{path.relative_to(root)}: an installed header includes the "
                                  f"internal {inc}")
                if other is None or other == mod:
                    continue
                if other not in RANK:
                    errors.append(f"{path.relative_to(root)}: includes {inc} (unknown module)")
                elif RANK[other] >= RANK[mod]:
                    errors.append(f"{path.relative_to(root)}: {mod} includes {inc}, which is "
                                  f"{'beside' if RANK[other] == RANK[mod] else 'above'} it")
            elif GENERATED.get(inc) == mod:
                continue  # written by CMake at configure time from the module's own template
            else:
                # Relative to the file, or to src/ (the libraries' private include directory).
                candidates = [(path.parent / inc).resolve(), (root / "src" / inc).resolve()]
                target = next((c for c in candidates if c.exists()), None)
                src_mod = root / "src" / mod
                if target is None or src_mod not in target.parents:
                    errors.append(f"{path.relative_to(root)}: private header \"{inc}\" is not "
                                  f"in src/{mod}/")
    # Every public module header is named by an umbrella (include/floornav/*.hpp), so that
    # `#include <floornav/floornav.hpp>` is everything (the consumer test checks the same).
    umbrellas = "".join(u.read_text() for u in (root / "include" / "floornav").glob("*.hpp"))
    for header in sorted((root / "include" / "floornav").glob("*/**/*.hpp")):
        name = header.relative_to(root / "include").as_posix()
        if f'#include "{name}"' not in umbrellas:
            errors.append(f"{name} is in no umbrella header (include/floornav/*.hpp)")
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} include(s) against the layers")
        return 1
    print(f"{len(files)} files: every include follows the layers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
