# Type stub of the relume extension module (python/src/): its whole interface with types, for
# editors, type checkers and notebooks. The docstrings of the module itself say more.
import os
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
version_line: str

PathLike = Union[str, os.PathLike]
ArrayLike = npt.ArrayLike
Float32Array = npt.NDArray[np.float32]
Progress = Callable[[str, float], object]
Direction = Union[Tuple[float, float, float], ArrayLike]
Color = Union[Tuple[float, float, float], ArrayLike]

class Error(ValueError):
    """A relume error: bad input (an option, an array, a value) or failed work."""

class FileError(Error, OSError):
    """A relume error about a file: missing, unreadable, not what it should be, or not writable."""

class Field:
    """A fixed-viewpoint reflectance field; array attributes are read-only views (no copy)."""

    def __init__(
        self,
        values: Float32Array,
        dirs: ArrayLike,
        *,
        mask: Optional[ArrayLike] = None,
        intensities: Optional[ArrayLike] = None,
    ) -> None: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def channels(self) -> int: ...
    @property
    def lights(self) -> int: ...
    @property
    def values(self) -> Float32Array:
        """(height, width, channels, lights)."""
    @property
    def mask(self) -> npt.NDArray[np.uint8]:
        """(height, width), 1 = inside."""
    @property
    def directions(self) -> Float32Array:
        """(lights, 3), unit vectors towards the lights."""
    @property
    def intensities(self) -> Float32Array:
        """(lights, 3)."""
    @property
    def image_names(self) -> list[str]: ...
    def relight(
        self,
        light: Optional[ArrayLike] = None,
        *,
        light_dir: Optional[Direction] = None,
        color: Color = (1.0, 1.0, 1.0),
        spread: float = 0.0,
        threads: int = 0,
    ) -> Float32Array:
        """The uncompressed field relit: (height, width, channels), under a light vector
        (lights, 3) or a light moved to light_dir (see light_vector)."""
    def save(self, folder: PathLike) -> None: ...

class CompressOptions:
    """Every option of compress, compress_file and `relume compress` with its default (the
    command's --help explains each: the names are its options' with _ for -)."""

    def __init__(self, **options: object) -> None: ...
    method: str = "l1"
    pca_center: str = "none"
    pca_iterations: int = 20
    trimmed_refit: int = -1
    refit_chooses_clusters: bool = False
    clusters: int = 64
    terms: int = 4
    residual: Union[int, str] = "5%"
    residual_allocation: str = "per-function"
    noise_floor: float = -1.0
    threshold: float = -1.0
    solver: str = "irls"
    transform: str = "identity"
    light_weighting: float = 0.0
    channel_clusters: str = "shared"
    multires: int = 0
    refine: int = -1
    iterations: int = 4
    candidates: int = 3
    irls_iterations: int = 5
    min_cluster_size: int = -1
    max_cluster_size: int = 0
    seed: int = 1
    threads: int = 0
    assign: str = "opencl"
    device: str = ""
    weights_precision: str = "quantized"
    residual_precision: str = "quantized"
    bases_precision: str = "quantized"
    quantization_budget: float = -1.0
    term_budget: float = -1.0
    target_error: float = 0.0
    target_bytes: int = 0
    target_bytes_per_pixel: float = 0.0
    target_psnr: float = 0.0
    target_region: str = "frame"
    target_models: str = "all"
    psnr_white: float = 1.0
    psnr_mask: PathLike = ""
    mask_file: PathLike = ""
    use_mask: bool = True
    input_encoding: str = "auto"
    memory_limit: Union[int, str] = 0
    resume: bool = False
    scratch: PathLike = ""
    quiet: bool = True

