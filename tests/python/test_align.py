"""floorgrid.align against `floorgrid align` on the same dataset and seed, and its models
against the simulator's truth."""

import json

import numpy as np
import pytest

import floorgrid
from conftest import run_cli


def without_wall_clock(node):
    """metrics.json less what depends on the clock (timings_s, *_seconds, seconds)."""
    if isinstance(node, dict):
        return {k: without_wall_clock(v) for k, v in node.items()
                if not (k == "timings_s" or k.endswith("seconds") or k.endswith("_s"))}
    if isinstance(node, list):
        return [without_wall_clock(v) for v in node]
    return node


def test_metrics_equal_the_cli(cli_alignment, python_alignment, workdir):
    result, _ = python_alignment
    cli_metrics = json.loads((cli_alignment / "metrics.json").read_text())
    written = json.loads((workdir / "py-align" / "metrics.json").read_text())
    assert without_wall_clock(written) == without_wall_clock(cli_metrics)
    assert without_wall_clock(result.metrics) == without_wall_clock(cli_metrics)
    assert "metrics.json" in result.files and "model.json" in result.files


def test_pairs_and_models_equal_the_cli(cli_alignment, python_alignment):
    result, _ = python_alignment
    cli_pairs = np.loadtxt(cli_alignment / "pairs.csv", delimiter=",", skiprows=1)
    assert result.pairs.shape == (len(cli_pairs), 4)
    assert np.max(np.abs(result.pairs - cli_pairs[:, :4])) <= 1e-9
    assert result.chosen == result.model.chosen
    assert set(result.models) == {"gt", "gp", "tps", "dt", "auto"}
    cli_model = floorgrid.Model.load(cli_alignment / "model.json")
    points = result.pairs[::7, :2]
    assert np.max(np.abs(result.model.forward(points).values -
                         cli_model.forward(points).values)) <= 1e-9


def truth_poses(office):
    """The simulator's true trajectory in the plan and in the grid frame (truth.json)."""
    truth = json.loads((office / "truth.json").read_text())
    trajectory = truth["trajectory"]
    plan = np.array([[p["plan"][0], p["plan"][1]] for p in trajectory])
    grid = np.array([[p["grid"][0], p["grid"][1]] for p in trajectory])
    return plan, grid


def test_the_chosen_model_maps_the_true_trajectory(office, python_alignment):
    result, _ = python_alignment
    plan, grid = truth_poses(office)
    mapped = result.model.forward(plan)
    error = np.linalg.norm(mapped.values - grid, axis=1)
    inside = mapped.flags != floorgrid.NOT_INVERTIBLE
    print(f"auto ({result.chosen}) on the true trajectory: median {np.median(error[inside]):.3f}"
          f" m, 95th percentile {np.percentile(error[inside], 95):.3f} m")
    assert np.median(error[inside]) < 0.10
    # std_m is calibrated: about 95% of true errors lie within 2 std_m (loosely).
    within = error[inside] <= 2 * mapped.std_m[inside]
    assert within.mean() > 0.7
    back = result.model.inverse(mapped.values)
    assert np.nanmax(np.linalg.norm(back.values - plan, axis=1)) <= 1e-6


def test_progress_is_reported_and_cancelling_stops(office, python_alignment):
    _, calls = python_alignment
    stages = {stage for stage, *_ in calls}
    assert {"localize", "fit"} <= stages
    seen = []
    with pytest.raises(floorgrid.Cancelled):
        floorgrid.align(office, seed=1, progress=lambda *p: seen.append(p) or len(seen) < 3)
    assert len(seen) == 3

    class Stop(Exception):
        pass

    def stop(*_):
        raise Stop()
    with pytest.raises(Stop):
        floorgrid.align(office, seed=1, progress=stop)


def test_config_has_every_option_as_the_cli(tmp_path):
    assert floorgrid.config() == json.loads(run_cli("config", "--dump", "--json").stdout)
    defaults = floorgrid.defaults()
    assert defaults["align.models.cv_folds"] == 5
    assert all("." in k for k in defaults)


def test_help_is_documented():
    for thing in (floorgrid, floorgrid.Model, floorgrid.Model.forward, floorgrid.Model.fit,
                  floorgrid.align, floorgrid.Mapped, floorgrid.InputError, floorgrid.config):
        assert thing.__doc__ and len(thing.__doc__) > 30, thing
