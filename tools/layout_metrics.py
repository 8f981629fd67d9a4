"""Issue #43's numbers for the package folder, to give "before and after" in its closing note:
read from the code itself (ast, nothing is imported, so no bpy), plus the `duplicates` command's
count of pairs where that command is on the PATH.

 1. functions outside fibrilfit/cli/ and fibrilfit/ui/ that take the argparse namespace: every
    function (methods and nested functions too) with a named parameter `args` or `opts`, or one
    annotated `argparse.Namespace`; *args and **kwargs are not a namespace and do not count (the
    issue's definition: it gave 67 functions in 18 files, 47 outside cli/ at a2caed5)
 2. `add_argument` calls, in all and outside cli/, per file; with `add_argument_group` calls
    too (the issue's 85 and 57 count both); the files that import argparse
 3. files over 400 lines, and whether each says why in its docstring ("400 lines")
 4. the longest chain of imports between the package's modules (relative imports, also those
    inside functions; `from . import x` is an import of module x where x is one), by DFS on the
    import graph, and every cycle found on the way
 5. the pairs `duplicates` lists over the whole package folder

    python tools/layout_metrics.py [PACKAGE_DIR] [--json PATH]

PACKAGE_DIR defaults to the fibrilfit/ beside tools/.
"""
from __future__ import annotations

import argparse
import ast
import collections
import json
import pathlib
import re
import shutil
import subprocess
import sys

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "fibrilfit"
NAMESPACE_NAMES = ("args", "opts")
NAMESPACE_ANNOTATION = re.compile(r"(?<![\w.])(argparse\.)?Namespace\b")
FRONT_ROOMS = ("cli", "ui")  # the command line and the sidebar: where the namespace belongs
LONG = 400
TOP = "(top level)"


def python_files(package: pathlib.Path) -> list[pathlib.Path]:
    return sorted(p for p in package.rglob("*.py") if "__pycache__" not in p.parts)


def relative(package: pathlib.Path, path: pathlib.Path) -> str:
    return path.relative_to(package).as_posix()


def room(rel: str) -> str:
    """The top-level subpackage a file is in ("cli" for cli/parser.py), or TOP."""
    return rel.split("/")[0] if "/" in rel else TOP


