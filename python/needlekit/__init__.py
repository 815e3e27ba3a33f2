"""needlekit: microneedle design and analysis (P. Boonma, NC State 2012), from Python.

The compiled part (``needlekit._needlekit``, pybind11) carries the C++ API under the same names: ``NeedleGeometry``,
``performance_index``, ``optimize_design``, ``sensitivity_sweep``, ``layered_block_mesh``, ``run_indentation``,
``SurfaceMesh``, ``straightest_geodesic``, ``fit_patch``, ``read_design_file`` ... SI units inside; every quantity
may also be given as a string with its unit (``"230 um"``, ``"169 GPa"``), parsed by needlekit's units parser.
Bad input raises ``needlekit.InvalidInput`` (a ``ValueError``) naming the key, file and line, or the argument and
index. This file adds what is Python only: ``evaluate`` (a design file or design in, a result out),
``evaluate_many`` (arrays of designs), ``to_dict()`` on every result and ``to_dataframe()`` where a table fits.
"""
from __future__ import annotations

import os as _os

import numpy as _np

from . import _needlekit
from ._needlekit import *  # noqa: F401,F403 (the C++ API)
from ._needlekit import InvalidInput, IoError  # noqa: F401

__all__ = [name for name in dir(_needlekit) if not name.startswith("_")] + [
    "evaluate", "evaluate_many", "EvaluateManyResult", "to_dict"]


def _plain(value):
    """A result value as plain Python/numpy: objects with to_dict() become dicts, enums their names."""
    if hasattr(value, "to_dict"):
        return value.to_dict()
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if hasattr(value, "__members__") or type(value).__name__ in _ENUM_NAMES:
        return value.name
    return value


def _properties(cls):
    return [name for name in dir(cls) if not name.startswith("_") and isinstance(getattr(cls, name), property)]


def to_dict(obj) -> dict:
    """Every field of a needlekit object as a dict (SI units; nested objects as dicts, enums as their names)."""
    return {name: _plain(getattr(obj, name)) for name in _properties(type(obj))}


def _repr(obj) -> str:
    fields = ", ".join(f"{name}={getattr(obj, name)!r}" for name in _properties(type(obj))[:8])
    more = ", ..." if len(_properties(type(obj))) > 8 else ""
    return f"{type(obj).__name__}({fields}{more})"


def _rebuild(name: str, fields: dict):
    obj = getattr(_needlekit, name)()
    for key, value in fields.items():
        setattr(obj, key, value)
    return obj


def _reduce(obj):
    """Pickle an input object by its fields (for Dask tasks and multiprocessing)."""
    cls = type(obj)
    return _rebuild, (cls.__name__, {name: getattr(obj, name) for name in _properties(cls)
                                     if getattr(cls, name).fset is not None})


_ENUM_NAMES = {name for name in dir(_needlekit) if hasattr(getattr(_needlekit, name), "__members__")}
for _name in dir(_needlekit):
    _cls = getattr(_needlekit, _name)
    if isinstance(_cls, type) and not _name.startswith("_") and _name not in _ENUM_NAMES and _properties(_cls):
        if not issubclass(_cls, BaseException):
            _cls.to_dict = to_dict
            _cls.__repr__ = _repr
            if all(getattr(_cls, p).fset is not None for p in _properties(_cls) if p != "hollow"):
                try:
                    _cls()
                    _cls.__reduce__ = _reduce
                except TypeError:  # no default constructor: not an input object
                    pass


# Meshes pickle by their arrays (they are immutable from Python: their constructors take the arrays).
TriangleMesh.__reduce__ = lambda self: (TriangleMesh, (_np.array(self.vertices), _np.array(self.triangles)))  # noqa
TetMesh.__reduce__ = lambda self: (TetMesh, (_np.array(self.nodes), _np.array(self.tets),  # noqa: F405
                                             _np.array(self.tet_layer), self.layers))


