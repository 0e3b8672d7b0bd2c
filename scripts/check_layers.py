#!/usr/bin/env python3
"""Checks the library's layering: a file under src/blockdem/<folder>/ may include only from its
own folder or from folders on lower floors, and only apps/ may start other programs (Python).
The Python bindings (python/src/) sit on top, like apps/: they may include any folder and start
no program. And sizes: no file under src/ over 800 lines, no function there over 150 lines but
the numerical kernels named in KERNELS (one algorithm each, commented block by block).
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
MAX_FILE_LINES = 800
MAX_FUNCTION_LINES = 150
# Functions allowed past MAX_FUNCTION_LINES: numerical kernels that are one algorithm, commented
# block by block (splitting them would scatter one derivation over several functions).
KERNELS = {
    "face_contact_geometry",  # collision/face_contact.cpp: the cells of a face contact
    "exponential_slip_sums",  # response/face_twist.cpp: the closed-form slip integrals
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"blockdem/([^/"]+)/')
LAUNCH = re.compile(r'\b(popen|std::system|execv?p?e?|posix_spawnp?)\s*\(')


def code_only(text: str) -> str:
    """The text with comments, string and character literals blanked (line breaks kept)."""
    text = re.sub(r'R"(\w*)\((?:.|\n)*?\)\1"', lambda m: '""' + "\n" * m.group(0).count("\n"), text)
    out = []
    i, n = 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text[i] in "\"'" and not (text[i] == "'" and i > 0 and text[i - 1].isalnum()):
            quote, j = text[i], i + 1
            while j < n and text[j] != quote:
                j += 2 if text[j] == "\\" else 1
            out.append(quote * 2)
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def long_functions(text: str):
    """(name, first line, lines) of each function body at namespace or class scope longer than
    MAX_FUNCTION_LINES, from the braces: a body opens where the code since the last ';', '{' or
    '}' holds a ')' and is no namespace or type (lambdas inside a body count with the body)."""
    code = code_only(text)
    stack, found = [], []
    line, last = 1, 0
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        elif c == "{":
            head = code[last:i]
            if any(kind == "function" for kind, _, _ in stack):
                kind = "inside"
            elif re.search(r"\bnamespace\b", head) or re.search(r"\bextern\b[^()]*$", head):
                kind = "namespace"
            elif re.search(r"\b(class|struct|enum|union)\b[^()]*$", head):
                kind = "type"
            elif ")" in head:
                kind = "function"
            else:
                kind = "other"
            names = re.findall(r"([A-Za-z_]\w*)\s*\(", head)
            stack.append((kind, line, names[0] if names else "?"))
            last = i + 1
        elif c == "}":
            kind, first, name = stack.pop() if stack else ("other", line, "?")
            if kind == "function" and line - first + 1 > MAX_FUNCTION_LINES:
                found.append((name, first, line - first + 1))
            last = i + 1
        elif c == ";":
            last = i + 1
    return found


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
        text = path.read_text(encoding="utf-8")
        if text.count("\n") > MAX_FILE_LINES:
            problems.append(f"{rel}: {text.count(chr(10))} lines, more than {MAX_FILE_LINES}")
        for name, first, lines in long_functions(text):
            if name.split("::")[-1] not in KERNELS:
                problems.append(f"{rel}:{first}: function {name} has {lines} lines, more than "
                                f"{MAX_FUNCTION_LINES} (or name it in KERNELS if it is one "
                                "numerical kernel)")
        for number, line in enumerate(text.splitlines(), 1):
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
    print("check_layers: layering and sizes clean")
    return 0


if __name__ == "__main__":
    sys.exit(main())
