"""tools/layout_metrics.py (issue #43's numbers) on a tiny package built in tmp_path: what counts
as a function taking the namespace, where, and the longest import chain."""
import importlib.util
import textwrap

from helpers import ROOT

spec = importlib.util.spec_from_file_location("layout_metrics",
                                              ROOT / "tools" / "layout_metrics.py")
metrics = importlib.util.module_from_spec(spec)
spec.loader.exec_module(metrics)


def _package(root, files: dict):
    for rel, code in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(code), encoding="utf-8")
    return root


def _tiny(tmp_path):
    return _package(tmp_path / "pkg", {
        "__init__.py": "",
        "d.py": "Y = 1\n",
        "cli/__init__.py": "",
        "cli/main.py": """
            def command(args):
                parser.add_argument("--x")
        """,
        "work/__init__.py": "",
        "work/a.py": """
            import argparse
            from . import b

            def run(args):
                def inner(opts):
                    pass

            def typed(ns: argparse.Namespace):
                pass

            def star(*args, **opts):
                pass

            class Walk:
                def __init__(self, args):
                    pass

            def add(parser):
                parser.add_argument("--y")
                parser.add_argument_group("z").add_argument("--z")
        """,
        "work/b.py": """
            def later():
                from .c import X
        """,
        "work/c.py": """
            from ..d import Y
            X = Y
        """})


def test_functions_taking_the_namespace_are_counted_outside_cli(tmp_path):
    rows = metrics.namespace_functions(_tiny(tmp_path))
    found = {(r["file"], r["function"]) for r in rows}
    assert found == {("cli/main.py", "command"), ("work/a.py", "run"),
                     ("work/a.py", "run.inner"), ("work/a.py", "typed"),
                     ("work/a.py", "Walk.__init__")}  # not star(*args, **opts)
    summary = metrics.namespace_summary(rows)
    assert summary["total"] == 5 and summary["files"] == 2
    assert summary["outside_cli_ui"] == 4  # the one in cli/ is not counted
    assert summary["by_subpackage"] == {"work": 4, "cli": 1}


def test_add_argument_calls_and_argparse_importers(tmp_path):
    use = metrics.argparse_use(_tiny(tmp_path))
    assert (use["add_argument"], use["add_argument_outside_cli"]) == (3, 2)
    assert (use["with_groups"], use["with_groups_outside_cli"]) == (4, 3)
    assert use["argparse_importers"] == ["work/a.py"]


def test_the_longest_import_chain_is_found(tmp_path):
    graph = metrics.import_graph(_tiny(tmp_path))
    assert graph["pkg.work.b"] == {"pkg.work.c"}  # an import inside a function counts
    chain, cycles = metrics.longest_chain(graph)
    assert chain == ["pkg.work.a", "pkg.work.b", "pkg.work.c", "pkg.d"]  # 3 imports
    assert cycles == []


def test_a_cycle_is_reported(tmp_path):
    package = _package(tmp_path / "pkg", {"__init__.py": "", "a.py": "from . import b\n",
                                          "b.py": "def f():\n    from .a import g\n"})
    chain, cycles = metrics.longest_chain(metrics.import_graph(package))
    assert len(chain) == 2
    assert cycles == [["pkg.a", "pkg.b", "pkg.a"]]


def test_a_long_file_says_why_or_not(tmp_path):
    body = "x = 1\n" * 401
    package = _package(tmp_path / "pkg", {
        "__init__.py": "",
        "why.py": '"""Over 400 lines because it must be."""\n' + body,
        "mute.py": '"""Long."""\n' + body,
        "short.py": body[:60]})
    assert metrics.long_files(package) == [
        {"file": "mute.py", "lines": 402, "says_why": False},
        {"file": "why.py", "lines": 402, "says_why": True}]
