"""Ready-made scenes for scripts and ``python -m weft render``.

- :func:`cloth_scene`: a cloth dropped onto a sphere standing on a ground plane, simulated until
  it drapes (SPEC §2), lit by a sun or, through :func:`light_with_environment`, by a captured
  environment with shadows from the dome of shadow lights (SPEC §4.4, §4.5);
- :func:`light_with_environment`: lights any scene (also ``weft.default_scene()``) with an
  environment instead of its lights.

A script that lights the cloth from a mirror-ball photo or an HDR file::

    import weft, weft.ibl, weft.scenes
    scene, camera, cloth = weft.scenes.cloth_scene(steps=180)
    cube = weft.ibl.load_environment_cube("ball.png", 64, source="sphere", wrap=0.9)
    weft.scenes.light_with_environment(scene, cube, dome_lights=16)
    weft.save_png("out/cloth.png", weft.Renderer(800, 600).render(scene, camera))
"""

from __future__ import annotations

from typing import Optional, Sequence, Tuple

import numpy as np

import weft
import weft.ibl
from weft._core import InvalidArgument

#: The sphere the cloth falls on: centre and radius (metres, y up, ground at y = 0).
SPHERE_CENTRE = (0.0, 0.5, 0.0)
SPHERE_RADIUS = 0.5
#: Side of the square cloth (metres) and the height it starts from (flat, above the sphere).
CLOTH_SIZE = 1.6
CLOTH_HEIGHT = 1.15
#: Half the side of the square ground plane.
GROUND_HALF = 5.0
#: Simulation steps (60 Hz) after which the default cloth has draped and nearly stopped.
DEFAULT_STEPS = 180
#: Dome sizes the renderer accepts: 0 (none) or a multiple of 8 up to 64 (SPEC §4.5).
DOME_SIZES = tuple(range(0, 65, 8))


def cloth_camera() -> "weft.Camera":
    """The cloth scene's camera: slightly off the +Z axis, above, looking at the sphere's foot
    so that both the draped cloth and open ground around it are in view."""
    return weft.Camera(position=(0.7, 1.55, 2.5), target=(0.0, 0.4, 0.0), fov_y=0.75)


def _checked_int(value: object, name: str, low: int, high: Optional[int] = None) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise InvalidArgument(f"{name} must be an integer, got {value!r}")
    if value < low or (high is not None and value > high):
        bound = f">= {low}" if high is None else f"in [{low}, {high}]"
        raise InvalidArgument(f"{name} must be {bound}, got {value}")
    return int(value)


