"""Options of the MOVE optimiser: bad values are refused by name."""

from __future__ import annotations

import pytest

from rt_drake import InputError
from rt_drake.shaping import (
    MoveOptimizerError,
    MoveOptimizerOptions,
)


@pytest.mark.parametrize(
    ("field", "value"),
    [("max_tilt_deg", -1.0), ("max_tilt_deg", 90.0), ("max_evaluations", 0),
     ("via_points", 0), ("sigma", 0.0), ("search_grid_weight", 1.5),
     ("search_grid_weight", -0.1), ("finish_tries", 0)],
)  # fmt: skip
def test_bad_options_are_rejected_with_the_name(field, value):
    with pytest.raises(MoveOptimizerError, match=field) as error:
        MoveOptimizerOptions(**{field: value})
    assert isinstance(error.value, InputError)
    assert "\n" not in str(error.value)
