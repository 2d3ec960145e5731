"""The firmware's wire status codes (a copy of firmware/base/cp_status.def).

Codes are frozen and never reused; ``tests/test_status.py`` checks that this table
equals the firmware's. On the wire a status is ``ok`` (code 0) or
``error:<code> <text>``, optionally followed by a cause `` (<keyword> <token>: <limit>)``.
"""
from __future__ import annotations

#: code -> (NAME, text on the wire)
STATUS: dict[int, tuple[str, str]] = {
    0: ("OK", "ok"),
    1: ("UNKNOWN_CMD", "unknown command"),
    2: ("LINE_TOO_LONG", "line too long"),
    3: ("BAD_ARITY", "wrong number of arguments"),
    4: ("BAD_NUMBER", "not a number"),
    5: ("NONFINITE", "non-finite number"),
    6: ("OUT_OF_RANGE", "value out of range"),
    7: ("BUSY", "not allowed while running"),
    8: ("BAD_CHAR", "invalid character in line"),
    9: ("BAD_KEYWORD", "unknown keyword"),
    10: ("NO_JOB", "incomplete job"),
    11: ("RADIUS", "radius not positive on the interval"),
    12: ("DEGENERATE", "degenerate curve"),
    13: ("EMPTY", "empty interval"),
    14: ("TOO_MANY", "count above compile-time maximum"),
    15: ("TOOL", "tool radius too large"),
    16: ("CUSP", "line crosses a cuspidal edge"),
    17: ("TOL", "tolerance cannot be met"),
    18: ("NUMERIC", "numeric failure"),
    19: ("PEER_ERROR", "machine reported an error"),
    20: ("ABORTED", "aborted"),
    21: ("RESUME_RANGE", "resume point out of range"),
    22: ("TIMEOUT", "machine did not answer"),
    23: ("LINK_ERROR", "link error limit reached"),
    24: ("WRONG_SURFACE", "command needs another SURFACE"),
    25: ("OFF_PLANE", "centre curve leaves the Oxz plane"),
    26: ("FRENET", "Frenet frame undefined"),
    27: ("FRAME_REF", "tangent parallel to the frame reference"),
    28: ("SECTION", "section size not positive"),
    29: ("FT_RANGE", "section law outside 0..1"),
    30: ("FOLD", "sweep folds"),
    31: ("TOO_FEW", "too few sections or points"),
    32: ("EXPONENT", "superellipse exponent below 1"),
    33: ("COINCIDENT", "coincident points or centres"),
    34: ("SECTION_PLANE", "section plane contains the chord"),
    35: ("AREA_LAW", "interpolated area or exponent invalid"),
    36: ("ISOTROPIC", "section orientation undefined"),
    37: ("TURN", "turning angle of 90 degrees or more"),
    38: ("TWIST", "twist of 45 degrees or more"),
    39: ("BUFFER", "buffer too small"),
    40: ("NO_FEED", "G-code needs FEED"),
    41: ("NO_SAFE", "G-code needs SAFE"),
    42: ("NO_MACHINE_LINK", "no machine link on this port"),
    43: ("DIALECT", "not in the machine's dialect"),
    44: ("MACHINE_RESET", "machine restarted"),
    45: ("ABOVE_SAFE", "point at or above SAFE"),
    46: ("SEAM", "radius or section law jumps at the seam"),
    47: ("OVERLAP", "parts of the sweep overlap"),
}

#: NAME -> code
CODE: dict[str, int] = {name: code for code, (name, _text) in STATUS.items()}


def status_text(code: int) -> str:
    """The firmware's text for a status code ("unknown status" if the code is not in the table)."""
    return STATUS.get(code, ("", "unknown status"))[1]


def status_name(code: int) -> str:
    """The firmware's NAME of a status code ("" if unknown)."""
    return STATUS.get(code, ("", ""))[0]
