"""floorgrid.Model against `floorgrid map` and `floorgrid fit` on the same files."""

import csv
import math
import threading
import time

import numpy as np
import pytest

import floorgrid
from conftest import ROOT, run_cli

MODELS = ROOT / "tests" / "fixtures" / "models"


def read_mapped_csv(path):
    """`map --points`'s output: values (N x 2 or 3), std_m, nearest_pair_m, flags."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    keys = ["x", "y", "theta"] if "theta" in rows[0] else ["x", "y"]
    number = lambda text: float(text) if text != "" else math.nan
    values = np.array([[number(r[k]) for k in keys] for r in rows])
    std = np.array([number(r["std_m"]) for r in rows])
    nearest = np.array([number(r["nearest_pair_m"]) for r in rows])
    return values, std, nearest, [r["flag"] for r in rows]


def write_points_csv(path, points):
    header = "x,y,theta" if points.shape[1] == 3 else "x,y"
    # repr() of a float reads back as the same double: the CLI maps exactly these points.
    path.write_text(header + "\n" + "".join(",".join(repr(float(v)) for v in p) + "\n"
                                            for p in points))


def cli_map(model_path, points, tmp_path, inverse=False):
    src, out = tmp_path / "in.csv", tmp_path / "out.csv"
    write_points_csv(src, points)
    run_cli("map", "--model", model_path, "--points", src, "--out", out,
            *(["--inverse"] if inverse else []))
    return read_mapped_csv(out)


def points_around(model_path, n, seed, margin=3.0):
    """n plan points spread over the model's pairs (and a margin beyond them, extrapolated)."""
    rng = np.random.default_rng(seed)
    with open(MODELS / "pairs.csv") as f:
        pairs = np.array([[float(v) for v in line.split(",")] for line in list(f)[1:]])
    low, high = pairs[:, :2].min(axis=0) - margin, pairs[:, :2].max(axis=0) + margin
    return rng.uniform(low, high, size=(n, 2))


def assert_same_as_cli(mapped, cli, tolerance=1e-9):
    values, std, nearest, flags = cli
    assert mapped.flag_names == flags
    both = ~np.isnan(values)
    assert np.array_equal(both, ~np.isnan(mapped.values))
    assert np.max(np.abs(mapped.values[both] - values[both])) <= tolerance
    assert np.array_equal(np.isnan(std), np.isnan(mapped.std_m))
    has_std = ~np.isnan(std)
    assert not has_std.any() or np.max(np.abs(mapped.std_m[has_std] - std[has_std])) <= tolerance
    assert np.max(np.abs(mapped.nearest_pair_m - nearest)) <= tolerance


@pytest.mark.parametrize("name", ["tps", "gp", "dt", "gt"])
def test_forward_and_inverse_of_1000_points_equal_the_cli(name, tmp_path):
    model_path = MODELS / f"{name}.json"
    model = floorgrid.Model.load(model_path)
    assert model.name == name
    points = points_around(model_path, 1000, seed=7)
    forward = model.forward(points)
    assert forward.values.shape == (1000, 2) and forward.flags.dtype == np.uint8
    assert_same_as_cli(forward, cli_map(model_path, points, tmp_path))
    # Some points lie beyond the pairs: they must say so.
    assert forward.extrapolated.any() and not forward.extrapolated.all()
    inverse = model.inverse(forward.values)
    assert_same_as_cli(inverse, cli_map(model_path, forward.values, tmp_path, inverse=True))
    back = ~np.isnan(inverse.values[:, 0])
    assert back.sum() >= 900
    round_trip = np.linalg.norm(inverse.values[back] - points[back], axis=1)
    print(f"{name}: forward = CLI, round trip max {round_trip.max():.3g} m over {back.sum()}")
    assert round_trip.max() <= 1e-6


