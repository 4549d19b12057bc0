"""A short gymnasium training loop on planlab/Nav-v0: random search over a
tiny linear policy (goal bearing and the nearest obstacle ahead → v, ω),
compared with uniformly random actions. No downloads, a few seconds.

    python examples/python/gym_train.py [--iterations 20] [--episodes 3] [--out curve.png]
"""

import argparse
import math

import gymnasium as gym
import numpy as np

import planlab.gym  # noqa: F401  (registers planlab/Nav-v0)


def features(obs: np.ndarray, beams: int) -> np.ndarray:
    gx, gy = obs[beams], obs[beams + 1]
    bearing = math.atan2(gy, gx)
    ahead = min(obs[0], obs[1], obs[beams - 1])
    return np.array([1.0, bearing, math.cos(bearing), ahead])


def rollout(env, theta, beams, seed):
    obs, _ = env.reset(seed=seed)
    total = 0.0
    while True:
        if theta is None:
            act = env.action_space.sample()
        else:
            act = np.tanh(theta @ features(obs, beams))
            act = env.action_space.low + (act + 1) / 2 * (env.action_space.high
                                                          - env.action_space.low)
        obs, r, term, trunc, info = env.step(act.astype(np.float32))
        total += r
        if term or trunc:
            return total, info["outcome"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--iterations", type=int, default=20)
    ap.add_argument("--episodes", type=int, default=3)
    ap.add_argument("--out", default=None, help="PNG of the learning curve")
    args = ap.parse_args()

    beams = 12
    env = gym.make("planlab/Nav-v0", beams=beams, jitter=0.2)
    env.action_space.seed(0)
    rng = np.random.default_rng(0)
    best = np.zeros((2, 4))
    seeds = list(range(args.episodes))

    def score(theta):
        res = [rollout(env, theta, beams, s) for s in seeds]
        return np.mean([r for r, _ in res]), sum(o == "reached" for _, o in res)

    random_score, random_reached = score(None)
    best_score, best_reached = score(best)
    curve = [best_score]
    for i in range(args.iterations):
        cand = best + 0.5 * rng.standard_normal(best.shape)
        s, reached = score(cand)
        if s > best_score:
            best, best_score, best_reached = cand, s, reached
        curve.append(best_score)
        print(f"iteration {i + 1}: best mean return {best_score:.2f} "
              f"(reached {best_reached}/{len(seeds)})")
    print(f"random actions: mean return {random_score:.2f} "
          f"(reached {random_reached}/{len(seeds)})")
    print(f"tiny policy: mean return {best_score:.2f} (reached {best_reached}/{len(seeds)})")
    if args.out:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(5, 3.5))
        ax.plot(curve, marker="o", label="tiny linear policy")
        ax.axhline(random_score, color="gray", ls="--", label="random actions")
        ax.set_xlabel("iteration")
        ax.set_ylabel("mean return")
        ax.legend()
        fig.savefig(args.out, dpi=100, bbox_inches="tight")
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
