"""A study analysed in pandas: how much the VH watches the opponent's face
as its standing interest in it (personality `a_face`) grows, over several
seeds, from the samples themselves (no CSV).

    pip install "./crates/shisen-py[test]" matplotlib
    python3 crates/shisen-py/examples/study_pandas.py [--out docs/python/study.png]
"""

import argparse
import pathlib

import pandas as pd

import shisen

ROOT = pathlib.Path(__file__).resolve().parents[3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=str(ROOT / "docs/python/study.png"))
    ap.add_argument("--seconds", type=float, default=8.0)
    ap.add_argument("--seeds", type=int, default=4)
    args = ap.parse_args()

    base = shisen.Scene.load(ROOT / "scenes/default.ron")
    rows = []
    for a_face in [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]:
        for seed in range(args.seeds):
            scene = base.edit({"vh.personality.a_face": a_face}, seed=seed)
            df = shisen.to_frame(scene.run(duration=args.seconds, every=10))
            rows.append(
                {
                    "a_face": a_face,
                    "seed": seed,
                    "on_face": (df["gaze_target"] == "head").mean(),
                    "on_gloves": df["gaze_target"].str.endswith("glove").mean(),
                    "guarding": (df["action"] == "guard").mean(),
                    "mean_los_err_deg": df[["los_err_l", "los_err_r"]].mean(axis=1).mean(),
                }
            )
    study = pd.DataFrame(rows)
    summary = study.groupby("a_face")[["on_face", "on_gloves", "guarding"]].agg(["mean", "std"])
    print(summary.round(3).to_string())

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    for col, label in [("on_face", "gaze on the face"), ("on_gloves", "gaze on a glove"), ("guarding", "guarding")]:
        m, s = summary[(col, "mean")], summary[(col, "std")]
        ax.errorbar(summary.index, m, yerr=s, marker="o", capsize=3, label=label)
    ax.set_xlabel("personality a_face (standing interest in the opponent's face)")
    ax.set_ylabel(f"share of time ({args.seeds} seeds, {args.seconds:.0f} s each)")
    ax.set_ylim(0, 1)
    ax.legend()
    ax.set_title("Where the VH looks, by its interest in the face")
    fig.tight_layout()
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print("plot:", args.out)


if __name__ == "__main__":
    main()
