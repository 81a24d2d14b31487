"""Foveated AR Studio's model: scenes, traces, the registered analyses and grating physics."""
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]

class Scene:
    """A bench scene (docs/scene-format.md): what a scene file holds."""
    @staticmethod
    def load(path: str) -> "Scene":
        """Load a scene file; ValueError lists every problem, as `fovea-cli validate` does."""
    @staticmethod
    def embedded() -> "Scene":
        """The default prototype bench compiled into the studio."""
    @staticmethod
    def from_json(text: str) -> "Scene": ...
    def save(self, path: str) -> None:
        """Write the scene file atomically."""
    def to_json(self) -> str: ...
    def validate(self) -> List[str]: ...
    def summary(self) -> str: ...
    def copy(self) -> "Scene": ...
    def __getitem__(self, path: str) -> float | int:
        """The number at a JSON path: scene["eye.relief_mm"]; KeyError for no such number."""
    def __setitem__(self, path: str, value: float | int) -> None:
        """Set it; ValueError (scene unchanged) with the validator's message when refused."""

def run(analysis: str, scene: Scene, *, progress: Optional[Callable[[float], Any]] = None,
        **parameters: Any) -> Dict[str, Any]:
    """The `fovea-cli ANALYSIS SCENE ... --json` document; parameters by the registry's names
    with '_' for '-'. Ctrl-C cancels the study cleanly."""

def analyses() -> Dict[str, Dict[str, Any]]:
    """Every registered analysis: title, description, parameters (label, unit, default, help)."""

def trace(scene: Scene, gaze_deg: Optional[Tuple[float, float]] = None,
          hoe_shift_mm: Tuple[float, float] = (0.0, 0.0), **parameters: Any) -> Dict[str, Any]:
    """The `fovea-cli trace --json` document plus ['ray_arrays']: source_mm, hoe_point_mm,
    out_direction (N x 3), field_deg (N x 2), wavelength_nm, efficiency, pupil_radius_mm (N),
    hits_hoe, in_pupil (N, bool)."""

def kogelnik(n0: ArrayLike, n1: ArrayLike, thickness_um: ArrayLike, period_nm: ArrayLike,
             slant_deg: ArrayLike, probe_deg: ArrayLike, wavelength_nm: ArrayLike, *,
             polarization: str = "s", absorption_per_mm: ArrayLike = 0.0) -> Dict[str, np.ndarray]:
    """Kogelnik coupled-wave diffraction, element-wise over broadcast arrays: efficiency,
    zero_order, nu, xi, diffracted_deg (NaN when evanescent), reflection (bool)."""

def rcwa(n0: ArrayLike, n1: ArrayLike, thickness_um: ArrayLike, period_nm: ArrayLike,
         slant_deg: ArrayLike, probe_deg: ArrayLike, wavelength_nm: ArrayLike, *,
         polarization: str = "s", absorption_per_mm: ArrayLike = 0.0, orders: Optional[int] = None,
         slices: Optional[int] = None) -> Dict[str, np.ndarray]:
    """Rigorous coupled-wave analysis of the same gratings: efficiency, zero_order, kogelnik_efficiency."""
