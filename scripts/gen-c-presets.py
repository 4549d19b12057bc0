#!/usr/bin/env python3
"""Writes the [C] (cleaning-robot DWA) scenario presets:
assets/scenarios/C-tab3-{asphalt,hollow-brick}.json and
assets/scenarios/C-tab5-{asphalt,hollow-brick}.json.

The scene resembles [C] Fig 7 (no obstacles): an open parking-lot strip
(16.2 x 6.4 m at 0.1 m per cell, no walls; the map edge, 2 m away, is
the only boundary) and a polyline ("折线") global path: 4 m east, a 45°
climb of 2 m, 6 m east (two bends, near x = 6 and 8 m; [C] saw its largest
deviations at two bends near x = 5 and 9 m), with eight cleaning target
points where the robot stops; top speed 0.4 m/s on asphalt,
0.3 m/s on hollow brick ([C] §4.2). Re-run after editing the numbers here.
"""
import json
import os

RES = 0.1
W, H = 162, 64
ROOT = os.path.join(os.path.dirname(__file__), "..", "assets", "scenarios")

# Cleaning target points (cell centres, metres) 1–1.5 m apart, where the
# robot stops ([C] §2.1: many close targets, frequent acceleration and
# braking); start and goal at the ends. The path bends at x = 6 and 8 m.
START = (2.05, 2.05)
WAYPOINTS = [
    [3.55, 2.05],
    [5.05, 2.05],
    [6.05, 2.05],
    [7.05, 3.05],
    [8.05, 4.05],
    [9.55, 4.05],
    [11.05, 4.05],
    [12.55, 4.05],
]
GOAL = (14.05, 4.05)

# Slip (K_true, noise) and road per surface. Asphalt: a few per cent of
# scale error and a slight sideways drift; hollow brick: about twice that
# and much noisier (the paper reports larger deviations there).
SURFACES = {
    "asphalt": {
        "v_max": 0.4,
        "terrain": {
            "road": "asphalt",
            "slip": {
                "k_true": [[0.96, 0.0, 0.0], [0.07, 0.97, 0.0], [0.0, 0.0, 0.95]],
                "noise_xy": 0.03,
                "noise_theta": 0.05,
                "noise_theta_per_m": 0.02,
            },
            "bump_drag": 1.0,
            "vehicle": {},
        },
    },
    "hollow-brick": {
        "v_max": 0.3,
        "terrain": {
            "road": "hollow-brick",
            "slip": {
                "k_true": [[0.92, 0.03, 0.0], [0.12, 0.94, 0.0], [0.0, 0.0, 0.9]],
                "noise_xy": 0.08,
                "noise_theta": 0.1,
                "noise_theta_per_m": 0.05,
            },
            "bump_drag": 1.0,
            "vehicle": {},
        },
    },
}


def cell(p):
    col = int(p[0] / RES)
    row = H - 1 - int(p[1] / RES)
    return {"col": col, "row": row}


def scenario(exp, surface, what):
    s = SURFACES[surface]
    v = s["v_max"]
    return {
        "version": 1,
        "name": f"[C] {exp} — {surface}",
        "description": what,
        "map": {
            "width": W,
            "height": H,
            "resolution": RES,
            "origin": {"x": 0.0, "y": 0.0, "yaw": 0.0},
            "cells": ["." * W for _ in range(H)],
        },
        "start": cell(START),
        "goal": cell(GOAL),
        "robot": {
            "drive": "omnidirectional",
            "footprint": {"shape": "circle", "radius": 0.35},
            "limits": {
                "v_max": v,
                "v_min": -v,
                "vy_max": v,
                "w_max": 1.0,
                "acc_v": 2.0,
                "acc_vy": 2.0,
                "acc_w": 1.0,
            },
            "wheel_base": 0.5,
        },
        "start_yaw": 0.0,
        "local_planner": {
            "name": "cleaning-dwa",
            "config": {"waypoints": WAYPOINTS, "stop_at_waypoints": True},
        },
        "sim": {
            "dt": 0.1,
            "max_time": 200.0,
            "goal_tolerance": 0.2,
            "stuck_time": 20.0,
            "stuck_distance": 0.2,
            "sensing_range": 5.0,
            "record_rollouts": False,
            "unknown_is_obstacle": True,
        },
        "terrain": s["terrain"],
        "seed": 1,
    }


TEXT = {
    "C-tab3": "[C] Table 3 / Fig 7: the omnidirectional cleaning robot (Table 1: 0.35 m radius, 2 m/s² per axis) follows a polyline A* path (4 m east, a 45° climb of 2 m, 6 m east) across an open {surface} yard (16.2 × 6.4 m, no obstacles), stopping at each of eight cleaning target points 1–1.5 m apart, at up to {v} m/s, with wheel slip (K_true ≠ I plus noise) and road vibration. Run with `cleaning-dwa` (load limit + odometry compensation) and `traditional-dwa`; compare the tracking error to the global path.",
    "C-tab5": "[C] Table 5 / Figs 14–15: the same polyline run on {surface} (up to {v} m/s, slip, road vibration, Table 1 vehicle); the wheel loads of [C] eq 8 are computed every step from the true body accelerations and a_z. Compare the share of time every wheel carries more than 40 N between `traditional-dwa` and `cleaning-dwa`.",
}

for exp, text in TEXT.items():
    for surface in SURFACES:
        sc = scenario(exp, surface, text.format(surface=surface.replace("-", " "), v=SURFACES[surface]["v_max"]))
        path = os.path.join(ROOT, f"{exp}-{surface}.json")
        with open(path, "w") as f:
            json.dump(sc, f, indent=2, ensure_ascii=False)
            f.write("\n")
        print(path)
