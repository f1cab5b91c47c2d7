"""Unit constants for converting at the edges (paper tables, axis labels).

Everything inside the package is SI; multiply a paper value by its unit to
bring it in (``48 * MPA``) and divide to print it (``depth / MM``).
Numbers given as text (command line, CSV rows, nose tables) are read by
``parse_number``, in one form everywhere.
"""
import math
import re

MM = 1e-3
CM = 1e-2
MPA = 1e6
GPA = 1e9
G0 = 9.80665  # standard gravity, m/s^2, for decelerations quoted in g
KG_PER_G_CM3 = 1e3  # 1 g/cm^3 in kg/m^3


# ------------------------------------------------------------ numbers as text
NUMBER_FORM = ("a plain decimal number such as 48, -0.5, .07 or 2.5e-3 (ASCII digits, at most one point, an optional "
               "exponent; no spaces, underscores, inf or nan)")
_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?", re.ASCII)


def parse_number(text) -> float:
    """A finite number from its text, in the one form every input reads (NUMBER_FORM).

    Python's float() also takes '3_0' (as 30), ' 3 ', 'inf', 'nan', 'Infinity' and non-ASCII digits, none of
    which a user writing a number means; a number that overflows to inf ('1e999') is refused too. Raises
    ValueError saying what is allowed. An int or float (from YAML or JSON) is taken as it is if finite.
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        value = float(text)
    elif isinstance(text, str) and _NUMBER.fullmatch(text):
        value = float(text)
    else:
        raise ValueError(f"{text!r} is not a number; allowed: {NUMBER_FORM}")
    if not math.isfinite(value):
        raise ValueError(f"{text!r} is not a finite number; allowed: {NUMBER_FORM}")
    return value
