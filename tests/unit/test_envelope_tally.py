"""The decorated fibril's envelope: radial distances of the domain centres from the fibril axis."""


def test_restarts_tally_the_envelope_over_seeds():
    from fibrilfit.search import restarts
    runs = [{"params": {"seed": s}, "status": "ok", "accommodated": True, "verdict": "successful",
             "clashing_pairs": [], "max_overlap": 0.0, "max_bond_stretch": 0.0,
             "frames_simulated": 100, "envelope": {"outer_diameter": d}}
            for s, d in ((0, 120.0), (1, 150.0), (2, 130.0))]
    tally = restarts.tally(runs + [{"params": {"seed": 3}, "status": "failed"}])
    assert tally["outer_diameter"] == {"median": 130.0, "min": 120.0, "max": 150.0}
    assert [r.get("outer_diameter") for r in tally["runs"]] == [120.0, 150.0, 130.0, None]
