#!/usr/bin/env python3
"""Writes the [L] reproduction presets (assets/scenarios/L-*.json).

[L]'s maps are only drawn (Matlab figures 13-19), so each scene is built to
resemble its figure: walls as rectangles on an ASCII grid (0.1 m cells),
movers as discs. The robot is [L] Table 1's: R_safe 0.3 m, v_max 1 m/s,
omega_max 5pi/3 rad/s, a_max 0.5 m/s^2, alpha_max 4pi rad/s^2; LiDAR 10 m.
Run from the repository root; the JSON files are committed, this script
documents how they were made.
"""
import json
import math
import sys

sys.path.insert(0, "scripts")
from gen_dwa_scenarios import Grid, moving, pacing  # noqa: E402

PI = math.pi
ROBOT_L = {
    "drive": "differential",
    "footprint": {"shape": "circle", "radius": 0.3},
    "limits": {"v_max": 1.0, "v_min": 0.0, "vy_max": 0.0, "w_max": 5 * PI / 3,
               "acc_v": 0.5, "acc_vy": 0.0, "acc_w": 4 * PI},
    "wheel_base": 0.4,
}


# DWA on the scan: the heading weight is raised from the MATLAB sample's
# 0.05 (which, normalised by sum, lets clearance dominate and the robot
# wander) so the robot follows its target; [L] gives no DWA weights.
MOTION = {"alpha": 0.2}


def scenario(name, desc, g, start, goal, yaw, planner, max_time, movers=(), config=None,
             stuck_time=60.0):
    return {
        "version": 1, "name": name, "description": desc, "map": g.json(),
        "start": g.point(*start), "goal": g.point(*goal),
        "robot": ROBOT_L, "start_yaw": yaw, "movers": list(movers),
        "local_planner": {"name": planner, "config": dict(config or {}, **(
            {"motion": MOTION} if planner.endswith("-dwa") else {}))},
        "sim": {"dt": 0.1, "max_time": max_time, "goal_tolerance": 0.3,
                "stuck_time": stuck_time, "stuck_distance": 0.2, "sensing_range": 10.0,
                "record_rollouts": False, "unknown_is_obstacle": True},
        "seed": 1,
    }


def wall(g, x0, y0, x1, y1, gaps=(), gap=0.4):
    """A wall rectangle; `gaps` are positions along its long side where a
    `gap`-wide hole is cut (narrower than the robot: [L] sim 4)."""
    g.rect(x0, y0, x1, y1)
    horizontal = (x1 - x0) >= (y1 - y0)
    for p in gaps:
        for r in range(g.h):
            y = (g.h - 1 - r + 0.5) * g.res
            for c in range(g.w):
                x = (c + 0.5) * g.res
                if horizontal and y0 <= y <= y1 and p - gap / 2 <= x <= p + gap / 2:
                    g.cells[r][c] = "."
                if not horizontal and x0 <= x <= x1 and p - gap / 2 <= y <= p + gap / 2:
                    g.cells[r][c] = "."


def sim1():
    g = Grid(26, 18, 0.1)
    # A U open away from the robot; the goal inside; start, U and goal on
    # one horizontal line (symmetric).
    wall(g, 9.0, 5.0, 9.3, 13.0)     # back, facing the robot
    wall(g, 9.0, 5.0, 14.0, 5.3)     # lower arm
    wall(g, 9.0, 12.7, 14.0, 13.0)   # upper arm
    return scenario(
        "[L] sim 1: goal inside a U",
        "The goal lies inside a large U whose opening faces away from the robot; start, U "
        "and goal are symmetric about the start-goal line ([L] Fig 13a). The two candidate "
        "temporary goals cost almost the same: the hold period keeps the first choice "
        "until the symmetry is broken; the robot goes round and enters from the back.",
        g, (2.0, 9.0), (13.5, 9.0), 0.0, "lidar-dwa", 120.0)


def sim2():
    g = Grid(26, 18, 0.1)
    # A shallow U (1.2 m deep, 9 m wide) open toward the robot; the goal
    # behind it; symmetric.
    wall(g, 12.0, 4.5, 12.3, 13.5)   # back
    wall(g, 10.8, 4.5, 12.3, 4.8)    # lower lip
    wall(g, 10.8, 13.2, 12.3, 13.5)  # upper lip
    return scenario(
        "[L] sim 2: goal behind a U",
        "A U open toward the robot with the goal behind it, symmetric about the start-goal "
        "line ([L] Fig 13b): plain DWA drives into the U; the navigator picks one side, "
        "holds it and passes round.",
        g, (2.0, 9.0), (22.0, 9.0), 0.0, "lidar-dwa", 120.0)


def sim3():
    g = Grid(26, 18, 0.1)
    # The robot starts in a bay closed toward the goal and at the top; the
    # way out is at the bottom right, not symmetric.
    wall(g, 11.0, 3.0, 11.3, 18.0)   # long wall to the top edge
    wall(g, 4.0, 14.0, 11.3, 14.3)   # roof of the bay
    wall(g, 4.0, 8.5, 4.3, 14.3)     # back of the bay
    return scenario(
        "[L] sim 3: asymmetric enclosure",
        "Start and goal on either side of a long wall that reaches the top edge; the robot "
        "starts in a bay under a roof ([L] Fig 14a). The temporary goal moves along the wall "
        "as more of it comes into view and leads out round its lower end.",
        g, (7.0, 11.0), (19.0, 12.0), 0.0, "lidar-dwa", 120.0)


