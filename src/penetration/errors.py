"""The package's error types, on the ground floor: every module may raise them, none is imported by them."""
from __future__ import annotations


class ParameterError(ValueError):
    """A parameter (of a nose, a material, a shot, a config or a scene) outside its allowed range: names the owner,
    the field, the value and what is allowed."""

    def __init__(self, owner, name, value, allowed):
        self.owner, self.name, self.value, self.allowed = owner, name, value, allowed
        where = f"{owner}: {name}" if " " in str(owner) else f"{owner}.{name}"
        super().__init__(f"{where} = {value!r} is not allowed: {allowed}")
