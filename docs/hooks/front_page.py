"""MkDocs hook: the site's home page is the repository's README.md, said once.

docs/index.md is only a stub; at build time its Markdown is replaced by README.md's, with the
README's links made relative to docs/ (`docs/guide/install.md` -> `guide/install.md`,
`CONTRIBUTING.md` -> `contributing.md`, the site's page on it). `--strict` then checks every link
as on any page (tests/unit/test_front_page.py checks the same without building the site).
"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
LINK = re.compile(r"(\]\()(?!https?:|#)([^)\s]+)(\))")


def front_page() -> str:
    """README.md with its links as docs/index.md needs them."""
    def relink(m):
        target = m.group(2)
        if target.startswith("docs/"):
            target = target[len("docs/"):]
        elif target.split("#")[0] == "CONTRIBUTING.md":
            target = "contributing.md" + target[len("CONTRIBUTING.md"):]
        return m.group(1) + target + m.group(3)
    return LINK.sub(relink, (ROOT / "README.md").read_text(encoding="utf-8"))


def on_page_markdown(markdown, page, config, files):
    if page.file.src_uri == "index.md":
        return front_page()
    return markdown
