"""--score-layers: only interior layers count, and each scored layer says whether it clashes."""
import pytest
from fibrilfit.model import params as P


def test_score_layers_parameter():
    assert P.make_params(score_layers="all").score_layers == 0
    assert P.make_params(layers=20, score_layers=9).score_layers == 9
    with pytest.raises(P.ParamError, match="score_layers: must leave at least one layer: from 0 to 9"):
        P.make_params(layers=20, score_layers=10)
