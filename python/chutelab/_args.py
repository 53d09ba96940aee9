"""The keywords of the package's functions checked before the C++ core sees them: the right type,
or InputError naming the keyword (as the command line names a flag); and the core's option
structs filled with them."""

import math as _math
import os as _os
from collections.abc import Mapping as _Mapping
from typing import Iterable, List, Sequence, Union

from ._tables import np as _np
from . import _chutelab

InputError = _chutelab.InputError
EffectsArg = Union[None, str, Sequence[str], _Mapping]


def _refuse(field: str, problem: str) -> Exception:
    """An InputError as the library raises them (file "", line 0, the keyword as field)."""
    e = InputError(f"{field}: {problem}")
    e.file, e.line, e.field, e.problem = "", 0, field, problem
    return e


def _flag(field, value) -> bool:
    """A yes/no keyword takes True or False, not "no" (which bool() would read as True)."""
    if not isinstance(value, (bool, _np.bool_)):
        raise _refuse(field, f"must be True or False, got {value!r}")
    return bool(value)


def _real(field, value, optional=False):
    """A number keyword takes a real number (int, float, NumPy scalar), not a text or a bool; the
    library then checks that it is finite and in range."""
    if value is None and optional:
        return None
    if isinstance(value, (bool, _np.bool_, str, bytes)) or not hasattr(value, "__float__"):
        raise _refuse(field, f"must be a number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise _refuse(field, f"must be a number, got {value!r}") from None


def _whole(field, value, optional=False):
    """A count keyword takes a whole number: 2 or 2.0, not 1.5, "2" or True."""
    if value is None and optional:
        return None
    f = None
    if not isinstance(value, (bool, _np.bool_, str, bytes)) and hasattr(value, "__float__"):
        try:
            f = float(value)
        except (TypeError, ValueError, OverflowError):
            f = None
    if f is None or not _math.isfinite(f) or f != int(f):
        raise _refuse(field, f"must be a whole number, got {value!r}")
    return int(f)


def _seed_like(field, value):
    """seed and self_check go to the library's own check (whole, in range, exact for huge ints)."""
    if isinstance(value, (str, bytes, bool, _np.bool_)) or not (hasattr(value, "__index__") or
                                                                  hasattr(value, "__float__")):
        raise _refuse(field, f"must be a whole number, got {value!r}")
    return value


def _text(field, value) -> str:
    """A text keyword (a quality, a condition) takes a str; None is the default."""
    if value is None:
        return ""
    if not isinstance(value, str):
        raise _refuse(field, f"must be a text, got {value!r}")
    return value


def _path(field, value, optional=True) -> str:
    """A file or folder keyword takes a str or a path (pathlib.Path); None is "not given"."""
    if value is None and optional:
        return ""
    if isinstance(value, (str, _os.PathLike)):
        p = _os.fspath(value)
        if isinstance(p, str):
            return p
    raise _refuse(field, f"must be a path (str or pathlib.Path), got {value!r}")


def _reals(field, values) -> List[float]:
    """A list keyword of numbers takes one number or a sequence of them (not a text)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        return [_real(field, values)]
    return [_real(field, v) for v in values]


def _texts(field, values) -> List[str]:
    """A list keyword of names takes one str or a sequence of str."""
    if isinstance(values, str):
        return [values]
    if not hasattr(values, "__iter__") or isinstance(values, bytes):
        raise _refuse(field, f"must be a text or a list of texts, got {values!r}")
    out = []
    for v in values:
        if not isinstance(v, str):
            raise _refuse(field, f"must be a text or a list of texts, got {values!r}")
        out.append(v)
    return out


def _effect_args(effects: EffectsArg, key: str = "effects") -> List[str]:
    """{"air_drag": 0.7, "belt_slip": "fit"}, ["air_drag=0.7"], "air_drag=fit" or None -> the
    library's NAME=VALUE strings; errors name `key`."""
    if effects is None:
        return []
    if isinstance(effects, str):
        return [effects]
    if isinstance(effects, _Mapping):
        out = []
        for name, value in effects.items():
            if not isinstance(name, str):
                raise _refuse(key, f"names an effect by {name!r}; use its name as a text")
            if isinstance(value, str):
                out.append(f"{name}={value}")
            else:
                out.append(f"{name}={_real(key, value)!r}")
        return out
    if isinstance(effects, Iterable):
        items = list(effects)
        if all(isinstance(e, str) for e in items):
            return items
    raise _refuse(key, f"must be {{name: value or \"fit\"}} or a list of \"name=value\", got {effects!r}")


def _model_list(models) -> List[str]:
    """"korzen,booth-cema" or a list of names; an empty item is passed on for the library to refuse."""
    if isinstance(models, str):
        return models.split(",") if models else []
    if isinstance(models, Iterable):
        items = list(models)
        if all(isinstance(m, str) for m in items):
            return items
    raise _refuse("models", f"must be model names (a list of texts), got {models!r}")


def _new(cls):
    """An instance made by this module's functions (the classes have no public constructor)."""
    return cls.__new__(cls)


def _options(options, **checked):
    """The module's option struct `options` with the keywords, already checked, set in their order
    (a keyword's own check in C++, the seed's, then comes at its place)."""
    for key, value in checked.items():
        setattr(options, key, value)
    return options
