#!/usr/bin/env python3
"""Writes the DWA-family reproduction presets (assets/scenarios/{T,S}-*.json).

The papers' maps are only drawn, so each scene is built to resemble its
figure: walls as rectangles on an ASCII grid, discs as movers (still discs
have velocity 0). Run from the repository root; the JSON files are committed,
this script documents how they were made.
"""
import json
import math
import sys

DEG = math.pi / 180

# [S] §5: v_max 1 m/s, ω_max "20" (20°/s, as in the MATLAB DWA sample it
# follows), a_v 0.2 m/s², a_ω "50" (50°/s²); radius 0.2 m.
ROBOT_S = {
    "drive": "differential",
    "footprint": {"shape": "circle", "radius": 0.2},
    "limits": {"v_max": 1.0, "v_min": 0.0, "vy_max": 0.0, "w_max": 20 * DEG,
               "acc_v": 0.2, "acc_vy": 0.0, "acc_w": 50 * DEG},
    "wheel_base": 0.3,
}
# [T] gives no limits for its Python simulations; planlab's default robot
# (v_max 1 m/s, ω_max 40°/s, a_v 0.2 m/s², a_ω 50°/s², the common DWA
# sample values). Its figures draw the robot as a big circle and the
# obstacles as small ones: radius 0.25 m here, discs 0.15–0.2 m.
ROBOT_T = {
    "drive": "differential",
    "footprint": {"shape": "circle", "radius": 0.25},
    "limits": {"v_max": 1.0, "v_min": 0.0, "vy_max": 0.0, "w_max": 40 * DEG,
               "acc_v": 0.2, "acc_vy": 0.0, "acc_w": 50 * DEG},
    "wheel_base": 0.3,
}


class Grid:
    def __init__(self, w_m, h_m, res, border=True):
        self.res = res
        self.w = round(w_m / res)
        self.h = round(h_m / res)
        self.cells = [["."] * self.w for _ in range(self.h)]
        if border:
            for c in range(self.w):
                self.cells[0][c] = self.cells[self.h - 1][c] = "#"
            for r in range(self.h):
                self.cells[r][0] = self.cells[r][self.w - 1] = "#"

    def rect(self, x0, y0, x1, y1):
        """Blocks the cells whose centres lie in [x0, x1] × [y0, y1] (m)."""
        for r in range(self.h):
            y = (self.h - 1 - r + 0.5) * self.res
            if not (y0 <= y <= y1):
                continue
            for c in range(self.w):
                x = (c + 0.5) * self.res
                if x0 <= x <= x1:
                    self.cells[r][c] = "#"

    def point(self, x, y):
        col = int(x / self.res)
        row = self.h - 1 - int(y / self.res)
        return {"col": col, "row": row, "world": {"x": x, "y": y}}

    def json(self):
        return {"width": self.w, "height": self.h, "resolution": self.res,
                "origin": {"x": 0.0, "y": 0.0, "yaw": 0.0},
                "cells": ["".join(r) for r in self.cells]}


def still(i, x, y, r):
    return {"id": i, "radius": r,
            "motion": {"model": "constant-velocity", "start": [x, y], "velocity": [0.0, 0.0]}}


def moving(i, x, y, r, vx, vy):
    return {"id": i, "radius": r,
            "motion": {"model": "constant-velocity", "start": [x, y], "velocity": [vx, vy]}}


def pacing(i, a, b, r, speed):
    return {"id": i, "radius": r, "motion": {"model": "back-and-forth", "a": a, "b": b, "speed": speed}}


def scenario(name, desc, g, start, goal, yaw, movers, planner, max_time, tol=0.2, robot=ROBOT_T,
             stuck_time=20.0):
    return {
        "version": 1, "name": name, "description": desc, "map": g.json(),
        "start": g.point(*start), "goal": g.point(*goal),
        "robot": robot, "start_yaw": yaw, "movers": movers,
        "local_planner": {"name": planner, "config": {}},
        "sim": {"dt": 0.1, "max_time": max_time, "goal_tolerance": tol, "stuck_time": stuck_time,
                "stuck_distance": 0.2, "sensing_range": 5.0, "record_rollouts": False,
                "unknown_is_obstacle": True},
        "seed": 1,
    }


