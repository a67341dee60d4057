"""Seeds of the libFuzzer targets (tests/fuzz/cpp) that the atheris targets' corpora do not
provide: glTF files (corpus/gltf), an OBJ with its material library in the obj target's
"#mtl" form (corpus/obj/materials.obj) and inputs of the C++ btftree target
(corpus/btftree-cpp). Deterministic; ``python tests/fuzz/libfuzzer_seeds.py`` rewrites them."""

from __future__ import annotations

import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")


def _png_rgba(width: int, height: int) -> bytes:
    """A small RGBA PNG (written here so the seeds need nothing but the standard library)."""
    rows = b"".join(b"\0" + bytes((37 * (x + y) + c * 60) % 256 for x in range(width)
                                  for c in range(4)) for y in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6,
                                                             0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def _quad_buffer() -> bytes:
    """Positions, normals, UVs (floats) and uint16 indices of a unit quad: offsets 0, 48, 96,
    128 (the same layout as the b.bin the gltf target writes)."""
    floats = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0] + [0, 0, 1] * 4 + [0, 0, 1, 0, 1, 1, 0, 1]
    return struct.pack("<32f", *floats) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)


def _gltf(buffer_uri, buffer_length: int, image_uri: str) -> dict:
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
             {"buffer": 0, "byteOffset": 48, "byteLength": 48},
             {"buffer": 0, "byteOffset": 96, "byteLength": 32},
             {"buffer": 0, "byteOffset": 128, "byteLength": 12}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                  "min": [0, 0, 0], "max": [1, 1, 0]},
                 {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                 {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                 {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    buffer = {"byteLength": buffer_length}
    if buffer_uri is not None:
        buffer["uri"] = buffer_uri
    return {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1],
                   "children": [1, 2]},
                  {"mesh": 0, "translation": [0, 1, 0], "rotation": [0, 0.7071068, 0, 0.7071068],
                   "scale": [2, 2, 2]},
                  {"mesh": 1, "scale": [-1, 1, 1]}],
        "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1,
                                                                   "TEXCOORD_0": 2},
                                                    "indices": 3, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 0}, "mode": 5, "material": 1}]}],
        "materials": [{"pbrMetallicRoughness": {
                           "baseColorFactor": [0.8, 0.6, 0.4, 1],
                           "baseColorTexture": {"index": 0, "extensions": {
                               "KHR_texture_transform": {"offset": [0.1, 0], "scale": [2, 2],
                                                         "rotation": 0.3}}},
                           "metallicFactor": 0.3, "roughnessFactor": 0.6},
                       "normalTexture": {"index": 1, "scale": 0.5},
                       "alphaMode": "MASK", "alphaCutoff": 0.4, "doubleSided": True},
                      {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.05}}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 33648}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(_png_rgba(2, 2)).decode()},
                   {"uri": image_uri}],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    }


def _glb(doc: dict, binary: bytes) -> bytes:
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = (struct.pack("<I4s", len(text), b"JSON") + text +
              struct.pack("<I4s", len(binary), b"BIN\0") + binary)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def write_gltf_seeds() -> None:
    out = os.path.join(CORPUS, "gltf")
    os.makedirs(out, exist_ok=True)
    quad = _quad_buffer()
    embedded = _gltf("data:application/octet-stream;base64," + base64.b64encode(quad).decode(),
                     len(quad), "t.png")
    external = _gltf("b.bin", 1024, "t.png")  # the whole b.bin of the gltf target
    binary = _gltf(None, len(quad), "t.png")
    with open(os.path.join(out, "embedded.gltf"), "w") as f:
        json.dump(embedded, f, indent=1)
    with open(os.path.join(out, "external.gltf"), "w") as f:
        json.dump(external, f, indent=1)
    with open(os.path.join(out, "quad.glb"), "wb") as f:
        f.write(_glb(binary, quad))


def write_obj_seed() -> None:
    text = ("mtllib m.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
            "vt 0 1\nvn 0 0 1\ng front\nusemtl cloth\nf 1/1/1 2/2/1 3/3/1\nusemtl shiny\n"
            "f -4/-4 -2/-2 -1/-1\ns 1\nf 1//1 3//1 4//1\n"
            "#mtl\n"
            "newmtl cloth\nKd 0.8 0.6 0.4\nKs 0.1 0.1 0.1\nNs 20\nmap_Kd -s 1 1 1 t.png\n"
            "newmtl shiny\nKd 0.2 0.2 0.2\nKs 0.9 0.9 0.9\nNs 400\nd 1\nillum 2\n")
    with open(os.path.join(CORPUS, "obj", "materials.obj"), "w") as f:
        f.write(text)


def write_btftree_seeds() -> None:
    """FuzzedDataProvider reads bytes from the front and integers from the back (one byte per
    value below 256): b"\\x01" at the end = 'start from a complete set', then the set's kind,
    the count of extra entries (0), then zip (1) or folder (0) and deflate."""
    out = os.path.join(CORPUS, "btftree-cpp")
    os.makedirs(out, exist_ok=True)
    for kind, ext in enumerate(("jpg", "png", "png16", "exr")):
        # read back to front: complete set, kind, 0 extras, as_zip, deflate
        with open(os.path.join(out, f"set_{ext}_folder"), "wb") as f:
            f.write(bytes([0, 0, 0, kind, 1]))
        with open(os.path.join(out, f"set_{ext}_zip"), "wb") as f:
            f.write(bytes([1, 1, 0, kind, 1]))


if __name__ == "__main__":
    write_gltf_seeds()
    write_obj_seed()
    write_btftree_seeds()
