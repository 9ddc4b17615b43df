"""e(v0) of every contact model from Python: Jiang & Liu's Fig. 4.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/restitution.py [--short] [--out F]

Two equal grains collide head-on in the engine at speeds from 1e-5 to 1e-1 (model units); for
the thermodynamic model the exact two-grain solver's curve is drawn beside the engine's.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import yuxi  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--short", action="store_true", help="two speeds a decade (the tests)")
    parser.add_argument("--out", default="restitution.png")
    args = parser.parse_args()

    table = yuxi.collide(per_decade=1 if args.short else 6)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for model in yuxi.built_in_models():
        for source, style in (("engine", "o-"), ("exact", "k--")):
            rows = (table["model"] == model) & (table["source"] == source)
            if rows.any():
                label = f"{model} ({source})" if source == "exact" else model
                ax.plot(table["impact_speed"][rows], table["e_n"][rows], style, ms=4, label=label)
    ax.set_xscale("log")
    ax.set_xlabel("impact speed 2 v0 [model units]")
    ax.set_ylabel("normal restitution e_n")
    ax.set_title("restitution against impact speed (Jiang & Liu 2018, Fig. 4)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print(args.out)


if __name__ == "__main__":
    main()
