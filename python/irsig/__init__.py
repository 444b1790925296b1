"""irsig from Python: thermal-infrared images of 3-D scenes, the same model as the tools.

Every call runs irsig's Rust libraries in this process (the extension module
``irsig._irsig``); nothing here computes radiometry. Options are the command line's flags
in Python spelling: ``sub_bands=4`` is ``--sub-bands 4``, ``supersample=3`` is
``--supersample 3``, a ``True`` flag is given alone, a list repeats the flag. What each one
means physically is the tool's ``--help`` (``irsig-trace --help``) and README.md.

    >>> import irsig
    >>> irsig.flatten("pipelines/quickstart/scene.ron",
    ...               materials="pipelines/quickstart/materials.ron", output="scene.raw")
    >>> frame = irsig.trace(scene="scene.raw", materials="pipelines/quickstart/materials.ron",
    ...                     view="pipelines/quickstart/view.ron", band="8-14",
    ...                     atmosphere="us-std-1976", radiance_exr="radiance.exr")
    >>> ds = frame.dataset()          # xarray.Dataset: radiance and every truth layer
    >>> ds.apparent_temperature.plot()

Long work releases the GIL. A trace reports its progress to ``progress(done, total)`` (rows)
or, without one, to the ``irsig`` logger at DEBUG; Ctrl-C stops it (within the frame it
is tracing: the tracer finishes that frame's rows), and nothing is written. Errors are :class:`IrsigError`, with the file, line and column the
command line prints.
"""

from __future__ import annotations

import logging
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

from . import _irsig

__all__ = [
    "IrsigError",
    "Frame",
    "trace",
    "trace_frames",
    "read_exr",
    "run_stage",
    "flatten",
    "import_object",
    "atmos",
    "material",
    "therm",
    "sensor",
    "stats",
    "report",
    "merge",
]

log = logging.getLogger("irsig")

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[int, int], Any]

IrsigError = _irsig.IrsigError
IrsigError.__doc__ = (
    "An input irsig refuses, or a run that failed. ``message`` is what the command line "
    "prints; ``file``, ``line`` and ``column`` (from 1) say where in an input, or are None; "
    "``usage`` is True for a call that is malformed as written (the command line's exit 2)."
)
IrsigError.message = property(lambda self: self.args[0])
IrsigError.file = property(lambda self: self.args[1])
IrsigError.line = property(lambda self: self.args[2])
IrsigError.column = property(lambda self: self.args[3])
IrsigError.usage = property(lambda self: self.args[4])
IrsigError.__str__ = lambda self: str(self.args[0])


def _flags(options: Mapping[str, Any]) -> List[str]:
    """Keyword arguments as command-line flags: ``sky_view_rays=8`` is ``--sky-view-rays 8``."""
    argv: List[str] = []
    for key, value in options.items():
        flag = "-o" if key == "output" else "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            argv.append(flag)
        elif isinstance(value, (list, tuple)):
            for item in value:
                argv += [flag, os.fspath(item) if isinstance(item, os.PathLike) else str(item)]
        else:
            argv += [flag, os.fspath(value) if isinstance(value, os.PathLike) else str(value)]
    return argv


def _log_progress(done: int, total: int) -> None:
    log.debug("tracing: %d of %d rows", done, total)