class Compressed:
    """A compressed reflectance field; array attributes are read-only views (no copy)."""

    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def channels(self) -> int: ...
    @property
    def lights(self) -> int: ...
    @property
    def terms(self) -> int: ...
    @property
    def clusters(self) -> int: ...
    @property
    def stored_rows(self) -> int: ...
    @property
    def non_negative(self) -> bool:
        """The compressed field had no negative value: relit under non-negative lights, images are
        projected onto >= 0."""
    @property
    def transform(self) -> str: ...
    @property
    def mask(self) -> npt.NDArray[np.uint8]: ...
    @property
    def directions(self) -> Float32Array: ...
    @property
    def intensities(self) -> Float32Array: ...
    @property
    def stored_function(self) -> npt.NDArray[np.uint32]: ...
    @property
    def cluster(self) -> npt.NDArray[np.uint32]: ...
    @property
    def weights(self) -> Float32Array:
        """(stored_rows, terms)."""
    @property
    def bases(self) -> Float32Array:
        """(clusters, terms, lights)."""
    @property
    def residual_offsets(self) -> npt.NDArray[np.uint32]: ...
    @property
    def residual_indices(self) -> npt.NDArray[np.uint32]: ...
    @property
    def residual_values(self) -> Float32Array: ...
    @property
    def dark_pixels(self) -> npt.NDArray[np.uint32]:
        """(n,), pixels y * width + x relit by the dark model."""
    @property
    def dark(self) -> Float32Array:
        """(channels, lights), the dark model; (0, lights) when no pixel is dark."""
    @property
    def dark_gains(self) -> Float32Array:
        """(n, channels): channel c of dark pixel d is dark_gains[d, c] * dark[c]."""
    @property
    def weights_precision(self) -> str: ...
    @property
    def residual_precision(self) -> str: ...
    @property
    def parameters(self) -> dict: ...
    def relight(
        self,
        light: Optional[ArrayLike] = None,
        *,
        light_dir: Optional[Direction] = None,
        color: Color = (1.0, 1.0, 1.0),
        spread: float = 0.0,
        residual: Optional[int] = None,
        device: Optional[str] = None,
        reference: bool = False,
    ) -> Float32Array:
        """Relit image (height, width, channels) under a light vector (lights, 3) or a light
        moved to light_dir (see light_vector)."""
    def relight_batch(
        self,
        lights: ArrayLike,
        *,
        residual: Optional[int] = None,
        device: Optional[str] = None,
        reference: bool = False,
    ) -> Float32Array:
        """Relit images (count, height, width, channels) under (count, lights, 3)."""
    def reconstruct(self, *, residual: Optional[int] = None) -> Field: ...
    def save(
        self,
        path: PathLike,
        *,
        weights_precision: Optional[str] = None,
        residual_precision: Optional[str] = None,
        light_index: str = "auto",
    ) -> None: ...
    def export_npz(self, path: PathLike) -> None:
        """The arrays as a NumPy .npz, as `relume export --to npz` writes it."""
    def file_size(
        self,
        *,
        weights_precision: Optional[str] = None,
        residual_precision: Optional[str] = None,
        light_index: str = "auto",
    ) -> int: ...

