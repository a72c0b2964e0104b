"""floorgrid: align a building's CAD floorplan with a robot's occupancy gridmap, then map
points and poses between the two frames, both ways, with a measured accuracy.

    import floorgrid, numpy as np
    model = floorgrid.Model.load("office-align/model.json")
    m = model.forward(np.array([[12.5, 3.0], [1.0, 2.0]]))     # plan -> grid
    m.points, m.std_m, m.flags, m.extrapolated
    back = model.inverse(m.points)                            # grid -> plan

    result = floorgrid.align("office", out="office-align", seed=1)
    result.metrics["models"]["gp"], result.chosen, result.model.forward(...)

Arrays: points are N x 2 (x, y) and poses N x 3 (x, y, theta in radians), float64; a C-ordered
float64 array is read in place and the results are written into new arrays, without copies.
Errors in input files raise InputError (a ValueError) with .file, .line and .field.
"""

from __future__ import annotations

import json as _json
from typing import Any, Callable, Dict, List, Mapping, Optional

import numpy as _np

from . import _floorgrid

__all__ = [
    "InputError", "AlignmentFailure", "Cancelled", "Model", "Mapped", "Dataset", "Alignment",
    "align", "config", "load_dataset", "FLAG_NAMES", "__version__",
]

InputError = _floorgrid.InputError
InputError.__doc__ = (
    "Bad input from outside (a file, a field, an argument): a ValueError whose .file, .line "
    "(1-based) and .field say where (None when unknown) and .message what.")
AlignmentFailure = _floorgrid.AlignmentFailure
AlignmentFailure.__doc__ = (
    "align() read its input but found no alignment (no reference pairs, or a plan of another "
    "building); the CLI exits 3 then. metrics.json and report.html are still written to `out`.")
Cancelled = _floorgrid.Cancelled
Cancelled.__doc__ = "align() was cancelled (its progress callback returned False)."

for _error in (InputError, AlignmentFailure, Cancelled):
    _error.__module__ = "floorgrid"

#: Names of the codes in Mapped.flags: FLAG_NAMES[code].
FLAG_NAMES = tuple(_floorgrid.FLAG_NAMES)
OK, UNCERTAIN, EXTRAPOLATED, OUTSIDE_HULL, NOT_INVERTIBLE = range(5)
__version__ = _floorgrid.version()


class Mapped:
    """Points or poses mapped through a Model (what `floorgrid map` writes per row).

    Attributes:
        values: N x 2 points or N x 3 poses in the target frame (model units; theta in
            radians); NaN where not invertible.
        std_m: N, the error's root mean square length in metres (the true point lies within
            std_m about 63% and within 2 std_m about 95% of the time); NaN where the model
            states none.
        nearest_pair_m: N, metres from the input point to the nearest reference pair.
        flags: N uint8 codes into FLAG_NAMES: 0 ok, 1 uncertain (2 std_m above the model's
            max_error), 2 extrapolated (farther than extrapolation_distance from every pair),
            3 outside_hull (outside the pairs' convex hull), 4 not_invertible.
    """

    __slots__ = ("values", "std_m", "nearest_pair_m", "flags")

    def __init__(self, values, std_m, nearest_pair_m, flags):
        self.values = values
        self.std_m = std_m
        self.nearest_pair_m = nearest_pair_m
        self.flags = flags

    @property
    def points(self) -> _np.ndarray:
        """N x 2: the mapped x, y (a view of values)."""
        return self.values[:, :2]

    @property
    def headings(self) -> Optional[_np.ndarray]:
        """N mapped headings (radians) for poses, else None."""
        return self.values[:, 2] if self.values.shape[1] == 3 else None

    @property
    def extrapolated(self) -> _np.ndarray:
        """N booleans: where the mapping is extrapolated (outside the pairs' hull or farther
        than the model's extrapolation distance from every pair)."""
        return (self.flags == EXTRAPOLATED) | (self.flags == OUTSIDE_HULL)

    @property
    def flag_names(self) -> List[str]:
        """The flags as the `map` CSV writes them ("ok", "extrapolated", ...)."""
        return [FLAG_NAMES[f] for f in self.flags]

    def __len__(self) -> int:
        return len(self.flags)

    def __repr__(self) -> str:
        return f"Mapped({len(self)} {'poses' if self.values.shape[1] == 3 else 'points'})"


def _as_points(points) -> _np.ndarray:
    array = _np.asarray(points, dtype=_np.float64)
    if array.ndim == 1:
        array = array.reshape(1, -1)
    return array


