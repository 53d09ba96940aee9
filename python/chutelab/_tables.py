"""Tables as the CSV files have them: a pandas DataFrame when pandas is installed, else a dict of
NumPy arrays, else a dict of lists. A column is numeric when every non-empty cell is a number
(empty cells become NaN, as pandas reads the files); names, quantities and verdicts stay text
even when they look like numbers (a condition may be called "3")."""

import csv as _csv
import io as _io
import math as _math

try:
    import numpy as _np
except ImportError:  # pragma: no cover - NumPy is optional
    _np = None
try:
    import pandas as _pd
except ImportError:  # pragma: no cover - pandas is optional
    _pd = None


_FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "'")


def _unescape(cell):
    """The apostrophe chutelab's CSV writer puts before a text that a spreadsheet would take as a
    formula (core/csv_field.h) is removed, so names read back as they were."""
    return cell[1:] if len(cell) >= 2 and cell[0] == "'" and cell[1] in _FORMULA_START else cell


def parse_csv(text):
    """CSV text with a header row -> {column: [cell text, ...]} in file order."""
    rows = [[_unescape(c) for c in r] for r in _csv.reader(_io.StringIO(text))]
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    return {name: [r[i] if i < len(r) else "" for r in body] for i, name in enumerate(header)}


def _number(cell):
    if isinstance(cell, bool):
        return None
    if isinstance(cell, (int, float)):
        return cell
    if cell == "":
        return _math.nan
    try:
        return int(cell)
    except ValueError:
        pass
    try:
        return float(cell)
    except ValueError:
        return None


def _column(values, text):
    if text:
        return [v if isinstance(v, str) else str(v) for v in values]
    if not values:
        return []
    if all(isinstance(v, bool) for v in values):
        return list(values)
    numbers = [_number(v) for v in values]
    if any(n is None for n in numbers):
        return list(values)
    if all(isinstance(n, int) for n in numbers):
        return numbers
    return [float(n) for n in numbers]


def table(columns, text_columns=()):
    """{name: cells} -> DataFrame / dict of arrays / dict of lists (see the module docstring)."""
    out = {name: _column(list(cells), name in text_columns) for name, cells in columns.items()}
    if _pd is not None:
        return _pd.DataFrame(out, columns=list(columns.keys()))
    if _np is not None:
        return {name: _np.array(v, dtype=object if v and isinstance(v[0], str) else None)
                for name, v in out.items()}
    return out
