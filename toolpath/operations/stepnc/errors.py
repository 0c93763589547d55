"""What goes wrong reading an ISO 14649 file, in two kinds kept apart (see :mod:`.model`):
:class:`StepNcError` for malformed data, :class:`UnsupportedEntity` for valid data this converter does
not machine."""
from __future__ import annotations

from ...ir.errors import InputError


class StepNcError(InputError):
    """Malformed ISO 14649 data; the message names the instance and the attribute."""


class UnsupportedEntity(Exception):
    """Valid data that this converter cannot machine (the workingstep is skipped)."""

    def __init__(self, type_name: str, instance_id: int, detail: str = ""):
        self.type_name = type_name
        self.instance_id = instance_id
        self.detail = detail
        text = f"{type_name} #{instance_id} is not supported"
        super().__init__(text + (f" ({detail})" if detail else ""))
