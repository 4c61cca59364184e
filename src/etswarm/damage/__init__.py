"""Damage: parse ``KIND REGION [at=TIME]`` specifications and apply them to a world."""

from etswarm.damage.apply import apply_damage, select
from etswarm.damage.spec import KINDS, DamageSpec, parse_damage

__all__ = ["KINDS", "DamageSpec", "apply_damage", "parse_damage", "select"]
