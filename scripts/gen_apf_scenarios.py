#!/usr/bin/env python3
"""Writes the potential-field reproduction presets
(assets/scenarios/T-fig4-*.json, T-tab4-1.json).

[T] ch. 4 draws its scenes only, so each is built to resemble its figure:
a point robot (the end effector / a small robot) stepping d = 0.04 m from
start to goal among discs (2D) or spheres (3D, T-tab4-1) of radius
0.05 m; movers move at constant velocity. The 2D scenes carry an empty
inline map (the page draws it; the run ignores it). The runs pick the
variant with `apf.config.mode`. Run from the repository root; the JSON
files are committed, this script documents how they were made.
"""
import json
import sys

RES = 0.02
ORIGIN = (-0.2, -0.6)
W, H = 80, 60  # 1.6 m x 1.2 m


def cell(x, y):
    c = int((x - ORIGIN[0]) / RES)
    r = H - 1 - int((y - ORIGIN[1]) / RES)
    return {"col": c, "row": r, "world": {"x": x, "y": y}}


def scene(name, description, start, goal, obstacles, config=None, **extra):
    apf = {"obstacles": obstacles, "config": config or {}}
    apf.update(extra)
    s2 = start[:2]
    g2 = goal[:2]
    if len(start) == 3:
        apf["start"] = start
        apf["goal"] = goal
    return {
        "version": 1,
        "name": name,
        "description": description,
        "map": {
            "width": W,
            "height": H,
            "resolution": RES,
            "origin": {"x": ORIGIN[0], "y": ORIGIN[1], "yaw": 0.0},
            "cells": ["." * W for _ in range(H)],
        },
        "start": cell(*s2),
        "goal": cell(*g2),
        "apf": apf,
    }


def disc(x, y, r=0.05, v=None, z=None):
    o = {"centre": [x, y] if z is None else [x, y, z], "radius": r}
    if v is not None:
        o["velocity"] = v
    return o


# Predicted instants t+1, t+2 at 0.8 s and 1.6 s ahead (the thesis plans
# every ~2 s; planlab's kinematic runs every 0.1 s).
PRED = {"predict_dt": 0.8}

SCENES = {
    "T-fig4-6": scene(
        "T-fig4-6 local minimum",
        "[T] Fig 4-6: start, a disc and the goal on one line; attraction and "
        "repulsion cancel in front of the disc.",
        [0.0, 0.0], [1.0, 0.0], [disc(0.5, 0.0)]),
    "T-fig4-8": scene(
        "T-fig4-8 goal near an obstacle",
        "[T] Fig 4-7 b / 4-8: the goal lies between the robot and a disc, "
        "inside its repulsion range.",
        [0.0, 0.0], [0.9, 0.0], [disc(1.0, 0.0)]),
    "T-fig4-10": scene(
        "T-fig4-10 head-on mover",
        "[T] Fig 4-10: a disc moves head-on along the robot's line.",
        [0.0, 0.0], [0.8, 0.0], [disc(0.6, 0.0, v=[-0.1, 0.0])], PRED),
    "T-fig4-11": scene(
        "T-fig4-11 mover, less overlap",
        "[T] Fig 4-11: the mover's line is offset from the robot's.",
        [0.0, 0.0], [0.8, 0.0], [disc(0.6, 0.04, v=[-0.1, 0.0])], PRED),
    "T-fig4-12": scene(
        "T-fig4-12 mover, little overlap",
        "[T] Fig 4-12: the mover's line is offset further.",
        [0.0, 0.0], [0.8, 0.0], [disc(0.6, 0.1, v=[-0.1, 0.0])], PRED),
    "T-tab4-1": scene(
        "T-tab4-1 end effector vs. hand (3D)",
        "[T] Table 4-1 / Fig 4-15: the end effector moves over a table while "
        "a hand reaches toward it head-on, slightly below its line.",
        [0.0, 0.0, 0.8], [0.7, 0.0, 0.8],
        [disc(0.55, 0.0, v=[-0.08, 0.0, 0.0], z=0.76)], PRED),
}

if __name__ == "__main__":
    only = sys.argv[1:]
    for name, s in SCENES.items():
        if only and name not in only:
            continue
        with open(f"assets/scenarios/{name}.json", "w") as f:
            json.dump(s, f, indent=2)
            f.write("\n")