def test_poses_equal_the_cli_both_ways(tmp_path):
    model_path = MODELS / "auto.json"
    model = floorgrid.Model.load(model_path)
    poses = np.column_stack([points_around(model_path, 200, seed=3),
                             np.random.default_rng(4).uniform(-math.pi, math.pi, 200)])
    forward = model.forward(poses)
    assert forward.values.shape == (200, 3)
    assert_same_as_cli(forward, cli_map(model_path, poses, tmp_path))
    inverse = model.inverse(forward.values)
    assert_same_as_cli(inverse, cli_map(model_path, forward.values, tmp_path, inverse=True))


def test_inputs_are_read_in_place_and_other_layouts_still_work():
    model = floorgrid.Model.load(MODELS / "tps.json")
    points = np.ascontiguousarray(points_around(MODELS / "tps.json", 50, seed=1))
    reference = model.forward(points).values
    # A Fortran-ordered copy, a list of lists and one point give the same numbers.
    assert np.array_equal(model.forward(np.asfortranarray(points)).values, reference)
    assert np.array_equal(model.forward(points.tolist()).values, reference)
    assert np.array_equal(model.forward(points[3]).values[0], reference[3])
    with pytest.raises(ValueError):
        model.forward(np.zeros((4, 5)))


def test_fit_equals_the_cli_fit_and_saves_a_file_the_cli_maps(tmp_path):
    pairs_csv = MODELS / "pairs.csv"
    cli_model = tmp_path / "cli-tps.json"
    run_cli("fit", "--pairs", pairs_csv, "--model", "tps", "--out", cli_model)
    with open(pairs_csv) as f:
        pairs = np.array([[float(v) for v in line.split(",")] for line in list(f)[1:]])
    model = floorgrid.Model.fit(pairs, "tps")
    assert model.name == "tps" and model.summary["pairs"]["used"] == len(pairs)
    points = points_around(pairs_csv, 300, seed=11)
    assert_same_as_cli(model.forward(points), cli_map(cli_model, points, tmp_path))
    saved = tmp_path / "py-tps.json"
    model.save(saved)
    assert_same_as_cli(model.forward(points), cli_map(saved, points, tmp_path))


def test_bad_pairs_name_the_row_and_column():
    with open(MODELS / "pairs.csv") as f:
        pairs = np.array([[float(v) for v in line.split(",")] for line in list(f)[1:]])
    pairs[4, 2] = 1e6  # a unit slip in one grid x
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.fit(pairs, "tps")
    assert error.value.line == 5 and error.value.field == "grid_x"
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.fit(pairs[:2], "tps", cv=0)
    with pytest.raises(floorgrid.InputError) as error:
        floorgrid.Model.fit(pairs, "tps", cv=1)
    assert error.value.field == "cv"
    with pytest.raises(ValueError):
        floorgrid.Model.fit(pairs[:, :3])


def test_non_physical_points_get_no_number_and_nothing_breaks():
    model = floorgrid.Model.load(MODELS / "tps.json")
    mapped = model.forward(np.array([[np.nan, 1.0], [1e9, 0.0], [3.0, np.inf], [3.0, 4.0]]))
    assert mapped.flag_names[:3] == ["not_invertible"] * 3 and mapped.flag_names[3] == "ok"
    assert np.isnan(mapped.values[:3]).all() and not np.isnan(mapped.values[3]).any()
    assert model.forward(np.zeros((0, 2))).values.shape == (0, 2)


def test_the_gil_is_released_while_mapping():
    model = floorgrid.Model.load(MODELS / "tps.json")
    points = np.random.default_rng(2).uniform(0, 10, size=(1_000_000, 2))
    worker = threading.Thread(target=model.forward, args=(points,))
    ticks = []
    start = time.perf_counter()
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    took = time.perf_counter() - start
    # This thread kept running while the worker mapped: with the GIL held for the whole call
    # it would stand still for about all of it.
    longest_stop = max(np.diff([start] + ticks), default=took)
    print(f"mapping took {took:.3f} s; this thread stood still {longest_stop:.4f} s at most")
    assert longest_stop < 0.5 * took
