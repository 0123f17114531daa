#!/usr/bin/env python3
"""Checks the project's structure (docs/architecture.md):

  check_structure.py layers SOURCE_DIR [BUILD_DIR]
      Every #include in Filters/ stays within the layers its folder may use (LAYERS below), the
      layers' graph has no cycle, the core and the formats include nothing of VTK, and, given the
      build folder, the VTK filter module does not link the formats library.
  check_structure.py sizes SOURCE_DIR
      No function over 80 lines and no source file over 1,000 lines, in C++ and Python, except
      those listed with their reason in size-exceptions.txt beside this script.

Prints every problem and exits with 1 if there is one.
"""
import ast
import os
import re
import sys

# Each layer (a folder under Filters/) and the layers it may include or link, besides itself.
LAYERS = {
    "Core/Common": [],
    "Core/Kernel": ["Core/Common"],
    "Core/Neighbours": ["Core/Common"],
    "Core/Octree": ["Core/Common", "Core/Kernel"],
    "Core/Measurement": ["Core/Common", "Core/Neighbours"],
    "Core/EdgeAware": ["Core/Common", "Core/Kernel", "Core/Neighbours"],
    "Core": ["Core/Common", "Core/Kernel", "Core/Neighbours", "Core/Octree", "Core/Measurement",
             "Core/EdgeAware"],
    "Formats": ["Core/Common"],
    "VTKCommon": ["VTK"],
    "VTKFilter": ["VTK", "VTKCommon", "Core", "Core/Common"],
    "VTKIO": ["VTK", "VTKCommon", "Formats", "Core/Common"],
    "Parallel": ["VTK", "VTKFilter", "Core", "Core/Common", "Core/Measurement"],
    # One file written by every process: the LAS writer of VTKIO over the pieces of Formats.
    "ParallelIO": ["VTK", "VTKIO", "Formats", "Core/Common"],
}
# Layers that must know nothing of VTK (nor of ParaView's Qt side).
PLAIN = [layer for layer in LAYERS if layer.startswith("Core") or layer == "Formats"]
MAX_FUNCTION_LINES = 80
MAX_FILE_LINES = 1000
SOURCE_EXTENSIONS = (".cxx", ".h", ".cpp", ".hpp")


def layer_of(relative):
    """The layer of a path relative to Filters/, or None."""
    folder = os.path.dirname(relative)
    while folder:
        if folder in LAYERS:
            return folder
        folder = os.path.dirname(folder)
    return None


def source_files(root, extensions):
    for folder, subfolders, files in os.walk(root):
        subfolders[:] = sorted(d for d in subfolders if not d.startswith((".", "build")))
        for name in sorted(files):
            if name.endswith(extensions):
                yield os.path.join(folder, name)


LITERALS = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|'
                      r"(?<![0-9A-Za-z_])'(?:\\.|[^'\\\n])+'", re.S)


def strip_cxx(text, keep_strings=False):
    """The text with comments (and, unless kept, string and character literals) blanked, its
    lines kept."""
    def blank(match):
        found = match.group(0)
        if found.startswith(("//", "/*")):
            return "\n" * found.count("\n") + " "
        return found if keep_strings else "\n" * found.count("\n") + '""'
    return LITERALS.sub(blank, text)


def check_layers(source_dir, build_dir):
    filters = os.path.join(source_dir, "Filters")
    headers = {}
    for path in source_files(filters, SOURCE_EXTENSIONS):
        relative = os.path.relpath(path, filters)
        headers.setdefault(os.path.basename(path), []).append(relative)
    problems = []
    edges = set()
    include = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
    for path in source_files(filters, SOURCE_EXTENSIONS):
        relative = os.path.relpath(path, filters)
        layer = layer_of(relative)
        if layer is None:
            problems.append(f"Filters/{relative}: in no layer (add its folder to LAYERS)")
            continue
        with open(path, encoding="utf-8") as stream:
            text = strip_cxx(stream.read(), keep_strings=True)
        for number, name in ((text.count("\n", 0, m.start()) + 1, m.group(1))
                             for m in include.finditer(text)):
            base = os.path.basename(name)
            targets = {layer_of(t) for t in headers.get(base, [])}
            if not targets:
                if re.match(r"(vtk|pq|QVTK|Q[A-Z])\w*\.h$", base):
                    targets = {"VTK"}
                else:
                    continue  # the standard library or the system
            if len(targets) > 1:
                problems.append(f"Filters/{relative}:{number}: {name} names files of several layers")
                continue
            target = targets.pop()
            if target == layer:
                continue
            edges.add((layer, target))
            if target == "VTK" and layer in PLAIN:
                problems.append(f"Filters/{relative}:{number}: includes {name}: "
                                f"{layer} is plain C++ and must not use VTK")
            elif target not in LAYERS[layer]:
                problems.append(f"Filters/{relative}:{number}: includes {name} of {target}, which "
                                f"{layer} may not use (it may use {', '.join(LAYERS[layer]) or 'nothing'})")
    problems += find_cycles(edges)
    if build_dir:
        problems += check_link_lines(build_dir)
    return problems


def find_cycles(edges):
    graph = {}
    for a, b in edges:
        graph.setdefault(a, set()).add(b)
    problems, state = [], {}

    def visit(node, path):
        state[node] = "open"
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                cycle = path[path.index(nxt):] + [nxt]
                problems.append("dependency cycle: " + " -> ".join(cycle))
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    return problems