def t_fig3_2():
    g = Grid(12, 8, 0.1)
    # A C opening toward the robot, straddling the start–goal line.
    g.rect(7.0, 2.0, 7.3, 6.0)   # back
    g.rect(5.0, 2.0, 7.3, 2.3)   # lower arm
    g.rect(5.0, 5.7, 7.3, 6.0)   # upper arm
    return scenario(
        "[T] Fig 3-2: C-shaped trap",
        "A C-shaped wall between start and goal, open toward the robot ([T] Fig 3-2). "
        "Plain DWA follows the heading into the C and stays there; the A* key points lead "
        "the improved fusion around it.",
        g, (1.5, 4.0), (10.5, 4.0), 0.0, [], "improved-dwa", 120.0)


def t_fig3_11():
    g = Grid(12, 6, 0.1)
    movers = [
        # Near the start, top to bottom across the robot's line, stops at the edge.
        moving(1, 3.6, 5.6, 0.2, 0.0, -0.4),
        # Near the goal, still, on the start–goal line (special).
        still(2, 8.5, 3.0, 0.2),
    ]
    return scenario(
        "[T] Fig 3-11: dynamic and special obstacle",
        "Open room; a mover crosses the start–goal line near the start moving down "
        "(0.4 m/s, stops at the wall) and a still disc sits on the line near the goal "
        "([T] Fig 3-11).",
        g, (1.0, 3.0), (11.0, 3.0), 0.0, movers, "improved-dwa", 90.0)


def t_fig3_13(scene):
    g = Grid(10, 6, 0.1)
    if scene == "a":
        # Scene 1: the goal beside an obstacle the robot reaches the goal before.
        movers = [still(1, 8.2, 3.25, 0.2)]
        goal = (7.7, 3.0)
        desc = ("Scene 1 of [T] Fig 3-13: the goal lies 0.36 m from the surface of a disc "
                "of radius 0.2 m (0.11 m beyond the robot's footprint); the robot comes "
                "from the open side and reaches the goal's region before the obstacle.")
    else:
        # Scene 2: the obstacle lies on the line just before the goal.
        movers = [still(1, 7.4, 3.0, 0.2)]
        goal = (8.1, 3.05)
        desc = ("Scene 2 of [T] Fig 3-13: a disc of radius 0.2 m on the start–goal line "
                "just before the goal (0.5 m from its surface); the robot meets it first.")
    return scenario(
        f"[T] Fig 3-13{scene}: goal near an obstacle",
        desc, g, (1.0, 3.0), goal, 0.0, movers, "improved-dwa", 90.0)


def t_tab3_2():
    # An office-like map ([T] Fig 3-15/3-16): two walls make the A* path a
    # climb over wall A, a long middle run under wall B and a final diagonal.
    g = Grid(20, 12, 0.1)
    g.rect(5.0, 0.0, 5.3, 4.5)    # wall A
    g.rect(12.0, 6.5, 12.3, 12.0)  # wall B
    # Key points on the map inflated by 0.35 m: (5.15, 6.15), (12.45, 6.15),
    # then the goal: the middle run is horizontal at y = 6.15.
    fin = (0.875, 0.484)                     # direction of the final run
    n_fin = (-fin[1], fin[0])
    p4 = (16.39 + 0.15 * n_fin[0], 8.33 + 0.15 * n_fin[1])
    movers = [
        moving(1, 3.0, 7.0, 0.2, 0.0, -0.40),                        # 0.40 m/s across the climb
        moving(2, 8.5, 10.5, 0.2, 0.0, -0.28),                       # 0.28 m/s across the middle run
        moving(3, 10.0, 5.5, 0.2, 0.0, 0.07),                        # 0.07 m/s slowly across it
        moving(4, p4[0], p4[1], 0.2, 0.01 * n_fin[0], 0.01 * n_fin[1]),  # 0.01 m/s, leaving the line
    ]
    return scenario(
        "[T] Table 3-2: four movers",
        "Office-like map ([T] Fig 3-15/3-16) with four movers at 0.40, 0.28, 0.07 and "
        "0.01 m/s: the fast two cross the path, the 0.07 m/s one creeps across the middle "
        "run, the 0.01 m/s one sits 0.15 m off the final run, drifting away from it.",
        g, (1.0, 2.0), (18.5, 9.5), 0.0, movers, "improved-dwa", 300.0, stuck_time=60.0)


