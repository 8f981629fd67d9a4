"""What a search is worth, said once: each protocol's search in words, as every answer that gives
P(fit) names it, and the restarts a search makes by default (docs/model/search.md#search).

One search per question: `report` and `minimal-linker` (and `largest-fraction`) search with
inflate unless asked otherwise; `run` relaxes with the protocol asked, the tutorial's gravity
bake by default, so `run --restarts R` counts that bake's hits. Plain Python: the plans
(search/plans.py), the printed result and the report read the same words.
"""
from __future__ import annotations

# Restarts a length, the one default of every command that runs a search (minimal-linker,
# largest-fraction, report; the sidebar's; `run --restarts` has none: without it one run)
DEFAULT_RESTARTS = 8
# Each protocol's search in words, as every answer that gives P(fit) names it (one search per
# question: report and minimal-linker use inflate unless asked; run, the tutorial's bake):
# docs/model/search.md#search
SEARCHES = {
    "inflate": "inflate (globules grown from small and regrown when jammed), the search report "
               "and minimal-linker use; a miss is still no proof that no layout exists",
    "tutorial": "the tutorial's gravity bake, a weak search: its misses are no evidence that no "
                "layout exists (report and minimal-linker search with inflate)",
}


def search_words(protocol: str) -> str:
    """The protocol's search in words (SEARCHES), or its name for one not described there."""
    return SEARCHES.get(protocol, f"protocol {protocol}")
