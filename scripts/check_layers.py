#!/usr/bin/env python3
"""Checks the library's layering: a file under src/blockdem/<folder>/ may include only from its
own folder or from folders on lower floors, and only apps/ may start other programs (Python).
The Python bindings (python/src/) sit on top, like apps/: they may include any folder and start
no program.
Standard library only. Exit 0 when clean, 1 with one line per violation."""
import pathlib
import re
import sys

# Floor of every folder under src/blockdem/ (docs/architecture.md draws the same table).
FLOORS = {
    "numerics": 0,
    "geometry": 1, "contact": 1,
    "collision": 2, "dynamics": 2, "analysis": 2,
    "response": 3,
    "world": 4,
    "scenario": 5, "io": 5, "parallel": 5,
    "voussoir": 6, "lab": 6, "calibration": 6, "rockmass": 6,
    "run": 7,
    "studies": 8,
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"blockdem/([^/"]+)/')
LAUNCH = re.compile(r'\b(popen|std::system|execv?p?e?|posix_spawnp?)\s*\(')


def main() -> int:
    root = pathlib.Path(__file__).resolve().parent.parent
    src = root / "src" / "blockdem"
    problems = []
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h", ".cc"):
            continue
        rel = path.relative_to(root)
        folder = path.relative_to(src).parts[0]
        if folder not in FLOORS:
            problems.append(f"{rel}: folder '{folder}' has no floor in scripts/check_layers.py")
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if m:
                target = m.group(1)
                if target not in FLOORS:
                    problems.append(f"{rel}:{number}: includes unknown folder '{target}'")
                elif target != folder and FLOORS[target] >= FLOORS[folder]:
                    problems.append(
                        f"{rel}:{number}: {folder}/ (floor {FLOORS[folder]}) includes "
                        f"{target}/ (floor {FLOORS[target]}): only lower floors may be included")
            if LAUNCH.search(line) and not line.lstrip().startswith("//"):
                problems.append(f"{rel}:{number}: starts a program; only apps/ may do that")
    # The Python bindings: on top of every floor; they start no program.
    for path in sorted((root / "python" / "src").rglob("*")):
        if path.suffix not in (".hpp", ".cpp"):
            continue
        rel = path.relative_to(root)
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if m and m.group(1) not in FLOORS:
                problems.append(f"{rel}:{number}: includes unknown folder '{m.group(1)}'")
            if LAUNCH.search(line) and not line.lstrip().startswith("//"):
                problems.append(f"{rel}:{number}: starts a program; only apps/ may do that")
    for p in problems:
        print(p)
    if problems:
        print(f"check_layers: {len(problems)} problem(s)")
        return 1
    print("check_layers: layering clean")
    return 0


if __name__ == "__main__":
    sys.exit(main())
