"""The house rules of CONTRIBUTING.md, read from the code itself (ast; nothing is imported):
arrows point down the rooms, no private name crosses a package wall, no path games."""
import ast
import pathlib
import re

from helpers import ROOT

PACKAGE = ROOT / "fibrilfit"
# The rooms, lowest first: a module may import its own room and the rooms before it.
ROOMS = ["exits", "files", "plans", "blender_check", "geom", "model", "ensemble", "structure",
         "builders", "analysis", "pipeline", "exports", "batch", "sweep", "search", "api", "cli", "ui",
         "__init__", "__main__"]


def modules():
    """(path, dotted name of its package as a list, its room) for every module of fibrilfit/."""
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
        package = parts[:-1]
        room = parts[0] if len(parts) > 1 or parts[0] != "__init__" else "__init__"
        yield path, package, room


def relative_imports(path, package):
    """(line, target as a list of names, imported names) of every relative import, also those
    inside functions."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package[:len(package) - (node.level - 1)]
            target = base + (node.module.split(".") if node.module else [])
            yield node.lineno, target, [a.name for a in node.names]


def test_every_room_is_listed():
    found = {room for _, _, room in modules()}
    assert found == set(ROOMS), found ^ set(ROOMS)


def test_arrows_point_down():
    wrong = []
    for path, package, room in modules():
        for line, target, names in relative_imports(path, package):
            # `from .. import pipeline, exits`: each name is a room; `from ..model import x`: one
            rooms = [target[0]] if target else names
            for to in rooms:
                if to in ROOMS and ROOMS.index(to) > ROOMS.index(room):
                    wrong.append(f"{path.relative_to(ROOT)}:{line}: {room} imports {to}")
    assert not wrong, "\n".join(wrong)


def _imported_modules(tree, package):
    """Local name -> the package (as a list) it was imported from, for FibrilFit modules."""
    names = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package[:len(package) - (node.level - 1)]
            target = base + (node.module.split(".") if node.module else [])
            for a in node.names:
                names[a.asname or a.name] = target + [a.name]
    return names


def _is_package(target) -> bool:
    return PACKAGE.joinpath(*target).is_dir()


def _private_crossings(tree, package, is_package=_is_package) -> list[str]:
    """'line: name' for each private name this module takes from another package: `from X
    import _name`, or `module._name` on a FibrilFit module it imported. A module's own package
    and the packages inside it are home; a top-level module (package []) is home only at the
    top level, since each subpackage is a room of its own."""
    def home(package_of_name):
        inside = package_of_name[:len(package)] == package
        return package_of_name == package or (inside and bool(package))

    def private(name):
        return name.startswith("_") and not name.startswith("__")

    crossing = []
    imported = _imported_modules(tree, package)
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package[:len(package) - (node.level - 1)]
            target = base + (node.module.split(".") if node.module else [])
            # `from ..batch import _x` takes it from batch/__init__; `from ..batch.pool` from batch
            owner = target if is_package(target) else target[:-1]
            crossing += [f"{node.lineno}: {a.name}" for a in node.names
                         if private(a.name) and not home(owner)]
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and private(node.attr):
            source = imported.get(node.value.id)
            if source is not None and source[:-1] != package:
                crossing.append(f"{node.lineno}: {node.value.id}.{node.attr}")
    return crossing


def test_no_private_name_crosses_a_package_wall():
    crossing = [f"{path.relative_to(ROOT)}:{found}" for path, package, _ in modules()
                for found in _private_crossings(ast.parse(path.read_text(encoding="utf-8")),
                                                package)]
    assert not crossing, "\n".join(crossing)


def test_the_private_check_sees_each_kind_of_crossing():
    def found(code, package):
        return _private_crossings(ast.parse(code), package, lambda t: t in (["batch"], []))
    # from another subpackage, from a subpackage into a top-level module, from the package root
    assert found("from ..batch.pool import _x", ["sweep"])
    assert found("from .builders.model import _x", [])
    assert found("from ..batch import _x", ["sweep"])
    assert found("from .. import _x", ["sweep"])
    assert found("from ..builders import model\nmodel._x()", ["sweep"])
    assert found("from .builders import model\nmodel._x()", [])
    # at home: its own package, a package inside it, the top level among its own modules
    assert not found("from .runner import _x", ["sweep"])
    assert not found("from .operators.common import _x", ["ui"])
    assert not found("from .exits import _x", [])
    assert not found("from . import runner\nrunner._x()", ["sweep"])
    assert not found("from ..batch import pool\npool.__file__", ["sweep"])


# The one exemption: the installed-extension scenario reproduces what Blender itself does to
# sys.path for an extension's bundled wheels (puts its site-packages first), to test the wheel.
PATH_EXEMPT = {"tests/blender/installed_scenario.py"}
PATH_CODE = re.compile(r"sys\.path\.(insert|append|extend|remove|pop|clear)\("
                       r"|sys\.path\s*(\[[^]]*\]\s*)?=[^=]")


def _changes_sys_path(tree) -> list[int]:
    """Lines that change sys.path: a call of one of its list methods, or an assignment to it."""
    def is_sys_path(node):
        return isinstance(node, ast.Attribute) and node.attr == "path" \
            and isinstance(node.value, ast.Name) and node.value.id == "sys"
    lines = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and is_sys_path(node.func.value) and node.func.attr in (
                    "insert", "append", "extend", "remove", "pop", "clear"):
            lines.append(node.lineno)
        if isinstance(node, (ast.Assign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for t in targets:
                if is_sys_path(t) or isinstance(t, ast.Subscript) and is_sys_path(t.value):
                    lines.append(node.lineno)
        if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and PATH_CODE.search(node.value):  # code run in a subprocess
            lines.append(node.lineno)
    return lines


def test_no_path_games():
    """No sys.path changes and no import-by-path loader module: `make` installs the checkout
    into each venv. Only headless.py and the sweep worker load the package from where they
    are (by importlib, from their own __file__), because Blender's -P runs them as scripts."""
    files = [ROOT / "headless.py", *[p for d in ("fibrilfit", "tests", "tools", "bench")
                                     for p in (ROOT / d).rglob("*.py")]]
    found = [f"{path.relative_to(ROOT)}:{line}" for path in files
             if path.relative_to(ROOT).as_posix() not in PATH_EXEMPT
             and path != pathlib.Path(__file__).resolve()
             for line in _changes_sys_path(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, "\n".join(found)
    assert not list(ROOT.glob("**/_load.py"))


def test_the_path_check_sees_each_kind_of_change():
    for code in ("import sys\nsys.path.insert(0, 'x')", "import sys\nsys.path[:0] = ['x']",
                 "import sys\nsys.path = ['x']", "import sys\nsys.path.remove('x')",
                 "code = 'import sys; sys.path.append(1)'"):
        assert _changes_sys_path(ast.parse(code)), code
    assert not _changes_sys_path(ast.parse("import sys\nprint(sys.path[0])"))


# ---- one plan per command (issue #43): the command line's namespace stays in cli/ ----------
EDGES = ("cli", "ui")  # the rooms that turn a user's input into a plan
NAMESPACE_NAMES = ("args", "opts", "namespace", "ns")


def _argparse_imports(tree) -> list[int]:
    return [node.lineno for node in ast.walk(tree)
            if isinstance(node, ast.Import) and any(a.name == "argparse" for a in node.names)
            or isinstance(node, ast.ImportFrom) and node.module == "argparse"]


def _namespace_takers(tree) -> list[str]:
    """'line: name' of every function (methods and nested ones too) with a parameter named as
    a namespace (args, opts, namespace, ns) or annotated argparse.Namespace; *args is not one."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        a = node.args
        for arg in (*a.posonlyargs, *a.args, *a.kwonlyargs):
            note = ast.unparse(arg.annotation) if arg.annotation is not None else ""
            if arg.arg in NAMESPACE_NAMES or "Namespace" in note:
                found.append(f"{node.lineno}: {getattr(node, 'name', 'lambda')}({arg.arg})")
    return found


def test_argparse_only_under_cli():
    wrong = [f"{path.relative_to(ROOT)}:{line}" for path, _, room in modules() if room != "cli"
             for line in _argparse_imports(ast.parse(path.read_text(encoding="utf-8")))]
    assert not wrong, "argparse imported outside fibrilfit/cli/:\n" + "\n".join(wrong)


def test_no_function_below_the_edges_takes_a_namespace():
    """Below cli/ and ui/ every function takes plans (api/plans.py), never the command line's
    namespace."""
    wrong = [f"{path.relative_to(ROOT)}:{hit}" for path, _, room in modules()
             if room not in EDGES
             for hit in _namespace_takers(ast.parse(path.read_text(encoding="utf-8")))]
    assert not wrong, "\n".join(wrong)


def test_the_namespace_checks_see_what_they_guard():
    """Planted: each kind of namespace-taker and argparse import is found; *args is not."""
    takers = ("def f(args): pass", "def f(p, *, opts=None): pass",
              "def f(x: argparse.Namespace): pass", "class C:\n    def m(self, ns): pass",
              "def outer():\n    def inner(args): pass")
    for code in takers:
        assert _namespace_takers(ast.parse(code)), code
    assert not _namespace_takers(ast.parse("def f(*args, **kwargs): pass"))
    assert not _namespace_takers(ast.parse("def f(plan, executor_plan): pass"))
    for code in ("import argparse", "from argparse import Namespace",
                 "def f():\n    import argparse"):
        assert _argparse_imports(ast.parse(code)), code
    assert not _argparse_imports(ast.parse("import argparser"))