def cloth_scene(resolution: int = 32, steps: int = DEFAULT_STEPS,
                cloth_colour: Sequence[float] = (0.75, 0.62, 0.35),
                sphere_colour: Sequence[float] = (0.7, 0.18, 0.14),
                ground_colour: Sequence[float] = (0.55, 0.55, 0.52),
                threads: int = 0) -> Tuple["weft.Scene", "weft.Camera", "weft.Cloth"]:
    """A ground plane, a sphere on it and a square cloth (``resolution`` x ``resolution``
    particles, :data:`CLOTH_SIZE` metres) dropped flat from above the sphere, simulated for
    ``steps`` fixed 1/60 s steps (0: still flat in the air) so that it drapes over the sphere
    and its corners hang towards the ground. The cloth collides with the sphere (with friction,
    so it stays on) and the ground; its state is what the returned scene draws.

    Lighting: a sun with shadow maps and a little ambient light, so the scene renders as it is;
    :func:`light_with_environment` replaces it with an environment and its dome. Returns
    ``(scene, camera, cloth)``; the scene's instance ids are 0 ground, 1 sphere, 2 cloth. Bad
    sizes, step counts or colours raise weft.InvalidArgument."""
    resolution = _checked_int(resolution, "resolution", 4, 256)
    steps = _checked_int(steps, "steps", 0)
    colours = []
    for name, c in (("cloth_colour", cloth_colour), ("sphere_colour", sphere_colour),
                    ("ground_colour", ground_colour)):
        a = np.asarray(c, np.float64)
        if a.shape != (3,) or not np.all(np.isfinite(a)) or np.any(a < 0.0):
            raise InvalidArgument(f"{name} must be three finite values >= 0, got {c!r}")
        colours.append(tuple(float(v) for v in a))
    cloth_c, sphere_c, ground_c = colours

    scene = weft.Scene()
    ground = weft.Material(kd=ground_c, ks=(0.04,) * 3, shininess=12.0)
    # the ground receives shadows but casts none, so the shadow maps (sun and dome) are fitted
    # to the sphere and the cloth only (full resolution where the shadows are)
    scene.add_mesh(weft.Mesh.plane(2 * GROUND_HALF, 2 * GROUND_HALF, 8, 8), ground,
                   cast_shadows=False)
    sphere = weft.Material(kd=sphere_c, ks=(0.35,) * 3, shininess=60.0,
                           reflectivity=(0.04,) * 3)
    m = np.eye(4, dtype=np.float32)
    m[:3, 3] = SPHERE_CENTRE
    scene.add_mesh(weft.Mesh.uv_sphere(SPHERE_RADIUS, 48, 24), sphere, transform=m)

    half = 0.5 * CLOTH_SIZE
    cloth = weft.Cloth(nx=resolution, ny=resolution, size=(CLOTH_SIZE, CLOTH_SIZE),
                       origin=(-half, CLOTH_HEIGHT, -half), axis_u=(1, 0, 0), axis_v=(0, 0, 1),
                       iterations=4, substeps=2, damping=0.99, thickness=0.01, threads=threads)
    # the sphere collider is a little larger than the drawn sphere so the cloth rests on it
    # instead of cutting into its facets
    cloth.add_collider(weft.Collider.sphere(SPHERE_CENTRE, SPHERE_RADIUS * 1.02, friction=0.6))
    cloth.add_collider(weft.Collider.plane((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), friction=0.8))
    for _ in range(steps):
        cloth.step(1.0 / 60.0)
    scene.add_cloth(cloth, weft.Material(kd=cloth_c, ks=(0.05,) * 3, shininess=8.0))

    scene.add_light(weft.DirectionalLight(direction=(-0.4, -1.0, -0.3), color=(1.0, 0.96, 0.9),
                                          intensity=0.9))
    scene.ambient = (0.15, 0.17, 0.2)
    scene.background = (0.4, 0.55, 0.78)
    return scene, cloth_camera(), cloth


