#!/usr/bin/env python3
"""The size rules of docs/dev/architecture.md, checked: no source file in filters/ or apps/ over
1,000 lines, none of their functions over 100, and vtkLocalReflectanceFilter.cxx at most 800.

The code is as clang-format writes it (the test `formatting`): a function defined at namespace
scope opens with "{" alone at the start of a line and closes with "}" alone there, after its
signature, which ends in ")" (or ") const", "noexcept", ...). Namespaces, types and
initialisers open the same way and are told apart by their first line or their "=".
"""
import pathlib
import re
import sys

FILE_LIMIT = 1000
FUNCTION_LIMIT = 100
NAMED_LIMITS = {"filters/vtk/vtkLocalReflectanceFilter.cxx": 800}
NOT_FUNCTIONS = re.compile(r"^(namespace|struct|class|enum|union|extern|template\s*<.*>\s*(struct|class))\b")
SIGNATURE_END = re.compile(r"\)\s*(const)?\s*(noexcept)?\s*(override)?\s*(final)?\s*$")


def functions(lines):
    """(first line number, length, signature) of each function body at namespace scope."""
    found = []
    for i, line in enumerate(lines):
        if line.rstrip() != "{" or i == 0:
            continue
        end = i - 1
        start = end
        # The signature's first line is the nearest one above that starts at column 0.
        while start > 0 and lines[start][:1] in (" ", "\t"):
            start -= 1
        head = " ".join(l.strip() for l in lines[start:end + 1])
        if NOT_FUNCTIONS.match(head) or not SIGNATURE_END.search(lines[end]) or "=" in head.split("(")[0]:
            continue
        close = next((j for j in range(i + 1, len(lines)) if lines[j].rstrip() == "}"), len(lines) - 1)
        found.append((start + 1, close - start + 1, head[:100]))
    return found


def main(repository):
    root = pathlib.Path(repository)
    problems = []
    count = 0
    for folder in ("filters", "apps"):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".h", ".cxx", ".cpp"):
                continue
            count += 1
            name = path.relative_to(root).as_posix()
            lines = path.read_text(encoding="utf-8").split("\n")
            limit = NAMED_LIMITS.get(name, FILE_LIMIT)
            if len(lines) - 1 > limit:
                problems.append(f"{name}: {len(lines) - 1} lines, more than {limit}: split it by job")
            for first, length, head in functions(lines):
                if length > FUNCTION_LIMIT:
                    problems.append(f"{name}:{first}: {head}: {length} lines, more than {FUNCTION_LIMIT}: "
                                    "split it into named steps")
    if count < 100:
        problems.append(f"only {count} source files found under {root}: is it the repository?")
    for problem in problems:
        print(problem)
    if problems:
        return 1
    print(f"all {count} source files in filters/ and apps/ keep to the size rules")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