class Frame:
    """One traced frame: its files' bytes and what the run said of it.

    ``files`` maps each file's suffix (``radiance.exr``, ``truth.exr``, and where the frame
    makes them ``map.png``, ``dc.png``, ``lut.txt``) to the bytes ``irsig-trace`` would
    write. ``decision`` is the pilot's decision (canonical RON) with ``tolerance=``.
    ``angles_x_deg`` and ``angles_y_deg`` are the pixel centres' angles from the optical
    axis (right and up positive), from the tracer's camera.
    """

    def __init__(self, raw: Mapping[str, Any]) -> None:
        self.files: Dict[str, bytes] = dict(raw["files"])
        self.decision: Optional[str] = raw["decision"]
        self.band: str = raw["band"]
        self.atmosphere: str = raw["atmosphere"]
        self.angles_x_deg: List[float] = list(raw["angles_x_deg"])
        self.angles_y_deg: List[float] = list(raw["angles_y_deg"])
        self.notes: List[str] = list(raw["notes"])
        self.warnings: List[str] = list(raw["warnings"])

    def dataset(self) -> "xarray.Dataset":  # noqa: F821 (xarray is imported lazily)
        """The radiance and every truth layer as one ``xarray.Dataset`` (``y``, ``x``).

        Coordinates: ``x`` and ``y`` in pixels (column and row of the pixel, from the top
        left), ``angle_x_deg`` and ``angle_y_deg`` beside them. Each variable's ``units``
        attribute is its EXR layer's. The dataset's attributes: ``band``, ``atmosphere``,
        ``radiance_units``, ``decision`` (empty without a tolerance), ``provenance`` (the
        EXR's provenance record, canonical RON) and ``run`` (the run's SHA-256).
        """
        radiance = read_exr(self.files["radiance.exr"], name="radiance.exr")
        truth = read_exr(self.files["truth.exr"], name="truth.exr")
        ds = truth.merge(radiance, compat="override", combine_attrs="override")
        ds = ds.assign_coords(
            angle_x_deg=("x", self.angles_x_deg), angle_y_deg=("y", self.angles_y_deg)
        )
        ds.angle_x_deg.attrs["units"] = "degree"
        ds.angle_y_deg.attrs["units"] = "degree"
        ds.attrs.update(
            band=self.band,
            atmosphere=self.atmosphere,
            radiance_units=ds.radiance.attrs.get("units", ""),
            decision=self.decision or "",
            provenance=radiance.attrs.get("provenance", ""),
            run=radiance.attrs.get("run", ""),
        )
        return ds

    @property
    def radiance(self) -> "numpy.ndarray":  # noqa: F821
        """The radiance at the sensor, W m⁻² sr⁻¹, as a read-only ``float32`` array (rows, columns)."""
        return read_exr(self.files["radiance.exr"], name="radiance.exr").radiance.values


def trace_frames(progress: Optional[Progress] = None, **options: Any) -> List[Frame]:
    """Traces every view of ``irsig-trace``'s options; one :class:`Frame` per view.

    ``options`` are the tracer's flags in Python spelling (``scene``, ``materials``,
    ``view`` (a list for several), ``band``, ``atmosphere``, ``atmosphere_model``,
    ``sub_bands``, ``tolerance``, ``pin``, ``sun_zenith_deg``, ``sun_utc``, ...), with its
    outputs (``output`` for ``-o PREFIX``, ``radiance_exr``, ``truth_exr``, ``map_png``,
    ``dc_png``, ``lut``, ``decision_out``): files named there are written as the command
    line writes them, all renamed into place at the end or none.
    """
    raw = _irsig.trace(_flags(options), progress if progress is not None else _log_progress)
    frames = [Frame(r) for r in raw]
    for note in frames[0].notes if frames else []:
        log.info("%s", note)
    for warning in frames[0].warnings if frames else []:
        log.warning("%s", warning)
    return frames


def trace(
    scene: PathLike,
    materials: PathLike,
    view: PathLike,
    *,
    progress: Optional[Progress] = None,
    **options: Any,
) -> Frame:
    """Traces one view: ``irsig-trace --scene SCENE --materials MATERIALS --view VIEW ...``.

    See :func:`trace_frames` for ``options`` and ``progress``. Raises :class:`IrsigError`
    for what the command line refuses, ``KeyboardInterrupt`` when interrupted (nothing is
    written), and ``ValueError`` when the view file holds more than one view.
    """
    frames = trace_frames(progress, scene=scene, materials=materials, view=view, **options)
    if len(frames) != 1:
        raise ValueError(f"{view} holds {len(frames)} views: use trace_frames")
    return frames[0]


