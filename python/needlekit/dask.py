"""needlekit on a Dask cluster (``distributed.Client``), for when one machine is not enough.

Three patterns, each returning exactly what the serial run returns (the same library code runs on the workers):

- ``map_designs(client, chunk_size=..., **evaluate_many_arguments)``: a design sweep or a Monte Carlo sample of
  designs, split into chunks of rows, each chunk an ``evaluate_many`` on a worker; the chunks are joined in order.
- ``map_samples(client, function, samples)``: any function of one sample (e.g. a Monte Carlo draw -> a result dict),
  one task per sample, results in sample order.
- ``map_runs(client, function, cases)``: independent FE runs (indentation, insertion, patch fits), one task per
  case. Functions should return plain data (``to_dict()``, numpy arrays): results travel back by pickle.

needlekit's input objects (NeedleGeometry, ArrayDesign, IndentationCase, ...) pickle by their fields, so they can be
arguments of tasks; a worker imports needlekit from its own PYTHONPATH (the same build or installation).

Example::

    from distributed import Client, LocalCluster
    import needlekit, needlekit.dask
    with LocalCluster(n_workers=2, processes=True) as cluster, Client(cluster) as client:
        result = needlekit.dask.map_designs(client, shape="cone", needles_per_row=10, tip_diameter=d1,
                                            base_diameter=d2, length=500e-6, width=1e-2)
"""
from __future__ import annotations

import numpy as _np

import needlekit as _nk

_ROW_ARGUMENTS = ("shape", "needles_per_row", "tip_diameter", "base_diameter", "length", "width", "bore_diameter",
                  "angle", "target_depth")


def _rows(value, start, stop):
    """Rows start:stop of an evaluate_many argument (scalars and strings apply to every row)."""
    if isinstance(value, str) or _np.ndim(value) == 0:
        return value
    return _np.asarray(value)[start:stop]


def _evaluate_chunk(arguments: dict) -> dict:
    return _nk.evaluate_many(**arguments).to_dict()


def map_designs(client, *, chunk_size: int = 250_000, **arguments) -> "_nk.EvaluateManyResult":
    """``needlekit.evaluate_many(**arguments)`` split over the cluster in chunks of ``chunk_size`` designs.

    The arguments are those of ``evaluate_many``; the result is an EvaluateManyResult equal, array for array, to
    the serial ``evaluate_many(**arguments)``. An invalid design raises InvalidInput from its worker (the index in the
    message counts from the start of its chunk).
    """
    sizes = [len(arguments[key]) for key in _ROW_ARGUMENTS
             if key in arguments and not isinstance(arguments[key], str) and _np.ndim(arguments[key]) > 0]
    count = max(sizes, default=1)
    if chunk_size < 1:
        raise _nk.InvalidInput(f"chunk_size: {chunk_size} must be >= 1")
    chunks = []
    for start in range(0, count, chunk_size):
        stop = min(start + chunk_size, count)
        chunks.append({key: (_rows(value, start, stop) if key in _ROW_ARGUMENTS else value)
                       for key, value in arguments.items()})
    parts = client.gather(client.map(_evaluate_chunk, chunks, pure=False))
    joined = {key: _np.concatenate([part[key] for part in parts]) for key in parts[0]}
    joined["distinct_sections"] = None  # counted per chunk on the workers; not meaningful for the whole
    return _nk.EvaluateManyResult(joined)


def map_samples(client, function, samples, **keywords) -> list:
    """``[function(sample, **keywords) for sample in samples]`` with one task per sample on the cluster."""
    futures = client.map(function, list(samples), pure=False, **keywords)
    return client.gather(futures)


def map_runs(client, function, cases, **keywords) -> list:
    """Independent FE runs (one task each), e.g. ``function = lambda case: needlekit.run_indentation(case).to_dict()``;
    results in the order of ``cases``."""
    return map_samples(client, function, cases, **keywords)