class Model:
    """A fitted mapping between a building's plan frame and a robot's gridmap frame.

    Load one (Model.load), or fit one to pairs (Model.fit); map points and poses with
    forward (plan -> grid) and inverse (grid -> plan). Safe to share between threads; the
    mapping runs on two threads with the GIL released.
    """

    def __init__(self, impl):
        self._impl = impl

    @classmethod
    def load(cls, path: str, max_error: Optional[float] = None) -> "Model":
        """Reads a model file written by `floorgrid fit`, `floorgrid align` or save().

        max_error: metres, overrides the file's bound of an `ok` point (`map --max-error`).
        Raises InputError naming the file (and line and field) for a missing, unreadable or
        damaged file."""
        return cls(_floorgrid.Model.load(str(path), max_error or 0.0))

    @classmethod
    def fit(cls, pairs, kind: str = "auto", *, cv: int = 5, cv_kind: str = "blocked",
            cv_block: float = 0.0, unit: float = 1.0, seed: int = 1,
            budget: Optional[int] = None, extrapolation: Optional[float] = None,
            max_error: Optional[float] = None, inlier_threshold: Optional[float] = None,
            memory_limit: Optional[float] = None) -> "Model":
        """Fits a model to reference pairs, as `floorgrid fit` does.

        pairs: N x 4 array (plan_x, plan_y, grid_x, grid_y) or N x 5 (..., weight), in `unit`
            metres per unit (1: metres).
        kind: lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps or auto (cross-validation
            chooses).
        cv: k of the k-fold cross-validation that gives the model its error and std_m (0: none).
        cv_kind: blocked, random or runs; cv_block: metres (0: chosen from the pairs).
        seed: randomness of RANSAC and subsampling; budget: pairs kept by gp, gpgt, tps, dt.
        extrapolation: metres from every pair beyond which a point is flagged extrapolated.
        max_error: metres, the 95% bound of an `ok` point; inlier_threshold: metres (gt
            models; default automatic); memory_limit: GiB a fit may use (default: half of
            this machine's memory, as `floorgrid fit`).
        Raises InputError for bad pairs (naming the row and column) or options."""
        impl = _floorgrid.Model.fit(
            _np.asarray(pairs, dtype=_np.float64), kind, cv, cv_kind, cv_block, unit, seed,
            budget, extrapolation, max_error, inlier_threshold, memory_limit)
        return cls(impl)

    def save(self, path: str) -> None:
        """Writes the model file (JSON, atomically); `floorgrid map --model` reads it."""
        self._impl.save(str(path))

    @property
    def name(self) -> str:
        """lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps or auto."""
        return self._impl.name

    @property
    def chosen(self) -> str:
        """For auto, the model it chose; else name."""
        return self._impl.chosen

    @property
    def unit(self) -> float:
        """Metres per unit of the points the model reads and writes (1: metres)."""
        return self._impl.unit

    @property
    def extrapolation_distance(self) -> float:
        """Metres from every pair beyond which a point is flagged extrapolated."""
        return self._impl.extrapolation_distance

    @property
    def max_error(self) -> float:
        """Metres: a point whose 2 std_m exceeds it is flagged uncertain (settable)."""
        return self._impl.max_error

    @max_error.setter
    def max_error(self, metres: float) -> None:
        self._impl.max_error = metres

    @property
    def summary(self) -> Dict[str, Any]:
        """The fit's summary: the model file's `fit` object (rms_m, cv_error_m, details, ...)
        with its `pairs` (given, merged, used, reduction)."""
        return _json.loads(self._impl.summary_json())

    def forward(self, points) -> Mapped:
        """Plan points (N x 2) or poses (N x 3, theta in radians) in the grid frame."""
        return Mapped(*self._impl.map(_as_points(points), False))

    def inverse(self, points) -> Mapped:
        """Grid points (N x 2) or poses (N x 3) in the plan frame; not_invertible where the
        mapping folds or the inverse does not exist."""
        return Mapped(*self._impl.map(_as_points(points), True))

    def __repr__(self) -> str:
        chosen = f" (chose {self.chosen})" if self.name == "auto" else ""
        return f"floorgrid.Model({self.name}{chosen})"


def _options_text(options: Optional[Mapping[str, Any]], groups: Mapping[str, Any]) -> str:
    """Options as `config --dump`'s nested mapping, from dotted keys and nested dicts."""
    tree: Dict[str, Any] = {}

    def put(path: List[str], value: Any) -> None:
        node = tree
        for key in path[:-1]:
            node = node.setdefault(key, {})
            if not isinstance(node, dict):
                raise InputError(f"'{'.'.join(path)}' sets a value inside a value")
        node[path[-1]] = value

    def walk(prefix: List[str], value: Any) -> None:
        if isinstance(value, Mapping):
            for key, item in value.items():
                walk(prefix + str(key).split("."), item)
        else:
            put(prefix, value)

    walk([], dict(options or {}))
    walk([], dict(groups))
    return _json.dumps(tree) if tree else ""


class Dataset:
    """A dataset read (dataset.yaml or its folder), ready to align."""

    def __init__(self, impl):
        self._impl = impl

    @property
    def name(self) -> str:
        return self._impl.name

    @property
    def manifest_path(self) -> str:
        return self._impl.manifest_path

    @property
    def scans(self) -> int:
        """Laser scans of the run (0: no log, aligned from the maps alone)."""
        return self._impl.scans

    @property
    def has_truth(self) -> bool:
        """Whether the dataset has a truth (a simulator's warp or hand-picked pairs)."""
        return self._impl.has_truth

    def __repr__(self) -> str:
        return f"floorgrid.Dataset({self.name!r}, {self.scans} scans)"


