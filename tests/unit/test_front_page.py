"""One front door: the site's home page is README.md (docs/hooks/front_page.py puts it in
docs/index.md's place at build time), so the two cannot say different things. Checked here
without building the site: the stub, the hook's place in mkdocs.yml, and that every link of the
README lands on a page of the site once the hook has made it relative to docs/."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
LINK = re.compile(r"\]\((?!https?:|#)([^)\s]+)\)")


def test_the_home_page_is_the_readme():
    stub = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    assert "README.md" in stub and len([l for l in stub.splitlines() if l.startswith("#")]) == 1
    # on GitHub the stub is what a reader of docs/ sees: it says what the project is and where
    # to start, not only a title
    assert "](tutorial.md)" in stub and "](../README.md)" in stub
    assert len([l for l in stub.splitlines() if l.strip() and not l.startswith(("#", "<!--"))]) >= 5
    assert "docs/hooks/front_page.py" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")


def test_every_readme_link_is_a_page_of_the_site():
    links = LINK.findall((ROOT / "README.md").read_text(encoding="utf-8"))
    assert len(links) >= 20
    outside = [link for link in links
               if not (link.startswith("docs/") or link.split("#")[0] == "CONTRIBUTING.md")]
    assert not outside, f"the site has no page for: {outside}"
    missing = [link for link in links if link.startswith("docs/")
               and not (ROOT / link.split("#")[0]).exists()]
    assert not missing, missing
    assert (ROOT / "docs" / "contributing.md").is_file()  # where CONTRIBUTING.md's links go


def test_the_front_page_names_every_command_and_the_tutorial():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for word in ("docs/tutorial.md", "report", "--full-length", "hull", "minimal-linker",
                 "largest-fraction", "inspect", "--periodic auto", "docs/limitations.md", "pip install"):
        assert word in readme, word
    # the tutorial is linked on the first screen (its first 25 lines)
    assert "docs/tutorial.md" in "\n".join(readme.splitlines()[:25])
