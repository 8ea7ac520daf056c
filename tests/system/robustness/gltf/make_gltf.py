#!/usr/bin/env python3
"""Writes the glTF files of the robustness corpus (tests/system/robustness/corpus.cmake) into this folder.

Each file is the valid test plant of tests/data/gltf/plant.gltf (two crossed blades, 10 vertices,
6 triangles) with one thing broken. Run it again after changing a case; the files are committed so
that the corpus is plain data to read.
"""
import base64
import copy
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

POSITIONS = [(-0.02, 0.0, 0.0), (0.02, 0.0, 0.0), (-0.015, 0.4, 0.0), (0.015, 0.4, 0.0), (0.0, 0.8, 0.05),
             (0.0, 0.0, -0.02), (0.0, 0.0, 0.02), (0.0, 0.4, -0.015), (0.0, 0.4, 0.015), (0.0, 0.8, 0.05)]
NORMALS = [(0.0, 0.0, 1.0)] * 10
INDICES = [0, 1, 2, 1, 3, 2, 2, 3, 4, 5, 6, 7, 6, 8, 7, 7, 8, 9]


def buffer_bytes(indices=INDICES, normals=True):
    data = b"".join(struct.pack("<3f", *p) for p in POSITIONS)
    if normals:
        data += b"".join(struct.pack("<3f", *n) for n in NORMALS)
    data += b"".join(struct.pack("<H", i) for i in indices)
    while len(data) % 4:
        data += b"\0"
    return data


