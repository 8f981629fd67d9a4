"""Code and case files cite the documentation as `docs/<page>.md#<anchor>`: every cited page
and anchor exists, and nothing cites a README section title (the README is a front page)."""
import pathlib
import re
import unicodedata

ROOT = pathlib.Path(__file__).resolve().parents[2]
CITE = re.compile(r"docs/([\w./-]+\.md)(?:#([\w-]+))?")
README_TITLE = re.compile(r"README[,:]? *[\"'“A-Z]")  # (README, "Settling") and the like
SOURCES = [ROOT / "headless.py", ROOT / "Makefile",
           *[p for d in ("fibrilfit", "tests", "tools", "bench", "examples")
             for p in (ROOT / d).rglob("*") if p.suffix in (".py", ".toml")]]
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*(?:\{#([\w-]+)[^}]*\})?\s*$")


def slug(title: str) -> str:
    """Python-Markdown's toc slugify: what an anchor without an explicit {#id} is called."""
    text = unicodedata.normalize("NFKD", title).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


def anchors(page: pathlib.Path) -> set:
    found, fenced = set(), False
    for line in page.read_text(encoding="utf-8").splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
        m = None if fenced else HEADING.match(line)
        if m:
            found.add(m.group(2) or slug(m.group(1)))
    return found


def citations():
    for path in SOURCES:
        if path.name == pathlib.Path(__file__).name:
            continue
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            for m in CITE.finditer(line):
                yield f"{path.relative_to(ROOT)}:{n}", m.group(1), m.group(2)


def test_code_cites_the_docs():
    assert len(list(citations())) >= 10  # the code's measured numbers point at their pages


def test_every_cited_page_and_anchor_exists():
    missing = []
    for where, page, anchor in citations():
        path = ROOT / "docs" / page
        if not path.is_file():
            missing.append(f"{where}: docs/{page} does not exist")
        elif anchor and anchor not in anchors(path):
            missing.append(f"{where}: docs/{page} has no #{anchor}")
    assert not missing, "\n".join(missing)


def test_nothing_cites_a_readme_section():
    cited = [f"{p.relative_to(ROOT)}:{n}: {line.strip()}" for p in SOURCES
             if p.name != pathlib.Path(__file__).name and "data" not in p.parts
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if README_TITLE.search(line) and "tests/data/README" not in line]
    assert not cited, "\n".join(cited)


def test_the_slug_is_python_markdowns():
    assert slug("Linker integrity over the bake") == "linker-integrity-over-the-bake"
    assert slug("Search: inflate, restarts and the minimal linker") == \
        "search-inflate-restarts-and-the-minimal-linker"
    assert slug("`run` and `sweep` from files") == "run-and-sweep-from-files"


def test_the_front_pages_links_exist():
    """README.md and CONTRIBUTING.md are not in the site (mkdocs --strict does not see them):
    every relative link of theirs names a file that exists, and an anchor its page has."""
    missing = []
    for page in ("README.md", "CONTRIBUTING.md"):
        text = (ROOT / page).read_text(encoding="utf-8")
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if "://" in target:
                continue
            path, _, anchor = target.partition("#")
            if not (ROOT / path).exists():
                missing.append(f"{page}: {target}")
            elif anchor and anchor not in anchors(ROOT / path):
                missing.append(f"{page}: {target} (no such anchor)")
    assert not missing, "\n".join(missing)



# A path into the repository, as text names it: `tests/blender/test_ui.py`, fibrilfit/ui/ ...
NAMED_PATH = re.compile(r"(?<![\w/.-])((?:fibrilfit|tests|tools|bench|docs|examples|\.ci)/"
                        r"[\w/.-]*\w)")


# Folders .gitignore names (wheels/, out/, dist/): made by make targets, absent from a clone.
MADE = {line.strip().strip("/") for line in (ROOT / ".gitignore").read_text().splitlines()
        if line.strip().endswith("/")}


def missing_paths(where: str, text: str) -> list[str]:
    """The repository paths `text` names that are neither a file nor a folder (a page may be
    named without its .md); globs, placeholders and the folders make targets write are
    skipped."""
    return [f"{where}:{n}: {m.group(1)}"
            for n, line in enumerate(text.splitlines(), 1) for m in NAMED_PATH.finditer(line)
            if line[m.end():m.end() + 1] not in ("*", "{", "<")
            and not MADE & set(m.group(1).split("/"))
            and not (ROOT / m.group(1)).exists() and not (ROOT / (m.group(1) + ".md")).exists()]


def test_the_files_the_text_names_exist():
    """The move left no text naming a file where it used to be (tests/test_search.py and the
    like): every repository path named in the docs, the front pages, the code and the tests
    is a file or folder that exists."""
    texts = [*SOURCES, ROOT / "README.md", ROOT / "CONTRIBUTING.md",
             *(ROOT / "docs").rglob("*.md"), *(ROOT / "tests" / "data").glob("*.md")]
    texts = [p for p in texts if p.name != pathlib.Path(__file__).name]
    assert sum(len(NAMED_PATH.findall(p.read_text(encoding="utf-8"))) for p in texts) > 50
    missing = [m for p in texts
               for m in missing_paths(str(p.relative_to(ROOT)), p.read_text(encoding="utf-8"))]
    assert not missing, "\n".join(missing)


def test_a_stale_path_is_caught():
    assert missing_paths("page.md", "see tests/test_search.py, fibrilfit/model/helix.py,\n"
                         "docs/model/search and tests/blender/test_*.py") == \
        ["page.md:1: tests/test_search.py"]
    assert missing_paths("page.md", "fetched into fibrilfit/wheels/ by make extension") == []
