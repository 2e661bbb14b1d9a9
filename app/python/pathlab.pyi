"""pathlab: the path integral's sampling techniques (s,t), their densities and weights, from Python.

Set-up: build pathlab (./dev.sh check), then ``PYTHONPATH=build/python /usr/bin/python3``.
"""
import os
from typing import Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Image = npt.NDArray[np.float32]  # (height, width, 3), linear radiance
Technique = Union[Tuple[int, int], Tuple[str, int, int]]  # (s, t), ("M", s, t) or ("E", 1, t)

class Error(Exception):
    """A refused argument or a failed call, with the one-line message the command line prints."""

class TechniqueSet:
    """A set of sampling techniques, as ``--techniques SPEC``: connections (s,t) and merges M(s,t)."""
    def __init__(self, spec: str = "all") -> None:
        """Parses SPEC: ';'-separated ``S,T | s=S | t=T | k=K | all | MS,T | m=K | m=all``."""
    def __contains__(self, technique: Technique) -> bool: ...
    def __or__(self, other: TechniqueSet) -> TechniqueSet: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Scene:
    """A loaded glTF 2.0 scene."""
    path: str
    @property
    def bounds(self) -> Tuple[Tuple[float, float, float], float]:
        """(centre, radius) of the scene's bounding sphere."""
    @property
    def lights(self) -> int:
        """The number of lights (emissive triangles count one each)."""
    @property
    def triangle_count(self) -> int: ...
    @property
    def camera(self) -> dict:
        """camera_to_world (4 rows), yfov or orthographic, aspect_ratio, name."""
    @property
    def warnings(self) -> list[str]: ...

def load(
    path: Union[str, "os.PathLike[str]"],
    *,
    environment: Optional[Union[str, Sequence[float]]] = None,
    environment_strength: Optional[float] = None,
    environment_rotation: Optional[float] = None,
    default_light: bool = True,
    light_sampler: Optional[str] = None,
    max_triangles: Optional[int] = None,
) -> Scene:
    """Loads a glTF 2.0 scene; the arguments are ``pathlab render``'s loading options.

    environment: an equirectangular .exr/.hdr map or a constant radiance (r, g, b);
    light_sampler: 'auto', 'power' or 'bvh' (how next-event estimation chooses a light).
    Raises pathlab.Error naming the file and the problem.
    """