def plant(indices=INDICES):
    """The valid plant: POSITION, NORMAL and indices in one embedded buffer."""
    data = buffer_bytes(indices)
    return {
        "asset": {"version": "2.0", "generator": "meadow robustness corpus (make_gltf.py)"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "plant", "mesh": 0}],
        "meshes": [{"name": "blades", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 120},
                        {"buffer": 0, "byteOffset": 120, "byteLength": 120},
                        {"buffer": 0, "byteOffset": 240, "byteLength": 2 * len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 10, "type": "VEC3",
                       "min": [-0.02, 0.0, -0.02], "max": [0.02, 0.8, 0.05]},
                      {"bufferView": 1, "componentType": 5126, "count": 10, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
    }


def write(name, doc):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")


def glb(doc, binary):
    """A .glb of `doc` whose buffer 0 is the BIN chunk."""
    doc = copy.deepcopy(doc)
    doc["buffers"] = [{"byteLength": len(binary)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    while len(text) % 4:
        text += b" "
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def main():
    base = plant()
    write("valid_plant.gltf", base)  # not a bad input: the control case, imported by the unit tests

    doc = copy.deepcopy(base)
    doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7
    write("accessor_missing.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][0]["count"] = 1000
    write("accessor_past_buffer.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][1]["byteOffset"] = 116
    write("accessor_offset_past_view.gltf", doc)

    # 2^63 + 1 indices of 2 bytes, 2^63 + 1 positions of 12: their byte ranges overflow 64 bits (to
    # 2 and 12 bytes), which a naive bounds check lets through.
    doc = copy.deepcopy(base)
    doc["accessors"][2]["count"] = 2**63 + 1
    write("huge_index_count.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][0]["count"] = 2**63 + 1
    write("huge_position_count.gltf", doc)

    # 4 billion indices: far past the buffer, without overflow.
    doc = copy.deepcopy(base)
    doc["accessors"][2]["count"] = 4000000002
    write("billion_indices.gltf", doc)

    doc = plant(INDICES[:-1] + [200])
    write("index_out_of_range.gltf", doc)

    doc = plant(INDICES[:-2])
    write("index_count_not_triangles.gltf", doc)

    for mode, name in ((1, "lines"), (5, "triangle_strip"), (6, "triangle_fan")):
        doc = copy.deepcopy(base)
        doc["meshes"][0]["primitives"][0]["mode"] = mode
        write("mode_%s.gltf" % name, doc)

    doc = copy.deepcopy(base)
    doc["accessors"][1]["count"] = 5
    write("normal_count_mismatch.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][0]["componentType"] = 5125
    write("position_component_uint.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][0]["type"] = "VEC2"
    write("position_vec2.gltf", doc)

    doc = copy.deepcopy(base)
    doc["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                     "values": {"bufferView": 0}}
    write("sparse_accessor.gltf", doc)

    doc = copy.deepcopy(base)
    doc["nodes"] = [{"name": "a", "mesh": 0, "children": [1]}, {"name": "b", "children": [0]}]
    write("node_cycle.gltf", doc)

    # Each node names the next one twice: 2^40 paths through 41 nodes if nothing stops the walk.
    doc = copy.deepcopy(base)
    doc["nodes"] = [{"name": "n%d" % i, "children": [i + 1, i + 1]} for i in range(40)] + [{"name": "leaf", "mesh": 0}]
    write("node_shared.gltf", doc)

    # A chain of 5000 nodes: deeper than any real asset, deep enough to exhaust a naive recursion's stack
    # under the sanitizers.
    doc = copy.deepcopy(base)
    doc["nodes"] = [{"children": [i + 1]} for i in range(5000)] + [{"name": "leaf", "mesh": 0}]
    write("node_chain_5000.gltf", doc)

    doc = copy.deepcopy(base)
    doc["nodes"][0]["children"] = [3]
    write("node_child_missing.gltf", doc)

    doc = copy.deepcopy(base)
    doc["nodes"][0]["mesh"] = 4
    write("mesh_missing.gltf", doc)

    doc = copy.deepcopy(base)
    doc["nodes"][0]["matrix"] = [1e39, 0, 0, 0, 0, 1e39, 0, 0, 0, 0, 1e39, 0, 0, 0, 0, 1]
    write("matrix_overflow.gltf", doc)

    doc = copy.deepcopy(base)
    doc["nodes"][0]["scale"] = [0.0, 0.0, 0.0]
    write("zero_scale.gltf", doc)

    # A base-colour texture whose image is not an image (TEXCOORD_0 read from the positions).
    doc = copy.deepcopy(base)
    doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3
    doc["meshes"][0]["primitives"][0]["material"] = 0
    doc["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 10, "type": "VEC2"})
    doc["materials"] = [{"name": "leaf", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["textures"] = [{"source": 0}]
    doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(b"not an image at all").decode()}]
    write("texture_not_an_image.gltf", doc)

    doc = copy.deepcopy(base)
    doc["buffers"][0]["uri"] = "missing_buffer.bin"
    write("buffer_file_missing.gltf", doc)

    # A buffer named by a folder: on Linux a folder opens, and its end lies at 2^63 - 1 (found by
    # the fuzzer; tinygltf's own reader tried to allocate that much).
    doc = copy.deepcopy(base)
    doc["buffers"][0]["uri"] = "."
    write("buffer_uri_folder.gltf", doc)

    doc = copy.deepcopy(base)
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,!!not base64!!"
    write("buffer_bad_base64.gltf", doc)

    doc = copy.deepcopy(base)
    doc["buffers"][0]["byteLength"] = 100000
    write("buffer_length_lie.gltf", doc)

    doc = copy.deepcopy(base)
    doc["bufferViews"][0]["byteLength"] = 1000
    write("buffer_view_past_buffer.gltf", doc)

    doc = copy.deepcopy(base)
    doc["scenes"] = []
    doc.pop("scene")
    write("no_scene.gltf", doc)

    doc = copy.deepcopy(base)
    doc["scene"] = 3
    write("default_scene_missing.gltf", doc)

    with open(os.path.join(HERE, "empty.gltf"), "w"):
        pass
    with open(os.path.join(HERE, "not_json.gltf"), "wb") as f:
        f.write(bytes(range(256)))

    text = json.dumps(base, separators=(",", ":"))
    with open(os.path.join(HERE, "truncated.gltf"), "w") as f:
        f.write(text[: len(text) // 2])

    binary = buffer_bytes()
    whole = glb(base, binary)
    with open(os.path.join(HERE, "valid_plant.glb"), "wb") as f:
        f.write(whole)
    with open(os.path.join(HERE, "truncated.glb"), "wb") as f:
        f.write(whole[: len(whole) - 100])
    with open(os.path.join(HERE, "truncated_header.glb"), "wb") as f:
        f.write(whole[:10])
    # The header and the JSON chunk claim more bytes than the file holds.
    lie = bytearray(whole)
    struct.pack_into("<I", lie, 8, 1 << 30)
    struct.pack_into("<I", lie, 12, 1 << 30)
    with open(os.path.join(HERE, "chunk_length_lie.glb"), "wb") as f:
        f.write(bytes(lie))
    bad = bytearray(whole)
    bad[0:4] = b"gLTF"
    with open(os.path.join(HERE, "bad_magic.glb"), "wb") as f:
        f.write(bytes(bad))


if __name__ == "__main__":
    main()
