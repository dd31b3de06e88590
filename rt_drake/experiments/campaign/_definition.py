"""A loaded campaign: its rows, each row's trial scenario, its content hash.

Trial ``i`` of every object and cup carries the object between the same
pair of poses: the ``i``-th pair sampled (with the campaign's seed) from the
base scenario's ``random_transport`` regions, raised by the object's grasp
height minus the base object's (``p_OC.z``; for boxes gripped on their top
face, half the difference of their heights), so every object lies where the
base object would. The comparisons of one trial are paired: same path, same
poses, same planner seed (campaign seed + trial).

The content hash (SHA-256) covers the resolved campaign (objects with their
grasps, cups, trials, seed, variants) and the bytes of the base scenario,
every object model and uncertainty file: a results database holds the rows
of one content hash only.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path

from pydrake.common.schema import Transform
from pydrake.math import RigidTransform

from rt_drake.errors import ScenarioError
from rt_drake.experiments.campaign._campaign_errors import CampaignError
from rt_drake.experiments.campaign._catalogue import (
    CampaignCup,
    CampaignObject,
)
from rt_drake.experiments.campaign._row_types import (
    RowKey,
    Variant,
)
from rt_drake.experiments.campaign._spec import (
    parse_cups,
    parse_objects,
    parse_variants,
    read_campaign_file,
)
from rt_drake.model.resources import resolve_scenario_path
from rt_drake.model.scenario import (
    ObjectConfig,
    Scenario,
    load_scenario,
)
from rt_drake.planning import sample_transports


@dataclasses.dataclass(frozen=True, eq=False)
class Combination:
    """Everything one row needs besides its worker's shared inputs.

    Attributes:
        key: The row.
        obj: The object carried.
        cup: The cup (or multi-cup tool) holding it.
        scenario: The trial's scenario: the base cell with this cup (or
            tool, replacing the base scenario's cup or tool) and this
            object alone, at the trial's start pose, with its goal pose (and
            its uncertainty set, which only the ``robust`` variant holds).
        planner_seed: Seed of the planner (campaign seed + trial).
    """

    key: RowKey
    obj: CampaignObject
    cup: CampaignCup
    scenario: Scenario
    planner_seed: int


@dataclasses.dataclass(frozen=True, eq=False)
class Campaign:
    """A campaign file, loaded and checked (see :func:`load_campaign`)."""

    path: Path
    scenario_path: Path
    scenario: Scenario
    objects: tuple[CampaignObject, ...]
    cups: tuple[CampaignCup, ...]
    trials: int
    seed: int
    variants: tuple[Variant, ...]
    transports: tuple[tuple[RigidTransform, RigidTransform], ...]
    canonical: str
    content_hash: str

    def row_keys(self) -> list[RowKey]:
        """Every row: object x cup x trial x variant, in that nesting order."""
        return [
            RowKey(obj.name, cup.name, self.seed, trial, variant)
            for obj in self.objects
            for cup in self.cups
            for trial in range(self.trials)
            for variant in self.variants
        ]

    def combination(self, key: RowKey) -> Combination:
        """The object, cup and trial scenario of row ``key``.

        Raises:
            CampaignError: the key is not a row of this campaign.
        """
        objects = {obj.name: obj for obj in self.objects}
        cups = {cup.name: cup for cup in self.cups}
        if (
            key.object not in objects
            or key.cup not in cups
            or key.seed != self.seed
            or not 0 <= key.trial < self.trials
            or key.variant not in self.variants
        ):
            raise CampaignError(f"{self.path}: no row {key} in this campaign")
        obj, cup = objects[key.object], cups[key.cup]
        scenario = self._trial_scenario(obj, cup, key.trial)
        return Combination(key, obj, cup, scenario, key.seed + key.trial)

    def cup_scenario(self, cup: CampaignCup) -> Scenario:
        """The base scenario with ``cup`` (or its tool) instead of its own."""
        return dataclasses.replace(self.scenario, cup=cup.parameters, tool=cup.tool)

    def _trial_scenario(
        self, obj: CampaignObject, cup: CampaignCup, trial: int
    ) -> Scenario:
        transport = self.scenario.random_transport
        assert transport is not None  # checked by load_campaign
        base = self.scenario.object(transport.object)
        X_OC_base = base.grasp.GetDeterministicValue()
        lift = obj.X_OC.translation()[2] - X_OC_base.translation()[2]
        X_start, X_goal = (
            RigidTransform(X.rotation(), X.translation() + [0.0, 0.0, lift])
            for X in self.transports[trial]
        )
        carried = ObjectConfig(
            name=obj.name,
            model=obj.model,
            start=Transform(X_start),
            goal=Transform(X_goal),
            approach_offset=base.approach_offset,
            grasp=Transform(obj.X_OC),
            uncertainty=obj.uncertainty_set,
        )
        return dataclasses.replace(
            self.cup_scenario(cup), objects=[carried], random_transport=None
        )


def load_campaign(path: str | Path) -> Campaign:
    """Load, check and hash a campaign file.

    Raises:
        CampaignError: one line naming the file, key and value: a missing or
            malformed file, unknown key, unknown scenario, model or variant,
            a cup out of range, fewer than one trial.
    """
    path = Path(path).resolve()
    spec = read_campaign_file(path)
    scenario_path, scenario = _base_scenario(path, spec.scenario)
    if spec.cup_physics:
        try:
            scenario = scenario.with_cup_physics(spec.cup_physics)
        except ScenarioError as error:
            message = str(error).split("key ", 1)[-1]
            raise CampaignError(f"{path}: key 'cup_physics': {message}") from None
    transport = scenario.random_transport
    if transport is None:
        raise CampaignError(
            f"{path}: key 'scenario': {scenario_path} has no 'random_transport' "
            "section (the regions where transports are sampled)"
        )
    if spec.trials < 1:
        raise CampaignError(f"{path}: key 'trials': must be >= 1, got {spec.trials}")
    objects = parse_objects(path, spec, scenario.object(transport.object).grasp)
    cups = parse_cups(path, spec.cups)
    variants = parse_variants(path, spec.variants)
    canonical = json.dumps(
        {
            "scenario": _file_hash(scenario_path),
            "objects": [
                {
                    "name": obj.name,
                    "model": obj.model,
                    "model_sha256": _file_hash(obj.file),
                    "X_OC": obj.X_OC.GetAsMatrix34().round(12).tolist(),
                    "uncertainty_sha256": obj.uncertainty
                    and _file_hash(obj.uncertainty),
                }
                for obj in objects
            ],
            "cups": [cup.as_dict() for cup in cups],
            "trials": spec.trials,
            "seed": spec.seed,
            "variants": [v.value for v in variants],
            # Only when given: the hashes of earlier campaigns stay the same.
            **({"cup_physics": spec.cup_physics} if spec.cup_physics else {}),
        },
        sort_keys=True,
    )
    return Campaign(
        path=path,
        scenario_path=scenario_path,
        scenario=scenario,
        objects=objects,
        cups=cups,
        trials=spec.trials,
        seed=spec.seed,
        variants=variants,
        transports=tuple(sample_transports(scenario, spec.trials, spec.seed)),
        canonical=canonical,
        content_hash=hashlib.sha256(canonical.encode()).hexdigest(),
    )


def _base_scenario(path: Path, name: str) -> tuple[Path, Scenario]:
    """The scenario file beside the campaign, or a shipped one of that name."""
    if not name:
        raise CampaignError(f"{path}: key 'scenario': name the base scenario")
    try:
        local = path.parent / name
        scenario_path = local if local.is_file() else resolve_scenario_path(name)
        return scenario_path, load_scenario(scenario_path)
    except ScenarioError as error:
        raise CampaignError(f"{path}: key 'scenario': {error}") from None


def _file_hash(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


__all__ = ["Campaign", "Combination", "load_campaign"]
