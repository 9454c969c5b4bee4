"""Simulate a hexapod, certify it, and plot each leg's certified boxes (x0, x1, outer, inner) in
the (a_x, a_y) projection next to the truth. Needs matplotlib for the figure (prints otherwise).

    python calib-py/examples/plot_boxes.py [out.png]
"""

import sys
import tempfile
from pathlib import Path

import certicalib


def main() -> None:
    d = Path(tempfile.mkdtemp())
    truth = certicalib.simulate(d, configs=21, seed=11)
    report = certicalib.certify(d / "robot.toml", d / "measurements.csv", d / "uncertainty.toml")
    for leg in report.legs:
        print(f"leg {leg.leg}: {leg.status}, outer/inner ≤ {max(leg.ratio):.3f}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.patches import Rectangle
    except ImportError:
        print("matplotlib is not installed: no figure")
        return
    fig, axes = plt.subplots(2, 3, figsize=(12, 7))
    for ax, leg in zip(axes.flat, report.legs):
        for name, box, color in [("x0", leg.x0, "0.6"), ("x1", leg.x1, "tab:blue"),
                                 ("outer", leg.outer, "tab:purple"), ("inner", leg.inner, "tab:red")]:
            if box is None:
                continue
            (x_lo, x_hi), (y_lo, y_hi) = box[0], box[1]
            ax.add_patch(Rectangle((x_lo, y_lo), x_hi - x_lo, y_hi - y_lo, fill=False,
                                   edgecolor=color, label=name))
        t = truth["legs"][leg.leg - 1]["a"]
        ax.plot(t[0], t[1], "k+", label="truth")
        ax.set_xlim(*leg.x0[0]); ax.set_ylim(*leg.x0[1])
        ax.set_title(f"leg {leg.leg}: {leg.status}"); ax.set_xlabel("a_x [cm]"); ax.set_ylabel("a_y [cm]")
    axes.flat[0].legend(loc="upper right", fontsize="small")
    fig.tight_layout()
    out = sys.argv[1] if len(sys.argv) > 1 else "certified_boxes.png"
    fig.savefig(out, dpi=100)
    print(f"figure written to {out}")


if __name__ == "__main__":
    main()
