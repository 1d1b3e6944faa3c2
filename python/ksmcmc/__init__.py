"""Semantic floor plans from occupancy grids, by knowledge-supervised MCMC.

``ksmcmc.floorplan(map)`` explains a map (a file, or a numpy array) as the rooms, corridors
and halls a person would draw, with their walls and doors, exactly as the ``ksmcmc floorplan``
command does: the same map, seed and settings give the same ``labels.pgm`` and ``world.json``.

>>> import ksmcmc
>>> plan = ksmcmc.floorplan("samples/office-small/map.yaml", seed=1)   # doctest: +SKIP
>>> plan.labels.shape, [r["type"] for r in plan.rooms][:3]              # doctest: +SKIP

``ksmcmc.mln`` queries and learns Markov logic networks, as ``ksmcmc mln`` does.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _ksmcmc, mln

__all__ = ["FloorPlan", "floorplan", "mln", "DEFAULT_RESOLUTION"]

#: Metres per cell assumed for a uint8 array without ``resolution`` (the benchmark maps' cell),
#: as the command line assumes it for an image without ``map.yaml``.
DEFAULT_RESOLUTION = 0.05

MapLike = Union[str, "os.PathLike[str]", np.ndarray]


class FloorPlan:
    """What ``floorplan`` found: the rooms and everything made from them.

    ``labels`` is ``labels.pgm`` as a ``numpy.uint16`` array (per map cell the id of its room,
    0 for none); ``world``, ``report`` and ``graph`` are ``world.json``, ``report.json`` and
    ``graph.json`` as dicts, and ``rooms`` is ``world["rooms"]``.
    """

    def __init__(self, native: Any) -> None:
        self._native = native
        self._labels: Optional[np.ndarray] = None
        self._world: Optional[Dict[str, Any]] = None

    @property
    def labels(self) -> np.ndarray:
        """Per map cell the id of its room (0 for none), rows from the top, ``numpy.uint16``."""
        if self._labels is None:
            data, width, height = self._native.labels_le()
            labels = np.frombuffer(data, dtype="<u2").reshape(height, width).astype(np.uint16)
            labels.flags.writeable = False
            self._labels = labels
        return self._labels

    @property
    def world(self) -> Dict[str, Any]:
        """``world.json``: the units, doors, rooms, placeholders and the frame, as a dict."""
        if self._world is None:
            self._world = json.loads(self._native.world_json())
        return self._world

    @property
    def rooms(self) -> List[Dict[str, Any]]:
        """The rooms of ``world.json``: id (its value in ``labels``), type, units, area, doors."""
        return self.world["rooms"]

    @property
    def placeholders(self) -> List[Dict[str, Any]]:
        """The placeholders of ``world.json``: where seen space meets unseen space, each with its
        cell ``x``, ``y`` (column, row), ``width_m``, the ``room`` it opens from (0: none),
        ``p_new_room`` (the probability that it leads to a room not yet in the map) and
        ``types`` (the probability of each type for the space beyond). Empty for a map with no
        frontier."""
        return self.world.get("placeholders", [])

    @property
    def report(self) -> Dict[str, Any]:
        """``report.json``: iterations, K(W,M), counts of units, doors and rooms."""
        return json.loads(self._native.report_json())

    @property
    def graph(self) -> Dict[str, Any]:
        """``graph.json``: the scene graph and the rooms."""
        return json.loads(self._native.graph_json())

    def geojson(self, georef: Optional[str] = None) -> str:
        """``world.geojson``; ``georef`` ``"LAT,LON,BEARING"`` places it on the Earth."""
        return self._native.geojson(georef)

    def svg(self) -> str:
        """``world.svg``: the floor plan as a drawing."""
        return self._native.svg()

    def glb(self) -> bytes:
        """``world.glb``: the 3D world (glTF 2.0 binary)."""
        return self._native.glb()

    def png(self) -> bytes:
        """``overlay.png``: the world drawn over the map."""
        return self._native.png()

    def route(self, start: Tuple[int, int], goal: Tuple[int, int]) -> Dict[str, Any]:
        """A route from map cell ``start`` to ``goal`` (column, row) through rooms and doors."""
        return json.loads(self._native.route(_cell(start, "start"), _cell(goal, "goal")))

    def save(self, directory: Union[str, "os.PathLike[str]"]) -> List[str]:
        """Writes the files ``ksmcmc floorplan`` writes into ``directory``; returns their paths."""
        os.makedirs(directory, exist_ok=True)
        paths = []
        for name, data in self._native.files():
            path = os.path.join(os.fspath(directory), name)
            with open(path, "wb") as f:
                f.write(data)
            paths.append(path)
        return paths

    def __repr__(self) -> str:
        w = self.world
        return f"<FloorPlan: {len(w['units'])} units, {len(w['doors'])} doors, {len(w['rooms'])} rooms>"


def floorplan(
    map: MapLike,
    *,
    resolution: Optional[float] = None,
    origin: Optional[Sequence[float]] = None,
    seed: int = 1,
    iterations: int = 20000,
    knowledge: str = "builtin",
    edits: Union[None, str, Sequence[Dict[str, Any]]] = None,
) -> FloorPlan:
    """Explains ``map`` as a floor plan, as ``ksmcmc floorplan MAP --seed SEED`` does.

    ``map`` is one of:

    * a path to a PNG, PGM or ROS ``map.yaml``, read exactly as the command line reads it
      (``resolution`` then overrides the file's);
    * a 2-D ``numpy.uint8`` array, read as a map image's pixels (0 occupied, 254 free, 205
      unknown, the command line's rule for the rest), rows from the top; ``resolution``
      defaults to 0.05 m with a warning;
    * a 2-D ``numpy.int8`` array in the ROS ``nav_msgs/OccupancyGrid`` convention (-1 unknown,
      0 - 100 occupancy, map_server's thresholds), rows as an image's rows (a message's data
      starts at the bottom row: flip it with ``[::-1]``); ``resolution`` is required.

    ``origin`` is ``(x, y, yaw)`` of the lower-left cell in metres and radians (arrays only).
    ``knowledge`` is ``"builtin"``, ``"none"`` (the weak prior), ``"handset"`` or the path of
    an indoor knowledge base. ``edits`` are a person's corrections (the JSON list of
    ``ksmcmc floorplan --edits``, as text or as a list of dicts). The chain runs without the GIL.

    Raises ``ValueError`` for a map, array or setting the core refuses (its message says why)
    and ``OSError`` for a file that cannot be read.
    """
    seed = _count(seed, "seed")
    iterations = _count(iterations, "iterations")
    if not isinstance(knowledge, str):
        raise ValueError(f"knowledge must be 'builtin', 'none', 'handset' or a path, not {knowledge!r}")
    edits_text = edits if edits is None or isinstance(edits, str) else json.dumps(list(edits))
    if isinstance(map, (str, os.PathLike)):
        if origin is not None:
            raise ValueError("origin applies to arrays; a map file carries its own (map.yaml)")
        res = None if resolution is None else float(resolution)
        native = _ksmcmc.floorplan_path(os.fspath(map), res, seed, iterations, knowledge, edits_text)
        return FloorPlan(native)
    if not isinstance(map, np.ndarray):
        raise ValueError(f"map must be a path or a 2-D numpy array (uint8 or int8), not {type(map).__name__}")
    if map.ndim != 2 or map.size == 0:
        raise ValueError(f"map must be a 2-D array with cells, not of shape {map.shape}")
    if map.dtype == np.uint8:
        kind = "pixels"
        if resolution is None:
            warnings.warn(
                f"no resolution given: reading the array at {DEFAULT_RESOLUTION} m a cell "
                "(pass resolution=M)",
                stacklevel=2,
            )
            resolution = DEFAULT_RESOLUTION
    elif map.dtype == np.int8:
        kind = "occupancy"
        if resolution is None:
            raise ValueError("an int8 OccupancyGrid array needs resolution= (its info.resolution, metres per cell)")
    else:
        raise ValueError(
            f"map's dtype is {map.dtype}: give uint8 (map image pixels) or int8 (OccupancyGrid values)"
        )
    o = (0.0, 0.0, 0.0) if origin is None else tuple(float(v) for v in origin)
    if len(o) != 3:
        raise ValueError(f"origin must be (x, y, yaw), not {origin!r}")
    height, width = map.shape
    cells = np.ascontiguousarray(map).tobytes()
    native = _ksmcmc.floorplan_cells(
        width, height, cells, kind, float(resolution), o, seed, iterations, knowledge, edits_text
    )
    return FloorPlan(native)


def _count(value: Any, name: str) -> int:
    """A non-negative whole number, or ValueError naming the argument."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise ValueError(f"{name} must be a whole number of 0 or more, not {value!r}")
    return int(value)


def _cell(point: Sequence[int], name: str) -> Tuple[int, int]:
    """A map cell (column, row), or ValueError naming the argument."""
    try:
        x, y = point
        return int(x), int(y)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a map cell (column, row), not {point!r}") from None
