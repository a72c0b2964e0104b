#!/usr/bin/python3
"""Robot poses between a robot's gridmap and the building's plan frame, the way an Open-RMF
fleet adapter converts them, with a floorgrid model instead of a similarity.

Open-RMF's fleet adapter template fits a `nudged` similarity (one scale, rotation and shift)
to a few hand-picked point pairs per level and converts every pose with it:

    transforms = {"rmf_to_robot": nudged.estimate(rmf_coordinates, robot_coordinates),
                  "robot_to_rmf": nudged.estimate(robot_coordinates, rmf_coordinates)}
    x, y = transforms["rmf_to_robot"].transform([rmf_x, rmf_y])
    theta = rmf_theta + transforms["rmf_to_robot"].get_rotation()

A robot's map is rarely a similarity of the drawing: it bends where the SLAM drifted. A
floorgrid model (`floorgrid align` or `fit`) follows the bend, maps the heading through its
local Jacobian, and says how sure each pose is (std_m) and where it is extrapolated, far from
every reference pair. Copy FloorgridTransforms into the adapter in place of the nudged pair.

    python3 examples/rmf_fleet_adapter.py MODEL.json --to-robot 12.5,3.0,1.57
    python3 examples/rmf_fleet_adapter.py MODEL.json --to-rmf 10.1,4.2,0.3
"""

from __future__ import annotations

import argparse
import logging
import math
from typing import Dict, Optional, Tuple

import numpy as np

import floorgrid

Pose = Tuple[float, float, float]  # x, y (metres), yaw (radians)

log = logging.getLogger("floorgrid_fleet_adapter")


class FloorgridTransforms:
    """The RMF (building plan) frame <-> the robot's map frame, per level, through floorgrid
    models: to_robot_map and to_rmf_map as the template's transform functions."""

    def __init__(self, models: Dict[str, floorgrid.Model]):
        self.models = models  # level name -> model fitted plan (RMF) -> gridmap (robot)
        self.last_std_m: Optional[float] = None
        self.last_extrapolated = False

    @classmethod
    def from_files(cls, files: Dict[str, str]) -> "FloorgridTransforms":
        return cls({level: floorgrid.Model.load(path) for level, path in files.items()})

    def _convert(self, level: str, pose: Pose, to_robot: bool) -> Optional[Pose]:
        model = self.models[level]
        mapping = model.forward if to_robot else model.inverse
        mapped = mapping(np.array([pose], dtype=np.float64))
        flag = mapped.flag_names[0]
        self.last_std_m = None if math.isnan(mapped.std_m[0]) else float(mapped.std_m[0])
        self.last_extrapolated = bool(mapped.extrapolated[0])
        if flag == "not_invertible":
            log.error("level %s: pose %s has no %s pose (the model folds there)", level, pose,
                      "robot" if to_robot else "RMF")
            return None
        if self.last_extrapolated:
            log.warning("level %s: pose %s is %s: %.1f m from the nearest reference pair, "
                        "the conversion is a guess there", level, pose, flag,
                        mapped.nearest_pair_m[0])
        x, y, yaw = mapped.values[0]
        return float(x), float(y), math.remainder(float(yaw), 2 * math.pi)

    def to_robot_map(self, level: str, rmf_pose: Pose) -> Optional[Pose]:
        """An RMF (plan) pose on the robot's map: the template's rmf_to_robot.transform."""
        return self._convert(level, rmf_pose, True)

    def to_rmf_map(self, level: str, robot_pose: Pose) -> Optional[Pose]:
        """A robot's map pose in the RMF frame: the template's robot_to_rmf.transform."""
        return self._convert(level, robot_pose, False)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", help="model file of `floorgrid align` or `fit`")
    parser.add_argument("--level", default="L1")
    direction = parser.add_mutually_exclusive_group(required=True)
    direction.add_argument("--to-robot", metavar="X,Y,YAW", help="an RMF pose")
    direction.add_argument("--to-rmf", metavar="X,Y,YAW", help="a robot's map pose")
    args = parser.parse_args()
    logging.basicConfig(format="%(levelname)s %(message)s")
    transforms = FloorgridTransforms.from_files({args.level: args.model})
    text = args.to_robot or args.to_rmf
    pose = tuple(float(v) for v in text.split(","))
    if len(pose) != 3:
        parser.error("a pose is x,y,yaw")
    convert = transforms.to_robot_map if args.to_robot else transforms.to_rmf_map
    result = convert(args.level, pose)
    if result is None:
        raise SystemExit(1)
    std = "n/a" if transforms.last_std_m is None else f"{transforms.last_std_m:.3f} m"
    print(f"{result[0]:.6f},{result[1]:.6f},{result[2]:.6f}  std {std}"
          f"{'  extrapolated' if transforms.last_extrapolated else ''}")


if __name__ == "__main__":
    main()
