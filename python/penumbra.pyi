"""Penumbra: shadow techniques rendered on the device and measured against a ray-traced truth,
as NumPy arrays (docs/python.md)."""

from typing import Any, Mapping, Optional, Sequence

import numpy as np
import numpy.typing as npt

Vec3 = Sequence[float]

class InputError(ValueError):
    """Bad input: the CLI's one-line message, `subject: what`."""

class DeviceError(RuntimeError):
    """The device failed (lost, out of memory) or the validation layer reported an error."""

class Scene:
    """A scene in memory: a glTF file or a built-in scene."""

    @staticmethod
    def load(
        path: str,
        max_file_size: int = 1 << 30,
        max_triangles: int = 100_000_000,
        no_ground: bool = False,
        time: Optional[float] = None,
        animation: str = "",
    ) -> Scene:
        """Loads a glTF 2.0 file (.gltf, .glb) or 'builtin:NAME' as the CLI does: a ground is
        added where nothing in view receives a cast shadow (warnings says so) unless no_ground;
        time (seconds) poses it in the animation named or numbered by animation (default the
        first), as --time and --animation do. Raises InputError naming the file or option."""
    @staticmethod
    def builtin(name: str, no_ground: bool = False) -> Scene:
        """A built-in scene: 'demo', 'showcase', ... (or 'builtin:demo'), or a generated one:
        'gen/FAMILY?seed=N[&scale=S]' (docs/scenes.md, "Generated scenes")."""
    def edit(
        self,
        *,
        sun_dir: Optional[Vec3] = None,
        light_pos: Mapping[str, Vec3] = {},
        light_dir: Mapping[str, Vec3] = {},
        camera_pos: Optional[Vec3] = None,
        look_at: Optional[Vec3] = None,
        fov: Optional[float] = None,
        add_light: Sequence[str] = (),
        view: Optional[str] = None,
        ground: bool = False,
        double_sided: bool = False,
    ) -> None:
        """The CLI's scene options, in place (all or nothing); InputError names the option."""
    @property
    def name(self) -> str: ...
    @property
    def time(self) -> Optional[float]:
        """The seconds into its animation the scene is posed at; None at rest."""
    @property
    def animation(self) -> str:
        """The animation time poses (its name, else its index); '' without animations."""
    @property
    def animation_duration(self) -> float:
        """That animation's length in seconds (its last keyframe); 0 without animations."""
    @property
    def triangles(self) -> int: ...
    @property
    def lights(self) -> list[dict[str, Any]]:
        """name, type, position, direction, color, intensity, radius, angular_diameter,
        casts_shadow."""
    @property
    def cameras(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]:
        """What the loader skipped, one line each."""

class Result:
    """One render: arrays over the renderer's own output (no copy; writes reach metrics())."""

    @property
    def image(self) -> npt.NDArray[np.uint8]:
        """(height, width, 4): the lit image, sRGB, rows top to bottom."""
    @property
    def visibility(self) -> list[npt.NDArray[np.float32]]:
        """One (height, width) array per shadow-casting light, 1 lit, NaN for background."""
    @property
    def transmittance(self) -> list[npt.NDArray[np.float32]]:
        """With the translucent layer on a scene with translucent casters: one (height, width, 3)
        array per light, the light per channel (linear RGB); its luminance is visibility."""
    @property
    def position(self) -> npt.NDArray[np.float32]:
        """(height, width, 3): world-space position, NaN for background."""
    @property
    def normal(self) -> npt.NDArray[np.float32]:
        """(height, width, 3): unit world-space normal, NaN for background."""
    @property
    def gpu_ms(self) -> dict[str, float]:
        """GPU milliseconds per pass, the median of the timed frames, and 'total', their sum
        (metrics.json's total)."""
    @property
    def gpu_ms_per_frame(self) -> dict[str, list[float]]:
        """Every timed frame's GPU milliseconds per pass, and 'total', each frame's sum."""
    @property
    def parameters(self) -> dict[str, str]:
        """Every parameter in effect, as --set would spell it."""
    @property
    def lights(self) -> list[dict[str, Any]]:
        """name, visibility_index (-1: casts no shadow), projection."""
    @property
    def name(self) -> str:
        """The row, e.g. 'pcf[box7]'."""
    @property
    def technique(self) -> str: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...

class Truth:
    """The ray-traced ground truth of a renderer's view."""

    @property
    def visibility(self) -> list[npt.NDArray[np.float32]]: ...
    @property
    def transmittance(self) -> list[npt.NDArray[np.float32]]:
        """Where the scene has translucent casters: one (height, width, 3) array per light."""
    @property
    def occluder_distance(self) -> list[npt.NDArray[np.float32]]:
        """Per light: how far the occluder is along the ray to the light's centre (inf: none)."""
    @property
    def samples(self) -> int: ...
    @property
    def rays(self) -> int: ...
    @property
    def seconds(self) -> float: ...

class Renderer:
    """A scene uploaded once to a device; renders any number of frames."""

    def __init__(
        self,
        scene: Scene,
        width: int = 1280,
        height: int = 720,
        *,
        device: int = -1,
        validation: bool = False,
        shadow_map_size: int = 2048,
        camera: str = "",
        light_radius: Optional[float] = None,
        light_angle: Optional[float] = None,
    ) -> None: ...
    def render(
        self,
        technique: str = "hard",
        params: Mapping[str, Any] = {},
        frames: int = 5,
        **keywords: Any,
    ) -> Result:
        """A technique or compare row ('pcf[box7]'); parameters as params={'pcf.size': 7} or
        pcf_size=7, checked before the device sees them (InputError). sdf audits its picture
        and raises InputError where its field cannot hold the view (sdf.refuse, docs/cli.md)."""
    def reference(
        self, samples: int = 256, embree_config: str = "", gbuffer: Optional[Result] = None
    ) -> Truth:
        """The ray-traced truth of the view (Embree), samples rays per pixel and light."""
    @property
    def device(self) -> dict[str, Any]: ...
    @property
    def device_memory_bytes(self) -> int: ...

def metrics(result: Result, truth: Truth) -> dict[str, Any]:
    """The metrics `penumbra compare` writes for a row (metrics.json)."""

def techniques() -> list[dict[str, Any]]:
    """Every technique with its parameters, defaults and ranges (penumbra techniques --json)."""
