"""Tables as the package returns them: a pandas DataFrame when pandas is installed, else a NumPy
record array with the same column names (numbers as float64/int64, flags as bool, names as str).
The columns arrive from the C++ core as NumPy arrays of its doubles, never as text."""

try:
    import numpy as np
except ImportError as e:  # pragma: no cover - NumPy is required
    raise ImportError("chutelab needs NumPy: install python3-numpy (Debian) or `pip install numpy`") from e
try:
    import pandas as _pd
except ImportError:  # pragma: no cover - pandas is optional
    _pd = None


def have_pandas() -> bool:
    return _pd is not None


def table(columns):
    """{name: array or list of str} -> DataFrame, or a NumPy record array without pandas."""
    if _pd is not None:
        return _pd.DataFrame({name: values for name, values in columns.items()}, columns=list(columns))
    arrays = []
    for values in columns.values():
        a = np.asarray(values)
        if a.size == 0 and not isinstance(values, np.ndarray):
            a = np.asarray(values, dtype=str)
        arrays.append(a)
    if not arrays:
        return np.rec.array(np.empty(0))
    return np.rec.fromarrays(arrays, names=list(columns))
