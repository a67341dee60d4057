"""The layers of cpp/ (docs/design/ARCHITECTURE.md, "Layers"): the build declares the allowed
graph, every public header belongs to one subsystem and no #include goes against the graph.
The compile-time side (a planted back-edge fails to compile) is ctest's layers.* tests."""
import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[3]
_spec = importlib.util.spec_from_file_location("weft_layers", ROOT / "scripts" / "layers.py")
layers = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(layers)

# The picture of ARCHITECTURE.md; changing it is a design decision, made here and in the build.
EXPECTED = {
    "core": set(),
    "vk": {"core"},
    "sim": {"core"},
    "ibl": {"core"},
    "btf": {"core"},
    "hair": {"core"},
    "scene": {"core", "ibl", "btf", "hair"},
    "render": {"vk", "scene"},
    "app": {"render", "sim"},
}


def test_the_build_declares_the_allowed_graph():
    declared = layers.declared_subsystems()
    assert {name: deps for name, (deps, _) in declared.items()} == EXPECTED
    assert layers.ALLOWED == EXPECTED
    folders = {p.name for p in (ROOT / "cpp" / "src").iterdir() if p.is_dir()}
    assert folders == set(EXPECTED), "every folder of cpp/src is one subsystem"


def test_the_graph_is_acyclic_and_keeps_vulkan_out_of_the_cpu_maths():
    for name, deps in EXPECTED.items():
        assert all(name not in layers.closure(d) for d in deps), name
    for cpu in ("core", "sim", "ibl", "btf", "hair", "scene"):
        assert "vk" not in layers.closure(cpu), cpu
    assert "sim" not in layers.closure("render"), "the renderer reads DeformableMesh, not Cloth"


def test_every_public_header_belongs_to_one_subsystem():
    declared = layers.declared_subsystems()
    named = [h for _, headers in declared.values() for h in headers]
    assert len(named) == len(set(named))
    on_disk = {p.stem for p in (ROOT / "cpp" / "include" / "weft").glob("*.h")}
    assert set(named) == on_disk


def test_no_include_goes_against_the_layers():
    edges, bad, unowned = layers.scan()
    assert unowned == []
    assert bad == []
    # The scan sees the edges that exist (it would not pass by reading nothing).
    assert len(edges[("render", "vk")]) > 5 and len(edges[("scene", "core")]) > 5


def test_a_planted_back_edge_is_reported():
    owners = layers.header_owners(layers.declared_subsystems())
    camera = ROOT / "cpp" / "src" / "scene" / "Camera.cpp"
    planted = '#include "render/ShadowFit.h"\n#include <weft/Renderer.h>\n#include "../vk/Vk.h"\n'
    bad = layers.violations_of(planted, "scene", camera, owners)
    assert [b.split(": ")[1].split(" (")[0] for b in bad] == [
        "scene -> render", "scene -> render", "scene -> .."]
    allowed = '#include "core/Validate.h"\n#include <weft/Environment.h>\n#include <vector>\n'
    assert layers.violations_of(allowed, "scene", camera, owners) == []
    # The top level reads public headers and only the private headers it lists.
    module = ROOT / "cpp" / "bindings" / "module.cpp"
    assert layers.violations_of('#include "app/DemoScene.h"\n', "bindings", module, owners)
    assert not layers.violations_of('#include <weft/DemoScene.h>\n', "bindings", module, owners)
