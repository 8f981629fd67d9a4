"""The install guide's measured times (docs/guide/install.md; the sidebar guide quotes the same
runs), read from docs/data/guide/install_times.csv: one row a number the page quotes, with what
was timed, its load average, date, commit, MODEL_VERSION, Blender or bpy, the command and where
the number comes from ("not recorded" where the page never said). Loaded by
docs/hooks/page_numbers.py.

- `install_took(key)`: a row's time as the page writes it, "295 s" or "about 2 min" (the value,
  unit and "about" as the file holds them);
- `install_sum(*keys)`: the sum of rows in seconds, "21 s" (a part of a measured whole, such as
  what Blender waits for after Report…'s workers: the best layout and the pictures)."""
from __future__ import annotations

TIMES = "guide/install_times.csv"


def macros(numbers) -> dict:
    def row(key: str) -> dict:
        found = [r for r in numbers.data(TIMES) if r["key"] == key]
        if len(found) != 1:
            raise KeyError(f"{TIMES}: {len(found)} rows with the key {key!r}")
        return found[0]

    def install_took(key: str) -> str:
        r = row(key)
        return f"{'about ' if r['about'] == 'yes' else ''}{r['value']} {r['unit']}"

    def install_sum(*keys: str) -> str:
        rows = [row(k) for k in keys]
        if any(r["unit"] != "s" or r["about"] == "yes" for r in rows):
            raise ValueError(f"install_sum{keys}: only exact times in seconds add up")
        return f"{sum(r['value'] for r in rows):g} s"

    return {"install_took": install_took, "install_sum": install_sum}
