"""The fish basin at m = 2 and 3 and at three amplitudes, from one settled bed.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/basin_sweep.py [--short]

The small basin (scenes/basin-small.toml) settles once, to just before the wall starts; each of
the six variants branches from that state (Simulation.branch: `yuxi run --from`), and a callback
records the height of the jets every 50 steps. The figure shows that height against
time for each. Under mpirun every rank runs its part; the heights come from every rank's grains,
gathered on rank 0.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import yuxi  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def jet_height(sim):
    """The height the jets reach: the 99th percentile of the grains' heights (single grains
    thrown far above the jets do not count). Collective; the value on rank 0, None elsewhere."""
    z, kind = sim.gather("position"), sim.gather("kind")
    if z is None:
        return None
    return float(np.percentile(z[kind == 0, 2], 99))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true",
                        help="a short settling and excitation (the tests): the path, not the physics")
    parser.add_argument("--scene", default=os.path.join(HERE, "..", "scenes", "basin-small.toml"))
    parser.add_argument("--runs", default="runs/basin-sweep")
    parser.add_argument("--out", default="basin_sweep.png")
    args = parser.parse_args()

    scene = yuxi.Scene(args.scene)
    t0 = scene.resolved()["basin"]["excitation"]["t0"]
    settle, excite = (0.3, 0.1) if args.short else (t0 - 0.1, 1.1)
    changes = {"analysis": None, "output": {"snapshot_interval": 0.0}}
    if args.short:
        changes["basin"] = {"excitation": {"t0": settle + 0.02}}
    base_scene = scene.changed(dict(changes, run={"name": "basin-settled", "t_end": settle}))
    base = os.path.join(args.runs, "settled")
    sim = yuxi.Simulation(base_scene, output=base, overwrite=True)
    sim.run()
    rank = sim.rank
    sim.close()

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for mode in (2, 3):
        for amplitude in (0.5, 0.7, 0.9):
            variant = scene.changed(dict(
                changes,
                run={"name": f"basin-m{mode}-a{amplitude}", "t_end": settle + excite},
                basin={"excitation": dict(changes.get("basin", {}).get("excitation", {}),
                                          mode=mode, amplitude=amplitude)}))
            sim = yuxi.Simulation.branch(base, variant, overwrite=True,
                                         output=os.path.join(args.runs, f"m{mode}-a{amplitude}"))
            times, heights = [], []

            def record(s):
                times.append(s.time)
                heights.append(jet_height(s))

            sim.run(callback=record, every=50)
            sim.close()
            ax.plot(times, heights, "-" if mode == 2 else "--",
                    label=f"m = {mode}, amplitude {amplitude} sigma")
    ax.set_xlabel("t [tau]")
    ax.set_ylabel("jet height: 99th percentile of grain heights [sigma]")
    ax.set_title("the fish basin: jets against mode and amplitude")
    ax.legend(fontsize=8)
    fig.tight_layout()
    if rank == 0:
        fig.savefig(args.out, dpi=130)
        print(args.out)


if __name__ == "__main__":
    main()
