"""Type stubs of the pure-Python part of needlekit (the compiled part: _needlekit.pyi)."""
from typing import Any, Dict, List, Optional, Union
import os

import numpy

from ._needlekit import *
from ._needlekit import InvalidInput as InvalidInput, IoError as IoError

_Quantity = Union[float, str]
_Column = Union[float, str, numpy.ndarray]

def to_dict(obj: Any) -> Dict[str, Any]:
    """Every field of a needlekit object as a dict (SI units; nested objects as dicts, enums as their names)."""

def evaluate(design: Union[str, os.PathLike, DesignFile, ArrayDesign], conditions: Optional[InsertionConditions] = None,
             options: Optional[PerformanceIndexOptions] = None) -> PerformanceIndexResult:
    """The performance index of one needle array with every intermediate quantity (SI)."""

class EvaluateManyResult:
    """The arrays of evaluate_many (one entry per design; SI, NaN where not assessed)."""
    distinct_sections: Optional[int]
    tip_area: numpy.ndarray
    puncture_force: numpy.ndarray
    deformation: numpy.ndarray
    cutting_depth: numpy.ndarray
    permeation_depth: numpy.ndarray
    diameter_at_surface: numpy.ndarray
    embedded_volume: numpy.ndarray
    q_factor: numpy.ndarray
    hole_volume: numpy.ndarray
    gap_volume: numpy.ndarray
    pitch: numpy.ndarray
    fractional_skin_volume: numpy.ndarray
    needle_volume: numpy.ndarray
    critical_buckling_load: numpy.ndarray
    tapered_factor: numpy.ndarray
    slenderness_ratio: numpy.ndarray
    column_constant: numpy.ndarray
    buckling_force: numpy.ndarray
    critical_bending_load: numpy.ndarray
    bending_force: numpy.ndarray
    performance_index: numpy.ndarray
    status: numpy.ndarray
    failed_checks: numpy.ndarray
    buckling_method: numpy.ndarray
    bending_ok: numpy.ndarray
    small_tip_branch: numpy.ndarray
    def __init__(self, arrays: Dict[str, Any]) -> None: ...
    def __len__(self) -> int: ...
    def status_names(self) -> numpy.ndarray: ...
    def reasons(self, index: int) -> List[str]: ...
    def to_dict(self) -> Dict[str, numpy.ndarray]: ...
    def to_dataframe(self) -> Any: ...

def evaluate_many(shape: Any, needles_per_row: Union[int, numpy.ndarray], tip_diameter: _Column,
                  base_diameter: _Column, length: _Column, width: _Column, bore_diameter: _Column = 0.0, *,
                  angle: _Column = 0.0, target_depth: _Column = 50e-6, material: Union[str, NeedleMaterial] = "silicon",
                  tissue: Union[str, PunctureModel] = "skin",
                  options: Optional[PerformanceIndexOptions] = None) -> EvaluateManyResult:
    """The performance index of many needle arrays at once (performance_index per design, the same bits)."""
