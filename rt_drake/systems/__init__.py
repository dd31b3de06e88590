"""Drake LeafSystems: the retimer, the suction cup and the pick-and-place sequencer."""
