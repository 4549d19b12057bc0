"""Run two planners on N seeded variants of a scenario and plot their
success rates (the episodes of `planlab batch`, spread by planlab.sweep).

    python examples/python/success_rates.py SCENARIO.json OUT.png \
        [--variants 100] [--planners dwa,improved-dwa] [--backend local|ray]

With --backend ray, Ray starts locally, or joins the cluster in RAY_ADDRESS.
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import planlab  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario")
    ap.add_argument("out")
    ap.add_argument("--variants", type=int, default=100)
    ap.add_argument("--planners", default="dwa,improved-dwa")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--jitter", type=float, default=0.3)
    ap.add_argument("--backend", default="local", choices=["local", "ray"])
    args = ap.parse_args()

    res = planlab.sweep(args.scenario, planners=args.planners.split(","),
                        variants=args.variants, seed=args.seed, jitter=args.jitter,
                        backend=args.backend)
    names = [s["planner"] for s in res.summaries]
    rates = [100 * s["success_rate"] for s in res.summaries]
    for s in res.summaries:
        print(f"{s['planner']}: success {100 * s['success_rate']:.1f}% "
              f"({s['reached']}/{s['runs']}; {dict(s['outcomes'])})")
    print(f"{res.episodes} episodes in {res.seconds:.1f} s on {args.backend} "
          f"({res.tasks} tasks of {res.variants_per_task} variants)")
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.bar(names, rates, color=["tab:blue", "tab:orange", "tab:green", "tab:red"][: len(names)])
    ax.set_ylim(0, 100)
    ax.set_ylabel("success rate (%)")
    ax.set_title(f"{args.variants} variants, jitter {args.jitter} m")
    for i, r in enumerate(rates):
        ax.text(i, r + 2, f"{r:.0f}%", ha="center")
    fig.savefig(args.out, dpi=100, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
