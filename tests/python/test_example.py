"""examples/rmf_fleet_adapter.py: the fleet adapter's pose conversions through a model."""

import math
import subprocess
import sys

import numpy as np

import floorgrid
from conftest import ROOT, run_cli

sys.path.insert(0, str(ROOT / "examples"))
import rmf_fleet_adapter  # noqa: E402

MODEL = ROOT / "tests" / "fixtures" / "models" / "auto.json"


def test_poses_go_to_the_robot_and_back_as_the_cli_maps_them(caplog):
    transforms = rmf_fleet_adapter.FloorgridTransforms.from_files({"L1": str(MODEL)})
    rmf_pose = (3.0, 4.0, 0.5)
    robot_pose = transforms.to_robot_map("L1", rmf_pose)
    cli = run_cli("map", "--model", MODEL, "3,4,0.5").stdout
    expected = [float(v) for v in cli.split("->")[1].split()[0].split(",")]
    assert np.allclose(robot_pose, expected, atol=1e-6)
    assert not transforms.last_extrapolated
    back = transforms.to_rmf_map("L1", robot_pose)
    assert math.dist(back[:2], rmf_pose[:2]) < 1e-6
    assert abs(math.remainder(back[2] - rmf_pose[2], 2 * math.pi)) < 1e-6
    # Far from every pair, the conversion is reported as a guess.
    far = transforms.to_robot_map("L1", (200.0, -150.0, 0.0))
    assert far is not None and transforms.last_extrapolated
    assert "nearest reference pair" in caplog.text


def test_the_script_runs():
    result = subprocess.run([sys.executable, str(ROOT / "examples" / "rmf_fleet_adapter.py"),
                             str(MODEL), "--to-robot", "3,4,0.5"],
                            capture_output=True, text=True, check=True)
    assert result.stdout.count(",") == 2 and "std" in result.stdout
