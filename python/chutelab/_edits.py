"""A Dataset's tables as edited, back to the files' text, so that the C++ reader checks an edit as
it checks a file: the measurements and trajectory tables are the files' columns (written whole);
the conditions table is resolved per condition, so its edits are written onto conditions.csv's own
rows (matched by position, or by condition name when rows were added or dropped), and every cell
not edited keeps its text."""

import math

from ._tables import np
from . import _chutelab


def columns(t):
    """The column names of a DataFrame or a record array."""
    return list(t.columns) if hasattr(t, "columns") else list(t.dtype.names or ())


def rows(t):
    """The rows of a table as dicts of plain Python values."""
    names = columns(t)
    cols = [list(t[c].tolist()) if hasattr(t[c], "tolist") else list(t[c]) for c in names]
    return [dict(zip(names, r)) for r in zip(*cols)] if cols else []


def index_of(t, k):
    """The label of row k (a DataFrame's index; a record array's position)."""
    return t.index[k] if hasattr(t, "index") else k


def copy(t):
    return t.copy(deep=True) if hasattr(t, "equals") else np.array(t, copy=True).view(type(t))


def same(a, b):
    """The same table (values, columns, row labels), NaN equal to NaN."""
    if hasattr(a, "equals") != hasattr(b, "equals"):
        return False
    if hasattr(a, "equals"):
        return a.equals(b)
    try:
        if a.dtype != b.dtype or a.shape != b.shape:
            return False
        for n in a.dtype.names or ():
            x, y = np.asarray(a[n]), np.asarray(b[n])
            if x.dtype.kind == "f":
                if not np.array_equal(x, y, equal_nan=True):
                    return False
            elif not np.array_equal(x, y):
                return False
        return True
    except (TypeError, ValueError, AttributeError):
        return False


def cell(v):
    """A value as a CSV cell: None or NaN empty, a number as a float, anything else as text."""
    if v is None:
        return None
    if isinstance(v, (bool, np.bool_)):
        return str(v)
    if isinstance(v, (int, float, np.integer, np.floating)):
        f = float(v)
        return None if math.isnan(f) else f
    return v if isinstance(v, str) else str(v)


def equal(a, b):
    ca, cb = cell(a), cell(b)
    if ca is None or cb is None:
        return ca is None and cb is None
    try:
        return bool(ca == cb)
    except (TypeError, ValueError):
        return False


def table_csv(t):
    """A measurements or trajectory table as its file's text: every column, every row."""
    names = columns(t)
    return _chutelab.csv_text(names, [[cell(r[c]) for c in names] for r in rows(t)])


def conditions_csv(now, seen, original, shown):
    """conditions.csv with the edits of the conditions table (`now` against `seen`, the table as it
    was read from `original`) written onto its rows."""
    header, cells = _chutelab.csv_cells(original, shown)
    header = list(header)
    cells = [list(c) for c in cells]
    now_rows, seen_rows = rows(now), rows(seen)
    seen_names = set(columns(seen))
    if "condition" not in columns(now):
        raise KeyError("condition")
    # A row keeps its file row by its name (rows sorted, added or dropped); renamed rows, when the
    # count is unchanged, by their place.
    by_name = {r["condition"]: i for i, r in enumerate(seen_rows)}
    names = [r["condition"] for r in now_rows]
    if all(n in by_name for n in names) or len(now_rows) != len(seen_rows):
        match = [by_name.get(n) for n in names]
    else:
        match = list(range(len(now_rows)))
    out = []
    for r, j in zip(now_rows, match):
        row = list(cells[j]) if j is not None else [None] * len(header)
        for c, v in r.items():
            if j is not None and c in seen_names and equal(v, seen_rows[j][c]):
                continue  # not edited: the file's own text stays
            if c not in header:
                header.append(c)
                for other in out + [row]:
                    other.append(None)
                for other in cells:
                    other.append(None)
            row[header.index(c)] = cell(v)
        out.append(row)
    return _chutelab.csv_text(header, out)
