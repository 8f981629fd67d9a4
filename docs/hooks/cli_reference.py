"""MkDocs hook: fill reference/cli.md's marker with the command line, read from the parser.

The parser is the one `headless.py` and `blender -c fibrilfit` use (fibrilfit.cli.build_parser),
so the reference cannot drift. If it cannot be imported the build fails: an empty reference must
never be published.
"""
from __future__ import annotations

import argparse

MARKER = "<!-- cli-reference -->"
PAGE = "reference/cli.md"


def _cell(text) -> str:
    # "[...]" escaped: help text such as "(x, y, z) [Å/s², default 0.5]" would otherwise read
    # as a reference-style link (mkdocstrings' autorefs then fails --strict on it)
    text = " ".join(str(text).split()).replace("|", "\\|")
    return text.replace("[", "\\[").replace("]", "\\]")


def _help(action: argparse.Action) -> str:
    text = action.help or ""
    if "%(" in text:
        values = {**vars(action), "prog": "", "default": action.default}
        if action.choices is not None:
            values["choices"] = ", ".join(map(str, action.choices))
        text = text % values
    return text


def _flags(action: argparse.Action) -> str:
    names = ", ".join(f"`{s}`" for s in action.option_strings) or f"`{action.dest}`"
    if action.nargs != 0 and action.option_strings:
        metavar = action.metavar or (
            "{" + ",".join(map(str, action.choices)) + "}" if action.choices else action.dest.upper())
        names += f" {_cell(metavar if isinstance(metavar, str) else ' '.join(metavar))}"
    return names


def _options(parser: argparse.ArgumentParser) -> list[str]:
    rows = []
    for group in parser._action_groups:  # argparse keeps groups only here
        actions = [a for a in group._group_actions
                   if a.help != argparse.SUPPRESS and not isinstance(a, argparse._SubParsersAction)]
        if not actions:
            continue
        rows += [f"**{_cell(group.title)}**", "", "| option | meaning |", "|---|---|"]
        rows += [f"| {_flags(a)} | {_cell(_help(a))} |" for a in actions]
        rows.append("")
    return rows


def _subcommands(parser: argparse.ArgumentParser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {c.dest: c.help for c in action._choices_actions}
            for name, sub in action.choices.items():
                yield name, helps.get(name, ""), sub


def render() -> str:
    from fibrilfit.cli import build_parser  # raises when it cannot be imported: the build fails
    parser = build_parser("headless.py")
    out = [f"## `{parser.prog}` {{#headless}}", "", _cell(parser.description or ""), ""]
    out += ["```", parser.format_usage().strip(), "```", ""]
    subs = list(_subcommands(parser))
    if subs:
        out += ["| command | what it does |", "|---|---|"]
        out += [f"| [`{name}`](#{name}) | {_cell(text)} |" for name, text, _ in subs]
        out.append("")
    for name, text, sub in subs:
        out += [f"## `{name}` {{#{name}}}", "", _cell(sub.description or text), ""]
        out += ["```", sub.format_usage().strip(), "```", ""]
        out += _options(sub)
    return "\n".join(out)


def on_page_markdown(markdown, page, config, files):
    if page.file.src_uri != PAGE:
        return markdown
    if MARKER not in markdown:
        raise RuntimeError(f"{PAGE} lost its marker {MARKER}")
    return markdown.replace(MARKER, render())
