"""Shader hot reload (issue 5): a renderer watching a copy of glsl/ picks up an edited shader
at the next frame; a broken edit is reported with file and line and the previous pipeline
keeps rendering."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Iterator

import numpy as np
import pytest
import weft
from weft import reference as ref

GLSL = Path(__file__).resolve().parents[3] / "glsl"

pytestmark = pytest.mark.skipif(not weft.shader_hot_reload_available(),
                                reason="built without libshaderc")


@pytest.fixture
def shader_dir(tmp_path: Path) -> Iterator[Path]:
    copy = tmp_path / "glsl"
    shutil.copytree(GLSL, copy)
    weft.clear_shader_errors()
    weft.set_shader_directory(str(copy))
    yield copy
    weft.set_shader_directory("")
    weft.clear_shader_errors()


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, f"{old!r} not in {path}"
    path.write_text(text.replace(old, new))


def test_edited_shader_changes_the_next_frame(shader_dir: Path, make_renderer) -> None:
    scene, camera = weft.default_scene()
    r = make_renderer(64, 48)
    before = r.render_linear(scene, camera)
    colour_before = r.render(scene, camera)
    # the output pass now writes half the radiance
    edit(shader_dir / "render" / "output.frag", "vec4(clamp(c, 0.0, 1.0), 1.0)",
         "vec4(clamp(0.5 * c, 0.0, 1.0), 1.0)")
    after = r.render(scene, camera)
    expected = ref.encode_u8(np.clip(0.5 * before[..., :3], 0.0, 1.0))
    assert np.abs(after[..., :3].astype(int) - expected.astype(int)).max() <= 1
    assert not np.array_equal(after, colour_before)
    assert weft.shader_errors() == []


def test_broken_shader_keeps_the_previous_pipeline(shader_dir: Path, make_renderer) -> None:
    scene, camera = weft.default_scene()
    r = make_renderer(64, 48)
    good = r.render(scene, camera)
    edit(shader_dir / "render" / "output.frag", "outColor = vec4", "outColr = vec4")
    kept = r.render(scene, camera)
    np.testing.assert_array_equal(kept, good)
    errors = weft.shader_errors()
    assert len(errors) == 1 and "render/output.frag:" in errors[0] and "error" in errors[0]
    # fixing it takes effect again; an edit in an included file recompiles its users
    edit(shader_dir / "render" / "output.frag", "outColr = vec4", "outColor = vec4")
    edit(shader_dir / "common" / "shading.glsl", "s.T = ins.baseColor.rgb * base.rgb;",
         "s.T = vec3(0.0) * ins.baseColor.rgb * base.rgb;")
    dark = r.render_debug(scene, camera)
    covered = dark["mask"]
    assert np.all(dark["albedo"][covered] == 0.0)


def test_bad_directory_is_rejected() -> None:
    with pytest.raises(ValueError, match="does not exist"):
        weft.set_shader_directory("/no/such/dir")
    assert weft.shader_directory() == ""


def test_shader_needing_a_new_descriptor_is_refused(shader_dir: Path, make_renderer) -> None:
    """A reloaded shader may not read a binding its pipeline layout lacks (that would be
    undefined behaviour): it is reported and the built-in pipeline keeps rendering."""
    scene, camera = weft.default_scene()
    r = make_renderer(48, 36)
    good = r.render(scene, camera)
    edit(shader_dir / "render" / "output.frag",
         "layout(set = 0, binding = 0) uniform sampler2D hdr;",
         "layout(set = 0, binding = 0) uniform sampler2D hdr;\n"
         "layout(set = 0, binding = 7) uniform sampler2D extra;")
    edit(shader_dir / "render" / "output.frag",
         "texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * push.params.x",
         "(texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb + texture(extra, vec2(0.5)).rgb) * "
         "push.params.x")
    np.testing.assert_array_equal(r.render(scene, camera), good)
    errors = weft.shader_errors()
    assert len(errors) == 1 and "binding 7" in errors[0], errors