def parse(path: pathlib.Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


# 1. functions that take the namespace

def _namespace_parameter(fn) -> str | None:
    """The parameter through which `fn` takes an argparse namespace, or None."""
    a = fn.args
    for p in [*a.posonlyargs, *a.args, *a.kwonlyargs]:  # not *args, **kwargs
        if p.arg in NAMESPACE_NAMES:
            return p.arg
        if p.annotation is not None:
            text = ast.unparse(p.annotation).strip("'\"")
            if NAMESPACE_ANNOTATION.search(text):
                return p.arg
    return None


def _functions(tree: ast.AST, prefix: str = ""):
    """(qualified name, node) of every function and method, nested ones too."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield prefix + node.name, node
            yield from _functions(node, prefix + node.name + ".")
        elif isinstance(node, ast.ClassDef):
            yield from _functions(node, prefix + node.name + ".")
        else:
            yield from _functions(node, prefix)


def namespace_functions(package: pathlib.Path) -> list[dict]:
    """One row per function that takes the namespace: file, line, name, parameter."""
    rows = []
    for path in python_files(package):
        rel = relative(package, path)
        for name, fn in _functions(parse(path)):
            param = _namespace_parameter(fn)
            if param:
                rows.append({"file": rel, "line": fn.lineno, "function": name, "param": param})
    return rows


def namespace_summary(rows: list[dict]) -> dict:
    outside = [r for r in rows if room(r["file"]) not in FRONT_ROOMS]
    return {"total": len(rows),
            "files": len({r["file"] for r in rows}),
            "outside_cli_ui": len(outside),
            "outside_cli_ui_files": len({r["file"] for r in outside}),
            "by_subpackage": dict(collections.Counter(room(r["file"]) for r in rows)
                                  .most_common()),
            "by_file": dict(collections.Counter(r["file"] for r in rows).most_common()),
            "functions": rows}


# 2. add_argument and argparse

def argparse_use(package: pathlib.Path) -> dict:
    """add_argument and add_argument_group calls per file; the files that import argparse."""
    calls, groups, importers = collections.Counter(), collections.Counter(), []
    for path in python_files(package):
        rel = relative(package, path)
        for node in ast.walk(parse(path)):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
                if node.func.attr == "add_argument":
                    calls[rel] += 1
                elif node.func.attr == "add_argument_group":
                    groups[rel] += 1
            if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "argparse"
                                                    for a in node.names) \
                    or isinstance(node, ast.ImportFrom) and node.module == "argparse" \
                    and not node.level:
                importers.append(rel)

    def outside(counter):
        return sum(n for f, n in counter.items() if room(f) != "cli")
    both = calls + groups
    return {"add_argument": sum(calls.values()), "add_argument_outside_cli": outside(calls),
            "add_argument_by_file": dict(sorted(calls.items())),
            "add_argument_group": sum(groups.values()),
            "with_groups": sum(both.values()), "with_groups_outside_cli": outside(both),
            "argparse_importers": sorted(set(importers))}


# 3. long files

def long_files(package: pathlib.Path, limit: int = LONG) -> list[dict]:
    rows = []
    for path in python_files(package):
        text = path.read_text(encoding="utf-8")
        lines = len(text.splitlines())
        if lines > limit:
            doc = ast.get_docstring(ast.parse(text)) or ""
            rows.append({"file": relative(package, path), "lines": lines,
                         "says_why": f"{limit} lines" in doc.lower()})
    return sorted(rows, key=lambda r: -r["lines"])


# 4. the import graph

def module_name(package: pathlib.Path, path: pathlib.Path) -> str:
    parts = list(path.relative_to(package).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join([package.name, *parts])


def import_graph(package: pathlib.Path) -> dict[str, set[str]]:
    """Module -> the package's modules it imports: relative imports anywhere in the file, and
    absolute ones that name the package. `from X import y` imports module X.y where y is a
    module, else X itself (X's __init__)."""
    modules = {module_name(package, p): p for p in python_files(package)}
    graph = {name: set() for name in modules}
    for name, path in modules.items():
        is_init = path.name == "__init__.py"
        here = name.split(".") if is_init else name.split(".")[:-1]  # its package
        for node in ast.walk(parse(path)):
            targets = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    if node.level - 1 > len(here) - 1:
                        continue  # above the package: not ours
                    base = here[:len(here) - (node.level - 1)]
                else:
                    base = []
                dotted = ".".join(base + ([node.module] if node.module else []))
                for a in node.names:
                    sub = f"{dotted}.{a.name}"
                    targets.append(sub if sub in modules else dotted)
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            for target in targets:
                # `import fibrilfit.x.y` or `from fibrilfit.x import z`: the deepest module named
                while target and target not in modules and "." in target:
                    target = target.rsplit(".", 1)[0]
                if target in modules and target != name:
                    graph[name].add(target)
    return graph


def longest_chain(graph: dict[str, set[str]]) -> tuple[list[str], list[list[str]]]:
    """The longest import chain (as its modules, importer first) and the cycles met.

    DFS with memo of the longest chain from each module; an edge back into the current path
    closes a cycle: it is recorded and not followed, so the chain stays a simple path (with no
    cycle, as the house rules ask, it is the exact longest path). Ties go to the first in name
    order."""
    best: dict[str, list[str]] = {}
    cycles: list[list[str]] = []
    on_path: list[str] = []

    def visit(node):
        if node in best:
            return best[node]
        on_path.append(node)
        longest = [node]
        for nxt in sorted(graph[node]):
            if nxt in on_path:
                cycles.append(on_path[on_path.index(nxt):] + [nxt])
                continue
            chain = visit(nxt)
            if 1 + len(chain) > len(longest):
                longest = [node, *chain]
        on_path.pop()
        best[node] = longest
        return longest

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10 * len(graph) + 100))
    chain = []
    for node in sorted(graph):
        found = visit(node)
        if len(found) > len(chain):
            chain = found
    return chain, cycles


# 5. duplicates