def light_with_environment(scene: "weft.Scene", environment, dome_lights: int = 16,
                           dome_map_size: int = 256, intensity: float = 1.0,
                           background: bool = True, dome_blur: float = 4.0,
                           sun_lights: int = 0) -> "weft.ibl.Environment":
    """Lights ``scene`` with ``environment`` (a weft.ibl.Environment or a world-space radiance
    weft.ibl.CubeMap) instead of its own lights: every instance's material gets the
    environment's diffuse light (``environment_diffuse = 1``; SH9 irradiance) and keeps its
    ``reflectivity`` (GGX reflections), the scene's lights are switched off (intensity 0, no
    shadow maps) and its constant ambient set to 0, and ``dome_lights`` (0, or a multiple of 8
    up to 64) shadow lights of the environment's dome subtract the light the scene occludes
    (SPEC eq. 2.23: shadows from the dome), blurred over ``dome_blur`` pixels (SPEC §4.5; 0: per
    pixel). With ``sun_lights`` > 0 up to that many bright lights are extracted
    (``weft.ibl.split_lights``: threshold + components) and added as directional lights with
    sharp shadow maps alongside the dome, which then lights with the rest of the sky: a sun
    that SH9 cannot follow is exact that way. With ``background`` the environment is drawn
    behind the scene (without the suns taken out as lights); the clear colour, left where
    nothing is drawn (e.g. render_debug's background), becomes its mean radiance over the upper
    hemisphere. Returns the Environment (call its ``set_radiance`` to change the lighting, e.g.
    from a video)."""
    if dome_lights not in DOME_SIZES:
        raise InvalidArgument(f"dome_lights must be 0 or a multiple of 8 up to 64, got "
                              f"{dome_lights!r}")
    if not (np.isfinite(intensity) and intensity >= 0.0):
        raise InvalidArgument(f"intensity must be finite and >= 0, got {intensity}")
    sun_lights = _checked_int(sun_lights, "sun_lights", 0, 16)
    env = environment
    if isinstance(env, weft.ibl.CubeMap):
        env = weft.ibl.Environment(env)
    if not isinstance(env, weft.ibl.Environment):
        raise InvalidArgument("environment must be a weft.ibl.Environment or a weft.ibl.CubeMap, "
                              f"got {type(environment).__name__}")
    suns = []
    if sun_lights:
        suns, sky = weft.ibl.split_lights(env.radiance, max_lights=sun_lights)
        if suns:
            env = weft.ibl.Environment(sky)
    scene.set_environment(env, intensity=float(intensity), dome_lights=int(dome_lights),
                          dome_map_size=int(dome_map_size), dome_refresh=0,
                          dome_blur=float(dome_blur), background=bool(background))
    for i in range(scene.instance_count):
        material = scene.material(i)
        material.environment_diffuse = 1.0
        scene.set_material(i, material)
    for i, light in enumerate(scene.lights):
        light.intensity = 0.0
        light.cast_shadows = False
        scene.set_light(i, light)
    scene.ambient = (0.0, 0.0, 0.0)
    for sun in suns:
        # colour is the light's integrated radiance: the irradiance E it brings at normal
        # incidence; weft's Blinn-Phong diffuse is n.l L K_D T against K_D T E / pi for the
        # environment, so L = E / pi
        colour = np.asarray(sun.colour, np.float64) * float(intensity) / np.pi
        peak = float(colour.max())
        if peak <= 0.0:
            continue
        # the disc it was taken from softens its shadow: solid angle 2 pi (1 - cos a)
        radius = float(np.arccos(np.clip(1.0 - float(sun.solid_angle) / (2.0 * np.pi), -1.0, 1.0)))
        scene.add_light(weft.DirectionalLight(direction=tuple(-np.asarray(sun.direction)),
                                              color=tuple(colour / peak), intensity=peak,
                                              cast_shadows=True, angular_radius=min(radius, 0.5)))
    if background:
        faces = np.asarray(env.radiance.faces, np.float64)
        dirs = weft.ibl.cube_texel_directions(faces.shape[1]).reshape(-1, 3)
        w = np.broadcast_to(weft.ibl.cube_texel_solid_angles(faces.shape[1]),
                            faces.shape[:3]).reshape(-1)  # the same (S, S) on every face
        up = dirs[:, 1] > 0.0
        mean = (faces.reshape(-1, 3)[up] * w[up, None]).sum(axis=0) / w[up].sum()
        scene.background = tuple(float(v) for v in np.clip(mean * intensity, 0.0, None))
    return env


def composite_over(scene: "weft.Scene", image, phantoms: Sequence[int] = (0,)) -> None:
    """AR compositing (SPEC §4.5): ``image`` (a camera frame: uint8 sRGB (H, W, 3) or (H, W, 4),
    or a weft.Texture) is drawn behind everything, stretched over the output, and the instances
    ``phantoms`` (default: the ground of :func:`cloth_scene` and ``weft.default_scene``) become
    phantoms -- stand-ins for real surfaces that hide what lies behind them and show the image
    darkened by the shadows they receive (lit / unshadowed diffuse light)."""
    if isinstance(image, weft.Texture):
        texture = image
    else:
        a = np.asarray(image)
        if a.dtype != np.uint8 or a.ndim != 3 or a.shape[2] not in (3, 4):
            raise InvalidArgument("background image must be uint8 sRGB (H, W, 3) or (H, W, 4), "
                                  f"got {a.dtype} {a.shape}")
        if a.shape[2] == 3:
            a = np.concatenate([a, np.full(a.shape[:2] + (1,), 255, np.uint8)], axis=2)
        texture = weft.Texture(np.ascontiguousarray(a))
    ids = [int(i) for i in phantoms]
    for i in ids:
        if not 0 <= i < scene.instance_count:
            raise InvalidArgument(f"phantom instance {i} does not exist "
                                  f"({scene.instance_count} instances)")
    scene.background_image = texture
    for i in ids:
        material = scene.material(i)
        material.phantom = True
        scene.set_material(i, material)