def load(
    path: PathLike,
    *,
    input_encoding: str = "auto",
    mask_file: Optional[PathLike] = None,
    use_mask: bool = True,
    threads: int = 0,
) -> Field: ...
def open(path: PathLike) -> Compressed: ...
def compress(
    field: Union[Field, Float32Array],
    dirs: Optional[ArrayLike] = None,
    *,
    mask: Optional[ArrayLike] = None,
    intensities: Optional[ArrayLike] = None,
    report: Optional[PathLike] = None,
    progress: Optional[Progress] = None,
    method: str = "l1",
    pca_center: str = "none",
    pca_iterations: int = 20,
    trimmed_refit: int = -1,
    refit_chooses_clusters: bool = False,
    clusters: int = 64,
    terms: int = 4,
    residual: Union[int, str] = "5%",
    residual_allocation: str = "per-function",
    noise_floor: float = -1.0,
    threshold: float = -1.0,
    solver: str = "irls",
    transform: str = "identity",
    light_weighting: float = 0.0,
    channel_clusters: str = "shared",
    multires: int = 0,
    refine: int = -1,
    iterations: int = 4,
    candidates: int = 3,
    irls_iterations: int = 5,
    min_cluster_size: int = -1,
    max_cluster_size: int = 0,
    seed: int = 1,
    threads: int = 0,
    assign: str = "opencl",
    device: str = "",
    weights_precision: str = "quantized",
    residual_precision: str = "quantized",
    bases_precision: str = "quantized",
    quantization_budget: float = -1.0,
    term_budget: float = -1.0,
    target_error: float = 0.0,
    target_bytes: int = 0,
    target_bytes_per_pixel: float = 0.0,
    target_psnr: float = 0.0,
    target_region: str = "frame",
    target_models: str = "all",
    psnr_white: float = 1.0,
    psnr_mask: PathLike = "",
    mask_file: PathLike = "",
    use_mask: bool = True,
    input_encoding: str = "auto",
    memory_limit: Union[int, str] = 0,
    resume: bool = False,
    scratch: PathLike = "",
    quiet: bool = True,
) -> Compressed: ...
def compress_file(
    input: PathLike,
    output: PathLike,
    *,
    report: Optional[PathLike] = None,
    progress: Optional[Progress] = None,
    method: str = "l1",
    pca_center: str = "none",
    pca_iterations: int = 20,
    trimmed_refit: int = -1,
    refit_chooses_clusters: bool = False,
    clusters: int = 64,
    terms: int = 4,
    residual: Union[int, str] = "5%",
    residual_allocation: str = "per-function",
    noise_floor: float = -1.0,
    threshold: float = -1.0,
    solver: str = "irls",
    transform: str = "identity",
    light_weighting: float = 0.0,
    channel_clusters: str = "shared",
    multires: int = 0,
    refine: int = -1,
    iterations: int = 4,
    candidates: int = 3,
    irls_iterations: int = 5,
    min_cluster_size: int = -1,
    max_cluster_size: int = 0,
    seed: int = 1,
    threads: int = 0,
    assign: str = "opencl",
    device: str = "",
    weights_precision: str = "quantized",
    residual_precision: str = "quantized",
    bases_precision: str = "quantized",
    quantization_budget: float = -1.0,
    term_budget: float = -1.0,
    target_error: float = 0.0,
    target_bytes: int = 0,
    target_bytes_per_pixel: float = 0.0,
    target_psnr: float = 0.0,
    target_region: str = "frame",
    target_models: str = "all",
    psnr_white: float = 1.0,
    psnr_mask: PathLike = "",
    mask_file: PathLike = "",
    use_mask: bool = True,
    input_encoding: str = "auto",
    memory_limit: Union[int, str] = 0,
    resume: bool = False,
    scratch: PathLike = "",
    quiet: bool = True,
) -> Dict[str, Any]:
    """The report, as `relume compress --report` writes it."""
def relative_error(
    original: Field,
    compressed: Compressed,
    *,
    masked: bool = True,
    residual: Optional[int] = None,
    threads: int = 0,
) -> float: ...
def light_vector(
    dirs: ArrayLike,
    env: Optional[Union[PathLike, ArrayLike]] = None,
    *,
    light_dir: Optional[Union[Direction, Sequence[Direction]]] = None,
    color: Color = (1.0, 1.0, 1.0),
    spread: float = 0.0,
    rotate: Union[float, Sequence[float], ArrayLike] = 0.0,
    layout: str = "auto",
    threads: int = 0,
) -> Float32Array:
    """Of an environment map (env, with rotate and layout) or of a light moved to light_dir
    (with color and spread): (lights, 3) for one angle or direction, (count, lights, 3) for a
    sequence of angles or (count, 3) directions."""
def sky(
    *,
    width: int = 512,
    sun_elevation: float = 35.0,
    sun_azimuth: float = 30.0,
    sun_radiance: float = 5000.0,
    sun_radius: float = 2.0,
) -> Float32Array: ...
def factor(
    matrix: ArrayLike,
    terms: int,
    *,
    solver: str = "lp-dual",
    init: str = "random-basis",
    seed: int = 1,
    max_iterations: int = 50,
    tolerance: float = 1e-8,
    residual_threshold: Optional[float] = None,
    gamma: float = 1e-3,
    irls_tolerance: float = 1e-6,
    nonnegative_residual: bool = False,
    threads: int = 0,
    progress: Optional[Progress] = None,
) -> Tuple[npt.NDArray, npt.NDArray, npt.NDArray]:
    """(W, F, E) in the matrix's dtype."""
def read_image(path: PathLike, *, srgb: bool = False) -> Float32Array: ...
def write_image(path: PathLike, image: ArrayLike, *, exposure: float = 0.0) -> None: ...