def read_exr(source: Union[PathLike, bytes], name: Optional[str] = None) -> "xarray.Dataset":  # noqa: F821
    """An irsig EXR (a path or its bytes) as an ``xarray.Dataset``, one variable per layer.

    Dimensions ``y`` (rows from the top) and ``x`` (columns), both in pixels; each variable
    is a read-only view of the decoded samples (no copy). Attributes: each variable's
    ``units``; the dataset's ``provenance`` and ``run`` where the file has them.
    """
    import numpy as np
    import xarray as xr

    if isinstance(source, bytes):
        data, label = source, name or "<bytes>"
    else:
        with open(source, "rb") as f:
            data = f.read()
        label = name or os.fspath(source)
    width, height, layers, provenance, run = _irsig.read_exr(label, data)
    variables = {}
    for layer, unit, samples in layers:
        array = np.frombuffer(samples, dtype=np.float32).reshape(height, width)
        variables[layer] = xr.Variable(("y", "x"), array, attrs={"units": unit})
    coords = {"x": np.arange(width), "y": np.arange(height)}
    attrs = {k: v for k, v in (("provenance", provenance), ("run", run)) if v is not None}
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def run_stage(stage: str, *args: PathLike, **options: Any) -> None:
    """Runs ``irsig-<stage> ARGS --OPTIONS`` in this process, the GIL released.

    ``stage`` is one of ``STAGES`` (flatten, import, atmos, material, therm, sensor, stats,
    merge, report); positional ``args`` come first (``run_stage("atmos", "plan", ...)``).
    Raises :class:`IrsigError` as the command line would fail.
    """
    _irsig.run_stage(stage, [os.fspath(a) for a in args] + _flags(options))


STAGES: Sequence[str] = tuple(_irsig.STAGES)


def flatten(scene: PathLike, *, output: PathLike, **options: Any) -> None:
    """``irsig-flatten SCENE -o OUTPUT``: a scene and its objects into a raw scene file."""
    run_stage("flatten", scene, output=output, **options)


def import_object(mesh: PathLike, *, output: PathLike, **options: Any) -> None:
    """``irsig-import MESH -o OUTPUT``: a facet file, OBJ or glTF into a canonical object."""
    run_stage("import", mesh, output=output, **options)


def atmos(command: str, *args: PathLike, **options: Any) -> None:
    """``irsig-atmos COMMAND ...``: plan and build atmospheres through LOWTRAN7, convert."""
    run_stage("atmos", command, *args, **options)


def material(command: str, *args: PathLike, **options: Any) -> None:
    """``irsig-material COMMAND ...``: material libraries, Fresnel emissivities, listings."""
    run_stage("material", command, *args, **options)


def therm(scene: PathLike, *, output: PathLike, **options: Any) -> None:
    """``irsig-therm SCENE -o OUTPUT``: every facet's temperature from a heat balance."""
    run_stage("therm", scene, output=output, **options)


def sensor(radiance: PathLike, *, output: PathLike, **options: Any) -> None:
    """``irsig-sensor RADIANCE -o OUTPUT``: MTF, sampling, noise and counts of a radiance EXR."""
    run_stage("sensor", radiance, output=output, **options)


def stats(truth: PathLike, **options: Any) -> None:
    """``irsig-stats TRUTH ...``: the thesis's local-area analysis per region."""
    run_stage("stats", truth, **options)


def report(truth: PathLike, *, output: PathLike, **options: Any) -> None:
    """``irsig-report TRUTH -o OUTPUT``: the run report, one self-contained HTML page."""
    run_stage("report", truth, output=output, **options)


def merge(*tiles: PathLike, **options: Any) -> None:
    """``irsig-merge TILES ...``: a frame's traced tiles back into its files."""
    run_stage("merge", *tiles, **options)
