"""The turn-mill workflow's error."""
from __future__ import annotations

from ...ir.errors import InputError


class TurnMillError(InputError):
    """Input the turn-mill workflow cannot use; the message names what is wrong."""
