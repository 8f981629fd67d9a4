"""Words a reader meets first are explained: the glossary (docs/reference/glossary.md) has an entry
for every term README.md and the tutorial use; README.md's first screen uses none of the jargon
before it links it; and no user page sends the reader to something only the developers can
follow (an issue number, a branch, a commit named in prose: a commit is fine in a measurement's
stamp, which names its date or MODEL_VERSION beside it, or in a table). docs/notebook/, the
contributing pages and the changelog are the developers' record and may keep them, and so do the
tables `make validate` writes from the case files (examples/*.toml)."""
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
GLOSSARY = DOCS / "reference" / "glossary.md"

# Every term the README and the tutorial use that a newcomer may not know
TERMS = ["anchor", "joint", "pf_rotation", "pf_rise", "protofilament", "layer", "rise", "twist",
         "linker", "free linker", "globule", "restart", "seed", "protocol", "inflate", "walk",
         "bracket", "envelope", "settled", "BVH", "Wilson", "MODEL_VERSION", "scored layers",
         "bound", "load", "P(fit)", "minimal linker", "verdict", "accommodated", "answer",
         "borderline", "cell", "exit", "report", "fast settings", "grazing"]
# Jargon README.md's first screen must not use before it links it
JARGON = ["protocol", "scored layers", "bound", "MODEL_VERSION", "load", "anchor", "joint",
          "pf_rotation", "restart", "seed", "walk", "bracket", "envelope", "settled", "BVH",
          "Wilson", "P(fit)", "verdict", "accommodated", "inflate", "cell"]
FIRST_SCREEN = 40  # lines


def glossary_headings() -> list[str]:
    heads = re.findall(r"^#{2,4} (.+?)(?:\s*\{#[^}]+\})?\s*$", GLOSSARY.read_text(encoding="utf-8"),
                       re.M)
    return [h.strip().lower() for h in heads]


def word(term: str) -> re.Pattern:
    return re.compile(r"(?<![\w])" + re.escape(term) + r"(?:s|es)?(?![\w])", re.I)


@pytest.mark.parametrize("term", TERMS)
def test_the_glossary_explains_the_term(term):
    heads = glossary_headings()
    assert any(re.search(r"(^|, )" + re.escape(term.lower()) + r"( interval)?(,|$)", h)
               for h in heads), f"no glossary entry for {term!r} (headings: {heads})"


def test_the_list_is_the_pages_own_words():
    """Each term is one the README or the tutorial uses (the list cannot drift into words no
    reader meets)."""
    text = ((ROOT / "README.md").read_text(encoding="utf-8")
            + (DOCS / "tutorial.md").read_text(encoding="utf-8"))
    unused = [t for t in TERMS if not word(t).search(text)]
    assert not unused, unused


def first_unlinked(lines: list[str], term: str) -> str | None:
    """The first line of `lines` where `term` appears outside a link's text, or None; a term
    whose first appearance is a link's text (to a page that explains it) is fine."""
    rx = word(term)
    for line in lines:
        linked = [m.span(1) for m in re.finditer(r"\[([^\]]*)\]\([^)]+\)", line)]
        for m in rx.finditer(line):
            if any(a <= m.start() and m.end() <= b for a, b in linked):
                return None
            return line
    return None


def test_the_readme_first_screen_links_its_jargon_before_using_it():
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()[:FIRST_SCREEN]
    bad = {t: first_unlinked(lines, t) for t in JARGON if first_unlinked(lines, t)}
    assert not bad, f"README.md's first {FIRST_SCREEN} lines use jargon before linking it: {bad}"


def test_the_first_screen_check_catches_an_unlinked_word():
    assert first_unlinked(["the search's hit rate over restarts"], "restart")
    assert first_unlinked(["[P(fit)](docs/reference/glossary.md#p-fit), then P(fit)"],
                          "P(fit)") is None
    assert first_unlinked(["nothing here"], "seed") is None