def load_dataset(path: str, *, config: Optional[str] = None, seed: Optional[int] = None,
                 cv: Optional[int] = None, cv_kind: Optional[str] = None,
                 cv_block: Optional[float] = None, memory_limit: Optional[float] = None,
                 pairs_from: Optional[str] = None, options: Optional[Mapping[str, Any]] = None,
                 **groups: Any) -> Dataset:
    """Reads a dataset with the job's options (see align() for them). Raises InputError
    naming the file, line and field for bad input."""
    impl = _floorgrid.Dataset.load(str(path), None if config is None else str(config),
                                   _options_text(options, groups) or None, seed, cv, cv_kind,
                                   cv_block, memory_limit, pairs_from)
    return Dataset(impl)


class Alignment:
    """What align() found.

    Attributes:
        pairs: N x 4 array (plan_x, plan_y, grid_x, grid_y, metres): the pairs every model was
            fitted on (`pairs.csv`).
        metrics: dict, metrics.json's content (docs/metrics.md): the file written to `out`;
            without `out`, the same less the heat maps' keys and write timings.
        models: dict name -> Model, every model fitted (`model-<name>.json`).
        chosen: the model auto chose ("" without auto).
        model: the auto model (`model.json`), or None.
        files: files written into `out`, relative to it (empty without `out`).
    """

    def __init__(self, raw: Dict[str, Any]):
        self.pairs: _np.ndarray = raw["pairs"]
        self.metrics: Dict[str, Any] = _json.loads(raw["metrics_json"])
        self.models: Dict[str, Model] = {name: Model(impl) for name, impl in raw["models"]}
        self.chosen: str = raw["chosen"]
        self.model: Optional[Model] = self.models.get("auto")
        self.files: List[str] = list(raw["files"])

    def __repr__(self) -> str:
        return (f"floorgrid.Alignment({len(self.pairs)} pairs, models {sorted(self.models)}, "
                f"chosen {self.chosen!r})")


def align(dataset, out: Optional[str] = None, *,
          progress: Optional[Callable[[str, str, int, int], Any]] = None,
          config: Optional[str] = None, seed: Optional[int] = None, cv: Optional[int] = None,
          cv_kind: Optional[str] = None, cv_block: Optional[float] = None,
          memory_limit: Optional[float] = None, pairs_from: Optional[str] = None,
          options: Optional[Mapping[str, Any]] = None, **groups: Any) -> Alignment:
    """The main job, as `floorgrid align DATASET --out OUT`: reference pairs by dual Monte Carlo
    localization (or from the two maps), every model fitted and judged, the one auto chose.

    dataset: a path (dataset.yaml or its folder) or a Dataset from load_dataset().
    out: folder to write as the CLI does (pairs.csv, model-*.json, model.json, metrics.json,
        overlays/, heatmaps/, exports/, report.html); None writes nothing.
    progress: called as progress(stage, detail, done, total) on the calling thread; return
        False (or raise) to stop: align raises Cancelled (or the callback's exception).
        Ctrl-C stops it too (KeyboardInterrupt). Either takes effect at the job's next progress
        step: every scan while localizing, every model while fitting (registering the maps,
        first, reports none for several seconds).
    config, seed, cv, cv_kind, cv_block, memory_limit, pairs_from: as the CLI's --config,
        --seed, --cv, --cv-kind, --cv-block, --memory-limit and --pairs-from.
    options: any option of config() by dotted name, {"align.models.cv_folds": 3}, or nested;
        keyword groups do the same: align=dict(models=dict(cv_folds=3)).
    Raises InputError for bad input, AlignmentFailure when no alignment was found (after
    writing metrics.json and report.html to `out`)."""
    if isinstance(dataset, Dataset):
        if any(v is not None for v in (config, seed, cv, cv_kind, cv_block, memory_limit,
                                       pairs_from, options)) or groups:
            raise TypeError("options are given to load_dataset() when dataset is a Dataset")
        loaded = dataset
    else:
        loaded = load_dataset(dataset, config=config, seed=seed, cv=cv, cv_kind=cv_kind,
                              cv_block=cv_block, memory_limit=memory_limit,
                              pairs_from=pairs_from, options=options, **groups)

    callback = None
    if progress is not None:
        def callback(stage, detail, done, total):
            if progress(stage, detail, done, total) is False:
                raise Cancelled("align cancelled by its progress callback")

    return Alignment(_floorgrid.align(loaded._impl, "" if out is None else str(out), callback))


def config() -> Dict[str, Any]:
    """Every option of align() with its default: nested dicts (as `floorgrid config --dump
    --json`) whose leaves are {"default", "unit", "description", "choices"}."""
    return _json.loads(_floorgrid.options_json())


def defaults() -> Dict[str, Any]:
    """Every option of align() by dotted name with its default ({"align.models.cv_folds": 5})."""
    flat: Dict[str, Any] = {}

    def walk(prefix: str, node: Dict[str, Any]) -> None:
        for key, value in node.items():
            name = f"{prefix}.{key}" if prefix else key
            if isinstance(value, dict) and "default" in value and "description" in value:
                flat[name] = value["default"]
            elif isinstance(value, dict):
                walk(name, value)

    walk("", config())
    return flat
