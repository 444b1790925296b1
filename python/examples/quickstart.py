"""The quickstart (pipelines/quickstart.ron) from Python, plotted with matplotlib.

Flattens the scene, traces it at 512 x 384 in 8-14 um through the built-in US Standard
1976 atmosphere, blurs it with the 1990 sensor's 5 x 5 IFOV, and plots the sensor's
apparent temperature in kelvin beside the traced radiance. The files are the pipeline's
(out/quickstart-python/ holds the same bytes as the command line's out/quickstart/).

    pip install ./python matplotlib         # from the repository root
    python python/examples/quickstart.py    # writes out/quickstart-python/plot.png
"""

import logging
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import irsig  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
SCENE = REPO / "pipelines" / "quickstart"
OUT = REPO / "out" / "quickstart-python"


def main() -> None:
    logging.basicConfig(level=logging.INFO, format="%(name)s: %(message)s")
    OUT.mkdir(parents=True, exist_ok=True)
    irsig.flatten(SCENE / "scene.ron", materials=SCENE / "materials.ron",
                  output=OUT / "scene.raw")
    frame = irsig.trace(
        OUT / "scene.raw",
        SCENE / "materials.ron",
        SCENE / "view.ron",
        band="8-14",
        atmosphere="us-std-1976",
        atmosphere_model="table",
        radiance_exr=OUT / "radiance.exr",
        truth_exr=OUT / "truth.exr",
        map_png=OUT / "map.png",
        progress=lambda done, total: print(f"\rtracing {done}/{total} rows", end="", flush=True),
    )
    print()
    irsig.sensor(OUT / "radiance.exr", output=OUT / "sensor.exr", mtf="box:5x5",
                 dc_per_kelvin=4, temperature_exr=OUT / "temperature.exr",
                 lut=OUT / "lut.txt")
    traced = frame.dataset()
    sensed = irsig.read_exr(OUT / "temperature.exr")
    kelvin = sensed[list(sensed.data_vars)[0]]

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.2), constrained_layout=True)
    traced.radiance.plot.imshow(ax=left, yincrease=False, cmap="gray",
                                cbar_kwargs={"label": "W m$^{-2}$ sr$^{-1}$"})
    left.set_title(f"radiance at the sensor, {traced.attrs['band']} um")
    kelvin.plot.imshow(ax=right, yincrease=False, cmap="inferno",
                       cbar_kwargs={"label": "K"})
    right.set_title("apparent temperature after the 5 x 5 IFOV")
    fig.savefig(OUT / "plot.png", dpi=100)
    print(f"{OUT / 'plot.png'}")


if __name__ == "__main__":
    main()
