"""Generate the stereo head and the scene of chapter 4.1 (``stereo_rig.json``, ``stereo_scene.json``).

Run from anywhere: ``python data/stereo_make.py``.  Only the standard library
is used.  The numbers are chosen by hand (the thesis does not give its stereo
head's calibration): a 12 cm baseline and a 640x480 image with a 700 px focal
length (49 degrees of horizontal field of view), mounted 1.2 m above the floor
and tilted 20 degrees down, looking at a few everyday objects 1.5-3.5 m away.

World frame: x forward, y to the left, z up, metres; the floor is z = 0.
"""

import json
import math
from pathlib import Path

HERE = Path(__file__).resolve().parent

RIG = {
    "name": "geometer stereo head (synthetic)",
    "frame": "world: x forward, y left, z up, metres; camera: x right, y down, z forward",
    "image_size": [640, 480],
    "focal_px": 700.0,
    "principal_point": [319.5, 239.5],
    "baseline_m": 0.12,
    "head_position_m": [0.0, 0.0, 1.2],
    "yaw_rad": 0.0,
    "tilt_rad": round(math.radians(20.0), 12),
    "note": "Both cameras share K and orientation (a parallel rig); the head position is the midpoint of the centres.",
}

_YAW = math.radians(25.0)

SCENE = {
    "name": "objects in front of the robot (section 4.1, figure 4.2)",
    "frame": RIG["frame"].split(";")[0] + "; floor z = 0",
    "points": [
        [1.9, 0.55, 0.75],
        [2.2, -0.65, 0.30],
        [2.7, 0.10, 0.05],
        [3.1, 0.80, 0.95],
        [1.6, 0.05, 0.10],
        [2.5, -0.15, 1.05],
    ],
    "segment": {"a": [2.6, -0.95, 0.0], "b": [2.35, -0.7, 1.05], "what": "a broom handle leaning on the wall"},
    "circle": {
        "center": [1.7, -0.3, 0.45],
        "normal": [0.0, 0.0, 1.0],
        "radius": 0.13,
        "what": "the rim of a plate on a low table",
    },
    "plane": {
        "center": [3.2, 0.25, 0.55],
        "normal": [-math.cos(_YAW), -math.sin(_YAW), 0.0],
        "up": [0.0, 0.0, 1.0],
        "size": [0.9, 0.7],
        "what": "a board standing on the floor, turned 25 degrees",
    },
    "sphere": {"center": [2.1, 0.45, 0.11], "radius": 0.11, "what": "a ball on the floor"},
}


def main():
    for name, obj in (("stereo_rig.json", RIG), ("stereo_scene.json", SCENE)):
        (HERE / name).write_text(json.dumps(obj, indent=1) + "\n")


if __name__ == "__main__":
    main()
