"""Thousands of random mutations of ex1.stp: the reader and the converter answer with our own
clear input errors (which name a line or an instance), never with any other exception."""
import os
import random
import re

from kezuri.toolpath.operations import stepnc
from kezuri.toolpath.ir.errors import InputError

FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = open(os.path.join(FIXTURES, "iso14649", "ex1.stp"), encoding="latin-1").read()
TOKENS = re.findall(r"#\d+|'[^']*'|\.[A-Z_]+\.|-?\d+\.\d*(?:E[+-]?\d+)?|-?\d+|[A-Z_][A-Z0-9_]*|\S", EX1)
JUNK = ["$", "*", "(", ")", ",", ";", "=", "#", "#9999", "'", ".T.", ".X.", "-1.", "1.E400", "0.", "()", "/*", "X"]


def mutate(text: str, rng: random.Random) -> str:
    kind = rng.randrange(6)
    at = rng.randrange(len(text))
    if kind == 0:                                   # delete a short span
        return text[:at] + text[at + rng.randint(1, 12):]
    if kind == 1:                                   # insert junk
        return text[:at] + rng.choice(JUNK) + text[at:]
    if kind == 2:                                   # replace a number by another number
        numbers = list(re.finditer(r"-?\d+\.\d*", text))
        m = rng.choice(numbers)
        value = rng.choice(["0.", "-5.", "1.E-9", "1.E9", "-0.", "180.", "3."])
        return text[:m.start()] + value + text[m.end():]
    if kind == 3:                                   # point a reference elsewhere
        refs = list(re.finditer(r"#\d+", text))
        m = rng.choice(refs)
        return text[:m.start()] + f"#{rng.randint(1, 130)}" + text[m.end():]
    if kind == 4:                                   # swap two instance lines
        lines = text.split("\n")
        data = [i for i, line in enumerate(lines) if line.startswith("#")]
        i, j = rng.sample(data, 2)
        lines[i], lines[j] = lines[j], lines[i]
        return "\n".join(lines)
    token = rng.choice(TOKENS)                      # replace an entity or enum name
    return text.replace(token, rng.choice(["PLANE", "BLOCK", "CARTESIAN_POINT", ".LEFT.", "$", "#2"]), 1)


def test_random_mutations_give_only_clear_input_errors():
    rng = random.Random(14649)
    outcomes = {"converted": 0, "input error": 0}
    for round_ in range(2500):
        text = EX1
        for _ in range(rng.randint(1, 3)):
            text = mutate(text, rng)
        try:
            loaded = stepnc.load_workplan(text)
            if round_ % 5 == 0:
                stepnc.to_program(loaded)
            outcomes["converted"] += 1
        except InputError as error:
            message = str(error)
            assert message and ("line" in message or "#" in message or "workingstep" in message), message
            outcomes["input error"] += 1
    # The mutations are strong enough to break the file often and mild enough to keep it often.
    assert outcomes["input error"] > 300 and outcomes["converted"] > 300, outcomes