def evaluate(design, conditions=None, options=None) -> PerformanceIndexResult:  # noqa: F405
    """The performance index of one needle array with every intermediate quantity (``needlekit evaluate``).

    ``design``: a design file path (TOML, as for the CLI), a ``DesignFile`` or an ``ArrayDesign`` (then
    ``conditions`` and ``options`` default to skin, 0 deg, T = 50 um). Quantities of the result are SI (m, m^2, m^3,
    N, 1/m); ``performance_json(design, result)`` gives the CLI's JSON (um, N, 1/um). Raises InvalidInput for a bad
    file (naming file, line and key) or an invalid design.
    """
    if isinstance(design, (str, _os.PathLike)):
        design = read_design_file(_os.fspath(design))  # noqa: F405
    if isinstance(design, DesignFile):  # noqa: F405
        conditions = design.conditions if conditions is None else conditions
        options = design.options if options is None else options
        design = design.design
    return performance_index(design, conditions or InsertionConditions(),  # noqa: F405
                             options or PerformanceIndexOptions())  # noqa: F405


class EvaluateManyResult:
    """The arrays of ``evaluate_many``: one entry per design.

    Real-valued columns (SI, NaN where not assessed): see ``evaluate_many_columns`` for each name and unit.
    Codes: ``status`` (PerformanceStatus values), ``failed_checks`` (bit ``1 << PerformanceStatus`` of every failed
    check: the reason code), ``buckling_method`` (BucklingMethod values), ``bending_ok`` (1, 0, -1: not assessed),
    ``small_tip_branch`` (0/1). ``status_names()`` and ``reasons(i)`` turn codes into words.
    """

    def __init__(self, arrays: dict):
        self.distinct_sections = arrays.pop("distinct_sections")
        self._arrays = arrays
        for key, value in arrays.items():
            setattr(self, key, value)

    def __len__(self):
        return len(self.status)

    def status_names(self) -> _np.ndarray:
        """The status of every design as its name ("ok", "buckles", ...)."""
        names = _np.array([performance_status_name(s) for s in PerformanceStatus.__members__.values()])  # noqa: F405
        return names[self.status]

    def reasons(self, index: int) -> list:
        """The names of every failed check of design ``index`` (first: its status)."""
        return [performance_status_name(s) for s in PerformanceStatus.__members__.values()  # noqa: F405
                if self.failed_checks[index] & (1 << int(s))]

    def to_dict(self) -> dict:
        return dict(self._arrays)

    def to_dataframe(self):
        """A pandas DataFrame: one row per design, the columns named with their SI units."""
        import pandas as pd

        units = dict(evaluate_many_columns)  # noqa: F405
        columns = {(f"{key}_{units[key]}" if units.get(key) else key).replace("^", "").replace("/", "per_"): value
                   for key, value in self._arrays.items()}
        columns["status"] = self.status_names()
        return pd.DataFrame(columns)


def evaluate_many(shape, needles_per_row, tip_diameter, base_diameter, length, width, bore_diameter=0.0, *,
                  angle=0.0, target_depth=50e-6, material="silicon", tissue="skin", options=None
                  ) -> EvaluateManyResult:
    """The performance index of many needle arrays at once (``performance_index`` per design, the same bits).

    Every design argument is a scalar (for all designs) or a 1-D numpy array (one entry per design); float64
    (int64 for ``needles_per_row``) contiguous arrays are read without a copy. Lengths in m (D1, D2, D3, L, w, T),
    ``angle`` in rad; a scalar may be a string with its unit ("230 um"). ``shape``: "cylinder" | "cone" | "bevel",
    a Shape, or an array of them or of codes 0/1/2. ``material``: a preset name or NeedleMaterial; ``tissue``:
    "skin" | "brain" or a PunctureModel; ``options``: PerformanceIndexOptions. Runs in parallel (TBB) without the GIL.
    Raises InvalidInput naming the argument and index (a NaN, a wrong dtype or shape, an invalid design); nothing is
    returned then.
    """
    arrays = _needlekit._evaluate_many(shape, needles_per_row, tip_diameter, base_diameter, bore_diameter, length,
                                       width, angle, target_depth, material, tissue,
                                       options or PerformanceIndexOptions())  # noqa: F405
    return EvaluateManyResult(arrays)