# ---- internal references --------------------------------------------------------------------
ISSUE = re.compile(r"(?<![\w&/`])#\d+\b|\bissues? #?\d+\b|\bPR #?\d+\b")
BRANCH = re.compile(r"\bbranch(?:es)?\s+`?[a-z0-9][\w./-]*`?\s+at\b|\bbranch\s+`[^`]+`"
                    r"|\bbranch\s+[a-z]+\d[\w-]*")
SHA = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b")
STAMP = re.compile(r"MODEL_VERSION|\b20\d\d-\d\d-\d\d\b")
# a table `make validate` writes from the case files (examples/*.toml): their words, read for
# issue numbers only (a commit there is a row's stamp)
GENERATED = re.compile(r"^<!-- .*: written by make [\w-]+ -->$")
END_GENERATED = re.compile(r"^<!-- end of .* -->$")
SINCE = re.compile(r"\bsince [0-9a-f]{7,40}\b")
DEVELOPERS = ("notebook/", "contributing", "changelog.md")


def internal_references(text: str) -> list[tuple[int, str]]:
    """(line, text) of every issue number, branch and commit named in prose. A commit is a
    measurement's stamp, and fine, in a table row or in a paragraph that names the
    measurement's date or MODEL_VERSION; "since <commit>" never is."""
    found, fence, para = [], False, []

    def close():
        stamped = any(STAMP.search(s) for _, s in para)
        for i, s in para:
            found.extend((i, m.group(0)) for m in SINCE.finditer(s))
            if not stamped and not s.lstrip().startswith("|"):
                found.extend((i, m.group(0)) for m in SHA.finditer(s)
                             if not SINCE.search(s[max(0, m.start() - 6):m.end()])
                             and not s[:m.start()].endswith("@ "))  # another repository's pin
        para.clear()

    generated = False
    for i, line in enumerate(text.splitlines(), 1):
        if GENERATED.match(line) or END_GENERATED.match(line):
            generated = bool(GENERATED.match(line))
            continue
        if line.lstrip().startswith(("```", "~~~")):
            fence = not fence
            close()
            continue
        if generated:  # the case files' words: no issue number either (their commits are stamps)
            found += [(i, m.group(0)) for m in ISSUE.finditer(re.sub(r"`[^`]*`", "``", line))]
            continue
        if fence:
            continue
        if not line.strip():
            close()
            continue
        prose = re.sub(r"`[^`]*`", "``", line)
        found += [(i, m.group(0)) for m in ISSUE.finditer(prose)]
        found += [(i, m.group(0)) for m in BRANCH.finditer(line)]
        para.append((i, prose))
    close()
    return sorted(found)


USER_PAGES = [ROOT / "README.md"] + sorted(
    p for p in DOCS.rglob("*.md") if not p.relative_to(DOCS).as_posix().startswith(DEVELOPERS))


@pytest.mark.parametrize("page", USER_PAGES, ids=[p.name if p.parent == ROOT else
                                                  p.relative_to(DOCS).as_posix()
                                                  for p in USER_PAGES])
def test_a_user_page_has_no_internal_reference(page):
    found = internal_references(page.read_text(encoding="utf-8"))
    assert not found, f"{page.name}: references a reader cannot follow (line, text): {found}"


def test_the_reference_check_finds_them():
    text = ("as quoted in issue #36\nmeasured on branch i23a\nsince ca20ffb the walk stops\n"
            "a table stamp: 2026-11-26, commit 9817027, MODEL_VERSION 5\n| 9817027 | row |\n"
            "```\nsha256 86101cb3bf05\n```\nsee [the bound](model/bound.md#bracket)\n")
    found = [t for _, t in internal_references(text)]
    assert found == ["issue #36", "branch i23a", "since ca20ffb"], found
    # a commit in a dated paragraph is a stamp; "since" is never one
    assert internal_references("measured at 1a2b3c4d,\n2026-11-27, bpy 5.0.1") == []
    assert internal_references("since 1a2b3c4 (2026-11-27)") == [(1, "since 1a2b3c4")]
    # a generated table: its commits are stamps, an issue number is not
    table = ("<!-- validation table: written by make validate -->\n| a | per issue #15 | 9817027 |\n"
             "<!-- end of validation table -->\n")
    assert [t for _, t in internal_references(table)] == ["issue #15"]