def s_map(res):
    """[S]-style grid map (Fig 2, 10): two long thin walls make the safe A*
    path an S (up past wall A, down under wall B, up to the goal); two
    blocks sit in the open, off the path. 24 × 16 m."""
    g = Grid(24, 16, res)
    g.rect(7.0, 0.0, 7.5, 10.5)     # wall A, from the bottom
    g.rect(15.0, 5.5, 15.5, 16.0)   # wall B, from the top
    g.rect(11.0, 12.0, 12.0, 13.0)  # block in the middle corridor
    g.rect(19.0, 5.5, 20.0, 6.5)    # block in the last corridor
    return g


S_START, S_GOAL = (2.0, 2.0), (22.0, 13.5)


def s_fig6():
    return scenario(
        "[S] Fig 6: Bottom-Up feature nodes",
        "The [S] map at 0.05 m: safe A* (24-neighbourhood, ε 100) finds a path of a few "
        "hundred nodes; Bottom-Up keeps a handful of feature nodes as temporary goals "
        "([S] Fig 6: 80 → 7).",
        s_map(0.05), S_START, S_GOAL, 0.0, [], "safe-dual-dwa", 200.0, robot=ROBOT_S)


def s_tab1():
    return scenario(
        "[S] Table 1 / Fig 10–11: dual velocity vs preliminary fusion",
        "The [S] map as a coarse grid (0.5 m cells, like the paper's): the preliminary "
        "fusion steers to every safe A* node and slows for each; the dual-velocity DWA "
        "steers to the Bottom-Up feature nodes and holds its speed near them.",
        s_map(0.5), S_START, S_GOAL, 0.0, [], "safe-dual-dwa", 400.0, robot=ROBOT_S,
        stuck_time=60.0)


def s_fig12():
    movers = [
        pacing(1, [1.0, 8.0], [6.0, 8.0], 0.3, 0.3),     # across the climb past wall A
        pacing(2, [11.5, 2.0], [11.5, 8.0], 0.3, 0.3),   # across the run under wall B
        pacing(3, [17.0, 10.0], [23.0, 10.0], 0.3, 0.3),  # across the climb to the goal
    ]
    return scenario(
        "[S] Fig 12: three back-and-forth movers",
        "The [S] Table 1 map with three discs pacing back and forth across the path "
        "(0.3 m/s, radius 0.3 m).",
        s_map(0.5), S_START, S_GOAL, 0.0, movers, "safe-dual-dwa", 400.0, robot=ROBOT_S,
        stuck_time=60.0)


SCENES = {
    "S-fig6": s_fig6,
    "S-tab1": s_tab1,
    "S-fig12": s_fig12,
    "T-fig3-2": t_fig3_2,
    "T-fig3-11": t_fig3_11,
    "T-fig3-13a": lambda: t_fig3_13("a"),
    "T-fig3-13b": lambda: t_fig3_13("b"),
    "T-tab3-2": t_tab3_2,
}

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/scenarios"
    for name, f in SCENES.items():
        with open(f"{out}/{name}.json", "w") as fh:
            json.dump(f(), fh, indent=2)
            fh.write("\n")
        print("wrote", name)