class Settings:
    """The options of ``pathlab render`` that decide the estimate (max_length=5 is --max-length 5)."""
    def __init__(
        self,
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        integrator: Optional[str] = None,
        max_length: Optional[int] = None,
        mis: Optional[str] = None,
        beta: Optional[float] = None,
        connect: Optional[str] = None,
        min_connection: Optional[float] = None,
        light_paths: Optional[Union[float, str]] = None,  # a number in (0, 1] or "auto"
        techniques: Optional[Union[str, TechniqueSet]] = None,
        isolate: Optional[Union[str, Tuple[int, int]]] = None,
        unweighted: bool = False,
        radius: Optional[float] = None,
        radius_alpha: Optional[float] = None,
        noncaustic_photons: Optional[float] = None,
        rr: bool = True,
        medium_sampling: Optional[str] = None,
        mlt_variant: Optional[str] = None,
        chains: Optional[int] = None,
        bootstrap: Optional[int] = None,
        large_step: Optional[float] = None,
        sigma: Optional[float] = None,
        seed: Optional[int] = None,
        aperture: Optional[float] = None,
        focus_distance: Optional[float] = None,
        inject_bias: Optional[str] = None,
        pyramid: Optional[int] = None,
        technique_maps: Optional[int] = None,
        variance_maps: Optional[int] = None,
        check_mis: bool = False,
        threads: Optional[int] = None,
    ) -> None:
        """integrator: 'bpt' (default), 'pt', 'lt', 'vcm', 'bpm', 'ppm', 'mlt' (mlt_variant 'mmlt' or 'pss'); mis: 'balance', 'power',
        'uniform', 'off', 'variance-aware', 'optimal'; connect: 'all' or 'endpoints' (naive BPT); isolate: "S,T" or "MS,T";
        width/height: neither given, the camera's shape with the longest side 512.
        Raises pathlab.Error naming the argument."""
    @property
    def integrator(self) -> str: ...
    @property
    def techniques(self) -> TechniqueSet:
        """The techniques the integrator uses (vcm: 'all;m=all')."""
    @property
    def max_length(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def pyramid(self) -> int: ...

def inspect(scene: Scene, settings: Settings, pixel: Tuple[int, int], sample: int = 0) -> dict:
    """One sample of one pixel replayed exactly as a render computes it: what ``pathlab inspect
    --json`` writes for the same options (every technique tried, its contribution, weight and path,
    and the path's density and MIS weight under every technique of its length), as dicts and lists."""

def check(
    scene: Scene,
    settings: Settings,
    *,
    spp: Optional[int] = None,
    time: Optional[float] = None,
    blocks: Optional[int] = None,
    alpha: Optional[float] = None,
    min_hits: Optional[int] = None,
    radius_levels: Optional[int] = None,
) -> dict:
    """``pathlab check``: does every enabled technique agree with the others on the paths both can
    sample? Returns what ``check --json`` writes: 'agrees', 'techniques' (a row each: its status,
    z-score, p-value and worst region), and with merges each merge's bias radius by radius. The
    image is 128 pixels on its longest side unless the settings give a size; render-only options
    (pyramid, technique_maps, check_mis) are refused."""

def converge(
    scene: Scene,
    configs: Union[Settings, Sequence[Settings], dict[str, Settings]],
    time: Optional[float] = None,
    spp: Optional[int] = None,
    reference: Optional[Union[str, "os.PathLike[str]", npt.ArrayLike]] = None,
    factor: float = 1.5,
    clock: str = "wall",
    mask: Optional[npt.ArrayLike] = None,
) -> dict[str, dict[str, np.ndarray]]:
    """``pathlab converge``: each configuration rendered for `time` seconds (default 10) or `spp`
    passes, its error recorded at checkpoints `factor` apart in time or passes.

    Returns {label: curve}; a list of Settings is labelled by their options ("integrator=pt
    max_length=5"). A curve holds one value per checkpoint: 'seconds' (on `clock`, 'wall' or 'cpu'),
    'wall_seconds', 'cpu_seconds', 'spp', 'camera_samples', 'rays', 'two_buffer_mse',
    'two_buffer_relmse', and with a reference (an array (height, width, 3) or an .exr/.pfm path)
    'mse', 'rmse', 'relmse', 'mape', 'bias2', 'variance'; and 'image', the final image. mask: an
    array (height, width), the error measured over its non-zero pixels. Ctrl+C raises
    KeyboardInterrupt after the pass in progress."""

class Renderer:
    """A progressive render of a scene with one Settings, pass after pass (one sample a pixel each)."""
    def __init__(self, scene: Scene, settings: Settings) -> None: ...
    def render(
        self,
        spp: Optional[int] = None,
        time: Optional[float] = None,
        progress: Optional[Callable[[int, float], None]] = None,
    ) -> Image:
        """Renders spp more passes (or for `time` seconds of wall time; neither: 64) and returns the
        image of every pass so far. The GIL is released meanwhile; progress(spp, seconds) is called
        after each pass. Ctrl+C raises KeyboardInterrupt after the pass in progress, and cancel()
        (from any thread) makes render() return then: every pass is kept. One render at a time
        per renderer; image(), pyramid(), counters(), technique_maps(), variance_maps() and
        outliers() are refused while a pass runs (call them from the progress callback, or after render returns)."""
    def cancel(self) -> None:
        """Stops render() after the pass in progress (safe from any thread); called while no
        render runs, it stops the next one at once."""
    def image(self) -> Image: ...
    def pyramid(self, max_length: Optional[int] = None) -> dict[Technique, Tuple[Image, Image]]:
        """Every technique up to max_length (Settings(pyramid=K)): (MIS-weighted share, own estimate)."""
    def technique_maps(self) -> dict:
        """With Settings(technique_maps=L): 'techniques' (keys in index order), 'dominant' {None (every
        length) or k: int32 (height, width) index into 'techniques', -1 no light, -2 a tie},
        'dominant_share', 'share' {key: the technique's share of the image, -1 where black},
        'cannot_sample' {key: the fraction of its length's image it cannot sample, -1 where black},
        and with merges 'merges_share'."""
    def variance_maps(self) -> dict:
        """With Settings(variance_maps=L): 'techniques' (keys in index order), 'variance' {key:
        float32 (height, width), the technique's variance of one pass's estimate of each pixel
        (luminance)}, 'dominant' (int32 index into 'techniques' of the technique with the most
        variance, -1 none, -2 a tie) and 'dominant_share' (its share of the techniques' variance)."""
    def find_outliers(self, top: int = 10) -> None:
        """Keeps the `top` brightest weighted contributions of the passes from the next one on (0
        stops; bpt, lt, vcm, bpm, ppm), as `pathlab outliers` does. Refused while render() runs."""
    def outliers(self) -> list[dict]:
        """What find_outliers kept, brightest first, each replayed: the entries of `pathlab outliers
        --json` (luminance, value, pixel, sample, technique, raster, shareOfPixel, densityRatio,
        bestTechnique, record)."""
    def counters(self) -> dict:
        """spp, seconds, camera_samples, rays, shadow_rays, discarded {nan, inf, negative}, and per
        technique (key (s, t), ("M", s, t) or ("E", 1, t)) and walk: tried, zero, blocked, contributed, discarded, rays."""
    @property
    def spp(self) -> int: ...
    @property
    def seconds(self) -> float: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
