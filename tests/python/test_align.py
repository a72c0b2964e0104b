"""floorgrid.align against `floorgrid align` on the same dataset and seed, and its models
against the simulator's truth."""

import json
import shutil
import subprocess
import sys

import numpy as np
import pytest

import floorgrid
from conftest import ROOT, run_cli

# bench/same_outputs.py's comparison: metrics.json less what depends on the clock (timings_s,
# *seconds, *_s, printed seconds such as the notes' "in 7.4 s") or on the process
# (peak_memory_mib: Python's own memory counts too).
sys.path.insert(0, str(ROOT / "bench"))
from same_outputs import without_wall_clock  # noqa: E402


def test_metrics_equal_the_cli(cli_alignment, python_alignment, workdir):
    result, _ = python_alignment
    cli_metrics = json.loads((cli_alignment / "metrics.json").read_text())
    written = json.loads((workdir / "py-align" / "metrics.json").read_text())
    assert without_wall_clock(written) == without_wall_clock(cli_metrics)
    assert without_wall_clock(result.metrics) == without_wall_clock(cli_metrics)
    assert "metrics.json" in result.files and "model.json" in result.files


def test_every_file_equals_the_cli_and_a_changed_pair_is_caught(cli_alignment, python_alignment,
                                                               workdir, tmp_path):
    same_outputs = [sys.executable, str(ROOT / "bench" / "same_outputs.py")]
    result = subprocess.run([*same_outputs, cli_alignment, workdir / "py-align"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert " 0 differ" in result.stdout
    # The same folder with one pair moved by a millimetre: the comparison must say so.
    changed = tmp_path / "changed"
    shutil.copytree(workdir / "py-align", changed)
    lines = (changed / "pairs.csv").read_text().splitlines()
    row = lines[1].split(",")
    row[-1] = repr(float(row[-1]) + 0.001)
    (changed / "pairs.csv").write_text("\n".join([lines[0], ",".join(row), *lines[2:]]) + "\n")
    result = subprocess.run([*same_outputs, cli_alignment, changed], capture_output=True,
                            text=True)
    assert result.returncode == 1
    assert "differs: pairs.csv" in result.stdout


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
    """The simulator's true trajectory (truth.json) as plan poses and grid poses: a plan pose
    is the world position times plan_per_world, with the world heading."""
    truth = json.loads((office / "truth.json").read_text())
    columns = truth["trajectory"]["columns"]
    poses = np.array(truth["trajectory"]["poses"])
    col = {name: poses[:, columns.index(name)] for name in columns}
    plan_per_world = truth["plan"]["plan_per_world"]
    plan = np.column_stack([col["world_x"] * plan_per_world, col["world_y"] * plan_per_world,
                            col["world_theta"]])
    grid = np.column_stack([col["grid_x"], col["grid_y"], col["grid_theta"]])
    return plan, grid


def test_the_chosen_model_maps_the_true_trajectory(office, python_alignment):
    result, _ = python_alignment
    plan, grid = truth_poses(office)
    mapped = result.model.forward(plan)
    error = np.linalg.norm(mapped.points - grid[:, :2], axis=1)
    heading = np.abs(np.angle(np.exp(1j * (mapped.headings - grid[:, 2]))))
    print(f"auto ({result.chosen}) on the true trajectory: position error median "
          f"{np.median(error):.3f} m, 95th percentile {np.percentile(error, 95):.3f} m; "
          f"heading error median {np.median(heading):.4f} rad; "
          f"{(error <= 2 * mapped.std_m).mean():.0%} within 2 std_m")
    assert np.median(error) < 0.10 and np.percentile(error, 95) < 0.30
    assert np.median(heading) < 0.02
    # The stated accuracy holds on the truth (about 95% within 2 std_m; loosely).
    assert (error <= 2 * mapped.std_m).mean() > 0.7
    back = result.model.inverse(mapped.values)
    ok = back.flags != floorgrid.NOT_INVERTIBLE
    assert ok.mean() > 0.95
    assert np.max(np.linalg.norm(back.points[ok] - plan[ok, :2], axis=1)) <= 1e-6


def test_progress_is_reported_and_cancelling_stops(office, python_alignment):
    _, calls = python_alignment
    stages = {stage for stage, *_ in calls}
    assert {"localize", "fit"} <= stages
    seen = []
    with pytest.raises(floorgrid.Cancelled):
        floorgrid.align(office, seed=1, progress=lambda *p: seen.append(p) or False)
    assert len(seen) == 1

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


def test_max_error_changes_the_flags(python_alignment):
    result, _ = python_alignment
    model = result.models["gp"]
    points = result.pairs[::5, :2]
    before = model.forward(points)
    assert not np.isnan(before.std_m).any()
    model.max_error = 1e-6
    after = model.forward(points)
    assert (after.flags[before.flags == floorgrid.OK] == floorgrid.UNCERTAIN).all()
    model.max_error = 0.25
