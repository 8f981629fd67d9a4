"""What `run --ensemble` asks of the sampler, declared once (plans.py `option()`): the command
line, the sidebar and the Python API take it from here (docs/model/ensemble.md#use).

    --ensemble SWEEPS  [--ensemble-replicas R]  [--ensemble-burn-in B]  [--ensemble-map FILE.mrc]
                       [--ensemble-volume]

Plain Python: no bpy, no numpy.
"""
from __future__ import annotations

import dataclasses

from ..plans import Plan, PlanError, option

GROUP = "the ensemble (docs/model/ensemble.md)"
MAX_SWEEPS = 100_000


@dataclasses.dataclass(frozen=True)
class EnsemblePlan(Plan):
    """The ensemble of a run's model sampled from its relaxed layout (0 sweeps: none)."""

    ensemble: int = option(0, "after the run, sample the model's layouts (every valid layout "
                              "equally likely) from the relaxed one for SWEEPS kept sweeps, "
                              "seeded by the run's seed; the result gets an 'ensemble' block "
                              "(0: off)", lo=0, hi=MAX_SWEEPS, unit="sweeps", metavar="SWEEPS",
                           group=GROUP, label="Ensemble sweeps")
    ensemble_replicas: int = option(16, "Markov chains sampled at once (the first half and the "
                                        "second are the two halves compared)", lo=2, hi=1024,
                                    metavar="R", group=GROUP, label="Replicas")
    ensemble_burn_in: int = option(30, "sweeps with no overlap anywhere before any layout is "
                                       "kept (the start's overlaps repaired first)", lo=1,
                                   hi=MAX_SWEEPS, unit="sweeps", metavar="B", group=GROUP,
                                   label="Burn-in")
    ensemble_map: str | None = option(None, "write the ensemble's helically averaged density "
                                            "map (MRC, needs mrcfile)", kind="path",
                                      metavar="FILE.mrc", group=GROUP, label="Map")
    ensemble_volume: bool = option(False, "add the ensemble's density over the fibril to the "
                                          "scene as a Volume object in the model's collection "
                                          "(Blender's Geometry Nodes; saved with --blend, shown "
                                          "by --render; docs/model/ensemble.md#volume)",
                                   group=GROUP, label="Density volume")

    def check(self) -> None:
        if self.ensemble_map and not self.ensemble:
            raise PlanError("ensemble_map", "only with --ensemble SWEEPS (at least 1)")
        if self.ensemble_volume and not self.ensemble:
            raise PlanError("ensemble_volume", "only with --ensemble SWEEPS (at least 1)")

    @property
    def on(self) -> bool:
        return self.ensemble > 0
