"""Writes Python dicts as TOML text for the scenario reader: the Python scene goes through the same
checks, and gives the same messages, as a TOML file. Floats are written with repr(), the shortest
text that reads back to the same double, so a scene gives bit-identical results either way."""
import math
import re

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k):
    if not isinstance(k, str):
        raise TypeError(f"TOML keys are strings, not {type(k).__name__}: {k!r}")
    if _BARE_KEY.match(k):
        return k
    return _string(k)


def _string(s):
    out = ['"']
    for ch in s:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _tolist(v):
    """NumPy arrays and scalars become plain Python values."""
    if hasattr(v, "tolist") and not isinstance(v, (str, bytes)):
        return v.tolist()
    return v


def value(v):
    """One TOML value (inline): bool, int, float, str, list/tuple, dict."""
    v = _tolist(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} as TOML: {v!r}")


def _is_table_array(v):
    v = _tolist(v)
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def dumps(root):
    """TOML text of a dict: top-level scalars and arrays first, then [tables] and [[arrays of
    tables]] (their own sub-tables written inline)."""
    lines = []
    for k, v in root.items():
        if not isinstance(_tolist(v), dict) and not _is_table_array(v):
            lines.append(f"{_key(k)} = {value(v)}")
    for k, v in root.items():
        if isinstance(_tolist(v), dict):
            lines.append("")
            lines.append(f"[{_key(k)}]")
            lines.extend(f"{_key(kk)} = {value(vv)}" for kk, vv in v.items())
    for k, v in root.items():
        if _is_table_array(v):
            for entry in v:
                lines.append("")
                lines.append(f"[[{_key(k)}]]")
                lines.extend(f"{_key(kk)} = {value(vv)}" for kk, vv in entry.items())
    return "\n".join(lines) + "\n"
