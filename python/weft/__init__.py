"""weft: real-time rendering of soft, textured materials with Vulkan, driven from Python.

The renderer and scene types live in the compiled module ``weft._core`` and are re-exported
here: build a :class:`Scene` from :class:`Mesh` instances with :class:`Material` s and
:class:`DirectionalLight` s, then ``Renderer(w, h).render(scene, camera)`` returns an sRGB
``uint8`` (H, W, 4) NumPy array (``render_linear`` and ``render_debug`` give float outputs).

Errors raise :class:`Error` (a ``RuntimeError``); bad input raises :class:`InvalidArgument`
(also a ``ValueError``; arguments that do not fit a signature raise its subclass
:class:`ArgumentError`, naming the bad keyword or values) and file problems :class:`IoError` (also
an ``OSError``).
``weft.reference`` holds NumPy reference implementations, ``python -m weft`` is the command
line (demo, devices, render) and ``python -m weft.bench`` runs the benchmarks.
"""

from weft import _arguments, _core
from weft._core import InvalidArgument as _InvalidArgument


class ArgumentError(_InvalidArgument, TypeError):
    """Arguments that do not fit a compiled function's parameters (a mistyped keyword, a negative
    count, a wrong type): a :class:`InvalidArgument` that names the function, the bad keyword or
    values and the signature that applies (and, for older code, a ``TypeError``)."""


_arguments.install(_core, ArgumentError)

from weft._core import (  # noqa: E402 (after the compiled callables are wrapped)
    BtfSamples,
    Camera,
    Cloth,
    Collider,
    DirectionalLight,
    Error,
    HairMaterial,
    HairStrands,
    InvalidArgument,
    IoError,
    Material,
    Mesh,
    MeshPart,
    PointLight,
    Renderer,
    Scene,
    SpotLight,
    Texture,
    Wind,
    __version__,
    clear_shader_errors,
    clear_validation_messages,
    default_scene,
    demo_scene,
    device_memory,
    devices,
    generate_fur,
    generate_hair,
    hair_from_bytes,
    hair_shade_eval,
    load_demo_script,
    load_exr,
    load_gltf,
    load_hair,
    load_hdr,
    load_image_float,
    load_obj,
    load_obj_parts,
    load_png,
    poll_shader_changes,
    run_demo,
    save_exr,
    save_hair,
    save_hdr,
    save_png,
    set_shader_directory,
    shader_directory,
    shader_errors,
    shader_hot_reload_available,
    validation_enabled,
    validation_messages,
)
from weft.fur import add_fur  # noqa: E402 (re-exported with the wrapped callables above)

__all__ = [
    "ArgumentError",
    "BtfMaterial",
    "BtfSamples",
    "add_fur",
    "Camera",
    "Cloth",
    "Collider",
    "DirectionalLight",
    "Error",
    "HairMaterial",
    "HairStrands",
    "InvalidArgument",
    "IoError",
    "Material",
    "Mesh",
    "MeshPart",
    "PointLight",
    "Renderer",
    "Scene",
    "SpotLight",
    "Texture",
    "Wind",
    "__version__",
    "clear_validation_messages",
    "default_scene",
    "demo_scene",
    "devices",
    "generate_fur",
    "generate_hair",
    "hair_from_bytes",
    "hair_shade_eval",
    "load_exr",
    "load_hair",
    "load_hdr",
    "load_image_float",
    "load_gltf",
    "load_obj",
    "load_obj_parts",
    "device_memory",
    "load_demo_script",
    "load_png",
    "run_demo",
    "save_exr",
    "save_hair",
    "save_hdr",
    "save_png",
    "shader_hot_reload_available",
    "shader_errors",
    "shader_directory",
    "set_shader_directory",
    "poll_shader_changes",
    "clear_shader_errors",
    "validation_enabled",
    "validation_messages",
]

from weft.btf.material import BtfMaterial  # noqa: E402  (needs weft._core first)