def duplicate_pairs(package: pathlib.Path, seconds: int = 120) -> dict:
    """The pairs the `duplicates` command lists over the whole folder (run in it, as its README
    says for a whole tree): {"pairs": n, "line": its first line} or {"pairs": None, "note": why}."""
    if not shutil.which("duplicates"):
        return {"pairs": None, "note": "not available"}
    done = subprocess.run(["duplicates", "--repo", str(package), "--seconds", str(seconds)],
                          cwd=package, capture_output=True, text=True)
    lines = done.stdout.splitlines()
    first = lines[0] if lines else ""
    incomplete = [line for line in lines if line.startswith("incomplete:")]
    m = re.match(r"(\d+) pairs? of places", first)
    pairs = int(m.group(1)) if m else 0 if first.startswith("no duplicates") else None
    out = {"pairs": pairs, "line": first}
    if incomplete:
        out["incomplete"] = incomplete
    if pairs is None:
        out["note"] = f"could not read its output: {first or done.stderr.strip()[:200]}"
    return out


# the report

def measure(package: pathlib.Path, duplicates: bool = True) -> dict:
    package = pathlib.Path(package).resolve()
    graph = import_graph(package)
    chain, cycles = longest_chain(graph)
    return {"package": str(package),
            "files": len(python_files(package)),
            "namespace_functions": namespace_summary(namespace_functions(package)),
            "argparse": argparse_use(package),
            "long_files": long_files(package),
            "imports": {"modules": len(graph), "edges": sum(map(len, graph.values())),
                        "longest_chain": chain, "longest_chain_imports": max(len(chain) - 1, 0),
                        "cycles": cycles},
            "duplicates": duplicate_pairs(package) if duplicates else {"pairs": None,
                                                                      "note": "not run"}}


def report(m: dict) -> str:
    ns, ap, imp, dup = m["namespace_functions"], m["argparse"], m["imports"], m["duplicates"]
    rooms = ", ".join(f"{r} {n}" for r, n in ns["by_subpackage"].items())
    files = ", ".join(f"{f} {n}" for f, n in ns["by_file"].items())
    calls = ", ".join(f"{f} {n}" for f, n in ap["add_argument_by_file"].items())
    out = [f"layout metrics of {m['package']} ({m['files']} .py files)",
           f"1. functions taking args/opts/argparse.Namespace: {ns['total']} in {ns['files']} "
           f"files; outside cli/ and ui/: {ns['outside_cli_ui']} in "
           f"{ns['outside_cli_ui_files']} files",
           f"   by subpackage: {rooms}",
           f"   by file: {files}",
           f"2. add_argument calls: {ap['add_argument']}, outside cli/: "
           f"{ap['add_argument_outside_cli']}; with add_argument_group "
           f"({ap['add_argument_group']}): {ap['with_groups']}, outside cli/: "
           f"{ap['with_groups_outside_cli']}",
           f"   by file: {calls}",
           f"   files importing argparse: {len(ap['argparse_importers'])} "
           f"({', '.join(ap['argparse_importers'])})"]
    longs = m["long_files"]
    out.append(f"3. files over {LONG} lines: {len(longs)}"
               + "".join(f"\n   {r['file']} {r['lines']} lines, "
                         + ("says why" if r["says_why"] else f"does NOT say why ('{LONG} lines')")
                         for r in longs))
    out.append(f"4. longest import chain: {imp['longest_chain_imports']} imports "
               f"({len(imp['longest_chain'])} modules; graph: {imp['modules']} modules, "
               f"{imp['edges']} imports)\n   " + " -> ".join(imp["longest_chain"]))
    out.append(f"   cycles: {len(imp['cycles'])}" + "".join(
        "\n   " + " -> ".join(c) for c in imp["cycles"]))
    pairs = dup["pairs"]
    out.append(f"5. duplicates pairs: {pairs if pairs is not None else dup['note']}"
               + (f"  ({dup['line']})" if dup.get("line") else "")
               + "".join(f"\n   {line}" for line in dup.get("incomplete", [])))
    return "\n".join(out)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("package", nargs="?", type=pathlib.Path, default=PACKAGE,
                        help="the package folder (default: the fibrilfit/ beside tools/)")
    parser.add_argument("--json", type=pathlib.Path, metavar="PATH",
                        help="also write the numbers as JSON to PATH")
    opts = parser.parse_args(argv)
    if not opts.package.is_dir():
        parser.error(f"no such folder: {opts.package}")
    metrics = measure(opts.package)
    print(report(metrics))
    if opts.json:
        opts.json.parent.mkdir(parents=True, exist_ok=True)
        opts.json.write_text(json.dumps(metrics, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
