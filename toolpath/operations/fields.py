"""The number and choice settings of an operation kind, described once and checked alike.

A kind lists its settings as :class:`Field` s (the name, the bound and its unit, or the choices) in a
:class:`Fields` that says how its numbers are typed; its settings' ``check()`` calls
:meth:`Fields.check` before the rules that relate one setting to another.  The first setting out of
bounds is refused with the kind's own error class, ``what`` (the operation, e.g. "pocket") first:

* typed NUMBER (an int or a float, not a bool, and finite): ``pocket: depth must be a number, got
  nan``; every number of the group is typed before the first bound is checked;
* typed FINITE (what ``math.isfinite`` takes): a value that is not a finite number fails its bound;
* the bounds: ``must be more than 0`` (typed FINITE: ``must be a positive number``), ``must be 0 or
  more``, ``must be at least 0.01 mm``, ``must be from 0.5 to 45 degrees``, ``must be more than 0
  and at most 45 degrees``, ``must be 0 (no helix) or from 0.1 to 100000 mm``, ``must be 0 (the end
  mill's radius) or more``; each followed by ``, got <the value as typed>``;
* the choices: ``must be one of offset, zigzag, got 'spiral'``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

NUMBER = "number"
FINITE = "finite"


@dataclass(frozen=True)
class Field:
    """One setting.  A number from ``low`` (refused itself when ``above``) to ``high``, either end
    open when None, in ``unit`` (named in the words of a range); ``zero``: 0 is taken too, meaning
    this.  A choice: one of ``choices``."""

    name: str
    low: float | None = None
    high: float | None = None
    above: bool = False
    unit: str = ""
    zero: str = ""
    choices: tuple = ()

    def holds(self, value) -> bool:
        """Whether the value (a finite number, or any value for a choice) is within the bound."""
        if self.choices:
            return value in self.choices
        if self.zero and value == 0:
            return True
        if self.low is not None and (value <= self.low if self.above else value < self.low):
            return False
        return self.high is None or value <= self.high

    def rule(self, typing: str) -> str:
        """The bound in words: "must be ..."."""
        if self.choices:
            return f"must be one of {', '.join(self.choices)}"
        if self.low is None and self.high is None:
            return "must be a number"
        unit = f" {self.unit}" if self.unit else ""
        zero = f"0 ({self.zero}) or " if self.zero else ""
        if self.high is not None and self.above:
            return f"must be more than {self.low:g} and at most {self.high:g}{unit}"
        if self.high is not None:
            return f"must be {zero}from {self.low:g} to {self.high:g}{unit}"
        if self.above:
            return "must be a positive number" if typing == FINITE and self.low == 0 else f"must be more than {self.low:g}"
        if self.low == 0:
            return f"must be {zero or '0 or '}more"
        return f"must be {zero}at least {self.low:g}{unit}"


def positive(name: str) -> Field:
    return Field(name, low=0.0, above=True)


def zero_or_more(name: str, zero: str = "") -> Field:
    return Field(name, low=0.0, zero=zero)


def one_of(name: str, choices: tuple) -> Field:
    return Field(name, choices=tuple(choices))


def is_number(value) -> bool:
    """An int or a float (not a bool), finite."""
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)


@dataclass(frozen=True)
class Fields:
    """A group of settings checked in order, their numbers typed NUMBER or FINITE."""

    typing: str
    fields: tuple

    def check(self, settings, what: str, error: type) -> None:
        """Raise ``error`` naming the first setting of ``settings`` that is not typed or not within
        its bound, ``what`` first."""
        typed = self.typing == FINITE
        for field in self.fields:
            value = getattr(settings, field.name)
            if not field.choices and not typed:
                for number in (f for f in self.fields if not f.choices):
                    given = getattr(settings, number.name)
                    if not is_number(given):
                        raise error(f"{what}: {number.name} must be a number, got {given!r}")
                typed = True
            if not self.accepts(field, value):
                raise error(f"{what}: {field.name} {field.rule(self.typing)}, got {value!r}")

    def accepts(self, field: Field, value) -> bool:
        if field.choices or self.typing == NUMBER:
            return field.holds(value)
        try:
            return math.isfinite(value) and field.holds(value)
        except TypeError:
            return False
