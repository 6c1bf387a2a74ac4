"""ASCII for characters LaTeX has no command for, so that a name in any script (an area or a
file named in Chinese, Arabic, Greek ...) reaches BibTeX and the PDF instead of stopping a run."""

from __future__ import annotations

import unicodedata
from collections.abc import Mapping


def transliterate(char: str, specials: Mapping[str, str]) -> str:
    """``char`` in ASCII LaTeX: its base letters when it decomposes to them (``specials`` maps
    TeX's special characters to their escapes), its value when it is a digit of any script, a
    space for a space and nothing for a control or format character, else its code point
    ``U+XXXX`` (so a name stays readable and distinct; the pages show it as written).

    >>> transliterate("\u0663", {}), transliterate("\u6e2f", {}), transliterate("\ufb01", {})
    ('3', 'U+6E2F', 'fi')
    """
    base = "".join(c for c in unicodedata.normalize("NFKD", char) if ord(c) < 128)
    if base.strip():
        return "".join(specials.get(c, c) for c in base)
    if unicodedata.digit(char, None) is not None:
        return str(unicodedata.digit(char))
    category = unicodedata.category(char)
    if category.startswith(("Z", "C")):
        return " " if category == "Zs" else ""
    return f"U+{ord(char):04X}"
