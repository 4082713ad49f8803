# Type stubs for the jgpm module (tracker/python/jgpm_module.cc). Arrays are NumPy float64;
# lengths millimetres, angles degrees.
from os import PathLike
from typing import Callable, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
_Path = Union[str, PathLike[str]]
_Array = npt.ArrayLike

class InputError(ValueError):
    """A file or value jgpm cannot use; the message names the file (and line) or option."""

class Motion:
    """A motion read from ASF/AMC or BVH."""
    @property
    def num_frames(self) -> int: ...
    @property
    def frames_per_second(self) -> float: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def values(self) -> npt.NDArray[np.float64]:
        """frames x channels, read-only view."""
    def joint_positions(self) -> npt.NDArray[np.float64]:
        """frames x joints x 3, mm."""
    def write_bvh(self, path: _Path) -> None: ...
    def write_amc(self, path: _Path) -> None: ...

def read_motion(path: _Path, asf: Optional[_Path] = None, amc_fps: float = 120.0,
                bvh_mm_per_unit: float = 10.0) -> Motion: ...

class Model:
    """A trained gait prior (jgpm train's JSON)."""
    @property
    def kind(self) -> str: ...
    @property
    def num_channels(self) -> int: ...
    @property
    def channel_names(self) -> list[str]: ...
    @property
    def latent(self) -> npt.NDArray[np.float64]: ...
    @property
    def has_dynamics(self) -> bool: ...
    @property
    def has_manifold(self) -> bool: ...
    def mean_pose(self, latent: _Array) -> npt.NDArray[np.float64]:
        """(M, 3) -> (M, D); (3,) -> (D,)."""
    @overload
    def log_density(self, latent: _Array) -> Union[float, npt.NDArray[np.float64]]: ...
    @overload
    def log_density(self, latent: _Array, gradient: bool) -> Union[
        float, npt.NDArray[np.float64], Tuple[Union[float, npt.NDArray[np.float64]], npt.NDArray[np.float64]]]: ...
    def next_latent(self, latent: _Array) -> npt.NDArray[np.float64]: ...
    def joint_positions(self, pose: _Array) -> npt.NDArray[np.float64]:
        """(M, D) -> (M, joints, 3); (D,) -> (joints, 3)."""
    def manifold_to_latent(self, phase: float, gait: float, scale: float) -> npt.NDArray[np.float64]: ...
    def save(self, path: _Path) -> None: ...
    def latent_to_manifold(self, latent: _Array) -> Tuple[float, float, float]: ...

def load_model(path: _Path) -> Model: ...
def train(kind: str, cycles: Optional[_Path] = None, data: Optional[str] = None, split: str = "train",
          learning: str = "full", max_iterations: int = 0, seed: int = 1,
          progress: Optional[Callable[[dict], None]] = None) -> Model: ...
def infer(model: Model, poses: _Array, observed: Optional[list[bool]] = None, adapt: bool = False) -> dict: ...
def calibrate_from_walkers(takes: list[list[str]], person_height_m: float = 1.70, backgrounds: list[str] = [],
                           intrinsics: list[str] = [], max_clock_offset_s: float = 2.0) -> list[Camera]: ...
def track_video(model: _Path, videos: list[str], cameras: list[str], out: Optional[str] = None,
                backgrounds: list[str] = [], seed: int = 1, threads: int = 0, people: str = "one",
                occluders: list[str] = []) -> dict: ...

class Camera:
    """A calibrated camera (OpenCV's pinhole model, world in millimetres)."""
    @staticmethod
    def from_yaml(path: str) -> Camera: ...
    name: str
    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float
    clock_offset_s: float
    @property
    def camera_matrix(self) -> npt.NDArray[np.float64]: ...
    @property
    def distortion(self) -> list[float]: ...
    @property
    def rotation(self) -> npt.NDArray[np.float64]: ...
    @property
    def translation_mm(self) -> npt.NDArray[np.float64]: ...
    @property
    def centre_mm(self) -> npt.NDArray[np.float64]: ...
    def project(self, points: _Array) -> npt.NDArray[np.float64]:
        """(M, 3) -> (M, 2) pixels; NaN for a point not in front of the camera."""

class Tracker:
    """The annealed particle filter in a prior's latent space, fed binary masks from any segmenter."""
    def __init__(self, model: Model, cameras: list[Camera], seed: int = 1, particles: int = 200, layers: int = 4,
                 threads: int = 0, fps: float = 30.0, people: str = "one", max_people: int = 8) -> None: ...
    def step(self, masks: Optional[list[_Array]]) -> list[dict]:
        """One frame's masks (one per camera, H x W, nonzero = person) or None; the frames tracked by this call
        (people='all': each {frame, time_s, people, born, ended}). people='one': a start's frames are given a
        second or more after it (once its leg order is settled: about 1.33 s), gone over again backwards."""
    def finish(self) -> list[dict]:
        """The frames still held when the sequence ended (for the start, or for going back over it)."""
    @property
    def joint_names(self) -> list[str]: ...