def check_link_lines(build_dir):
    """The link lines of the VTK filter modules (in build.ninja: a Ninja build) must not
    name the formats library, and the core's libraries must not name VTK."""
    ninja = os.path.join(build_dir, "build.ninja")
    if not os.path.exists(ninja):
        return [f"{build_dir}: no build.ninja (configure with -G Ninja to check the links)"]
    with open(ninja, encoding="utf-8") as stream:
        text = stream.read()
    blocks = re.split(r"\n(?=build )", text)
    problems, found = [], set()
    for block in blocks:
        head = block.split("\n", 1)[0]
        for module in ("libvtkFiltersPointCloudBilateral", "libvtkFiltersParallelPointCloudBilateral"):
            if re.match(rf"build lib/{module}\.so[.\d]*:", head) and "_LINKER__" in head:
                found.add(module)
                if "PointCloudBilateralFormats" in block:
                    problems.append(f"{module} links the formats library")
        match = re.match(r"build lib/libPointCloudBilateral(\w+)\.a:", head)
        if match and re.search(r"vtk\w+-pv|/vtk-?9", block):
            problems.append(f"the core library PointCloudBilateral{match.group(1)} uses VTK")
    if "libvtkFiltersPointCloudBilateral" not in found:
        problems.append("build.ninja has no link rule for libvtkFiltersPointCloudBilateral")
    return problems


def load_exceptions(source_dir):
    path = os.path.join(source_dir, "Testing", "Structure", "size-exceptions.txt")
    exceptions = {}
    with open(path, encoding="utf-8") as stream:
        for line in stream:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            key, _, reason = line.partition(" ")
            if not reason.strip():
                raise SystemExit(f"{path}: '{key}' has no reason")
            exceptions[key] = reason.strip()
    return exceptions


CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "decltype",
           "noexcept", "else", "do", "case", "new", "delete", "throw"}


def cxx_functions(text):
    """(name, first line, last line) of each function body in C++ text: an outermost brace
    block that follows a parameter list. Lambdas and blocks inside a function count as part of
    it; a function's length is counted from its opening brace to its closing brace."""
    text = strip_cxx(text)
    stack, found = [], []
    line = 1
    signature = re.compile(r"([~\w:]+|operator\s*\S+?)\s*\($")
    for index, char in enumerate(text):
        if char == "\n":
            line += 1
        elif char == "{":
            kind, name = "block", ""
            if not any(entry[0] == "function" for entry in stack):
                before = text[max(0, index - 2000):index]
                before = re.sub(r"\s+", " ", before).rstrip()
                before = re.sub(r"(\b(const|override|final|noexcept|mutable|volatile)\b\s*)+$", "",
                                before).rstrip()
                before = re.sub(r"->\s*[\w:<>,\s\*&]+$", "", before).rstrip()
                # A constructor's initialiser list: "...) : A(b), C{d}" back to its ')'.
                init = re.search(r"\)\s*:\s*(?:[\w:]+\s*[({][^;{}]*[)}]\s*,?\s*)+$", before)
                if init:
                    before = before[:init.start() + 1]
                if before.endswith(")"):
                    depth, j = 0, len(before) - 1
                    while j >= 0:
                        depth += before[j] == ")"
                        depth -= before[j] == "("
                        if depth == 0:
                            break
                        j -= 1
                    match = signature.search(before[:j + 1])
                    word = match.group(1) if match else ""
                    if word and word.split("::")[-1] not in CONTROL and not before[:j].rstrip().endswith("]"):
                        kind, name = "function", word
            stack.append((kind, line, name))
        elif char == "}" and stack:
            kind, start, name = stack.pop()
            if kind == "function":
                found.append((name, start, line))
    return found


def python_functions(text):
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return []
    return [(node.name, node.lineno, node.end_lineno) for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))]


def check_sizes(source_dir):
    exceptions = load_exceptions(source_dir)
    used, problems = set(), []
    for top in ("Filters", "Plugin", "Examples", "Testing", "Data"):
        for path in source_files(os.path.join(source_dir, top), SOURCE_EXTENSIONS + (".py",)):
            relative = os.path.relpath(path, source_dir)
            with open(path, encoding="utf-8") as stream:
                text = stream.read()
            lines = text.count("\n")
            if lines > MAX_FILE_LINES:
                if relative in exceptions:
                    used.add(relative)
                else:
                    problems.append(f"{relative}: {lines} lines (at most {MAX_FILE_LINES})")
            functions = python_functions(text) if path.endswith(".py") else cxx_functions(text)
            for name, first, last in functions:
                length = last - first + 1
                key = f"{relative}:{name}"
                if length <= MAX_FUNCTION_LINES:
                    continue
                if key in exceptions:
                    used.add(key)
                else:
                    problems.append(f"{relative}:{first}: {name} is {length} lines "
                                    f"(at most {MAX_FUNCTION_LINES})")
    for key in sorted(set(exceptions) - used):
        problems.append(f"size-exceptions.txt: '{key}' is not over the limits any more: remove it")
    return problems


def report(problems, summary):
    """Prints each problem, then the summary with their number; the exit status."""
    for problem in problems:
        print(problem)
    print(f"{summary}{len(problems)} problem(s)")
    return 1 if problems else 0


def main(arguments):
    if len(arguments) < 2 or arguments[0] not in ("layers", "sizes"):
        raise SystemExit(__doc__)
    if arguments[0] == "layers":
        problems = check_layers(arguments[1], arguments[2] if len(arguments) > 2 else None)
    else:
        problems = check_sizes(arguments[1])
    return report(problems, "")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