def sim4():
    g = Grid(26, 16, 0.1)
    # A Z-shaped channel (right, up, right) between two L-shaped walls.
    # Obstacles 1-3 (the L's legs) have 0.4 m holes, narrower than the
    # robot and than T_gap; obstacle 4 (the upper bar) is whole.
    wall(g, 0.0, 5.0, 13.3, 5.3, gaps=(4.0, 8.0, 11.0))    # 1: lower floor
    wall(g, 13.0, 5.0, 13.3, 16.0, gaps=(8.5, 12.5))       # 2: shaft, left side
    wall(g, 17.0, 0.0, 17.3, 10.3, gaps=(3.0, 7.0))        # 3: shaft, right side
    wall(g, 17.0, 10.0, 26.0, 10.3)                        # 4: upper bar
    return scenario(
        "[L] sim 4: Z channel with narrow holes",
        "A Z-shaped channel between two L-shaped walls: right along the bottom, up the "
        "shaft, right along the top ([L] Fig 14b). Obstacles 1-3 have 0.4 m holes, narrower "
        "than the robot and than T_gap: Algorithm 1 removes them and the temporary goals "
        "ignore them.",
        g, (2.0, 2.5), (23.0, 13.0), 0.0, "lidar-dwa", 150.0)


def sim5():
    g = Grid(24, 16, 0.1)
    # [L] Fig 15 vs improved DWA [17]: a long wall hooked at its top end.
    wall(g, 9.0, 2.5, 9.3, 12.5)
    wall(g, 9.0, 12.2, 13.0, 12.5)
    return scenario(
        "[L] sim 5: long hooked wall (vs DWA)",
        "A long wall across the way, hooked at its upper end, slightly offset from the "
        "start-goal line ([L] Fig 15). The navigator sees the wall early and heads for its "
        "lower end; plain DWA on the same scan meets it head-on and follows it.",
        g, (2.0, 9.0), (21.0, 8.0), 0.0, "lidar-dwa", 150.0)


def sim6():
    g = Grid(24, 16, 0.1)
    # [L] Fig 16 vs Critical-PointBug [21]: scattered blocks.
    for (x0, y0, x1, y1) in [(5, 5, 7, 11), (10, 2, 12, 7), (10, 9.5, 12, 14), (15, 6, 17, 12),
                             (19, 2, 20, 5)]:
        wall(g, x0, y0, x1, y1)
    return scenario(
        "[L] sim 6: scattered blocks (vs TangentBug)",
        "Scattered rectangular obstacles between start and goal ([L] Fig 16).",
        g, (1.5, 8.0), (22.5, 9.0), 0.0, "lidar-dwa", 150.0)


def sim7():
    g = Grid(20, 14, 0.1)
    # [L] Fig 17 vs RL-RRT [2]: two offset free-standing walls.
    wall(g, 6.0, 2.0, 6.3, 10.0)
    wall(g, 12.0, 4.0, 12.3, 12.0)
    return scenario(
        "[L] sim 7: two offset walls (vs RRT)",
        "Two free-standing walls, offset, across the way ([L] Fig 17).",
        g, (2.0, 6.0), (18.0, 8.0), 0.0, "lidar-dwa", 150.0)


def sim8():
    g = Grid(26, 16, 0.1)
    # [L] Fig 18 vs RS-APF [11]: blocks and a wall; APF underneath.
    for (x0, y0, x1, y1) in [(6, 5, 8, 11), (12, 9, 14, 13), (12, 2, 14, 6), (18, 5, 20, 10)]:
        wall(g, x0, y0, x1, y1)
    return scenario(
        "[L] sim 8: blocks (vs APF)",
        "Blocks across the way ([L] Fig 18); the motion planner under the navigator is the "
        "basic APF, compared with plain APF on the same scan.",
        g, (2.0, 8.0), (24.0, 8.0), 0.0, "lidar-apf", 150.0)


def sim9():
    g = Grid(20, 14, 0.1)
    movers = [
        pacing(1, [7.0, 3.0], [7.0, 11.0], 0.5, 0.3),
        pacing(2, [11.0, 11.0], [11.0, 3.0], 0.5, 0.3),
        moving(3, 16.0, 7.0, 0.5, -0.2, 0.0),
    ]
    dyn = {"nav": {"d_oe": 0.8, "d_te": 1.0, "switch_condition": False, "hold": False}}
    return scenario(
        "[L] sim 9: three moving obstacles",
        "Three discs (r 0.5 m) move across the way: two pace up and down, one comes head-on "
        "([L] Fig 19); APF under the navigator. Dynamic settings: d_oe 0.8 m, d_te 1 m, no extra switching conditions.",
        g, (1.5, 7.0), (18.5, 7.0), 0.0, "lidar-apf", 120.0, movers, dyn)


SCENES = {
    "L-sim1": sim1, "L-sim2": sim2, "L-sim3": sim3, "L-sim4": sim4, "L-sim5": sim5,
    "L-sim6": sim6, "L-sim7": sim7, "L-sim8": sim8, "L-sim9": sim9,
}

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/scenarios"
    only = sys.argv[2:] or list(SCENES)
    for name in only:
        with open(f"{out}/{name}.json", "w") as fh:
            json.dump(SCENES[name](), fh, indent=2)
            fh.write("\n")
        print("wrote", name)
