#!/usr/bin/env python3
"""Writes the hand-made test plants of tests/data/gltf (README.md there says what each is for).

Every file is glTF 2.0 with its buffer (and image) embedded as base64 data URIs, made from plain
geometry here so that the assets carry nothing from elsewhere. Run it from any folder:

    python3 tests/data/gltf/make_plants.py

The output is deterministic; the files are small enough to keep in git.
"""

import base64
import json
import math
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent


def blade(base, direction, height, width, bend, segments=6):
    """One tapering blade: a strip rising `height` metres and leaning `bend` metres along
    `direction` (a unit xz vector) at its tip, on a quadratic curve; `width` at the base.
    Returns positions, normals, uvs (u across, v along) and triangle indices."""
    dx, dz = direction
    side = (-dz, dx)  # across the blade, horizontal
    positions, normals, uvs, indices = [], [], [], []
    for k in range(segments + 1):
        s = k / segments
        cx = base[0] + dx * bend * s * s
        cz = base[1] + dz * bend * s * s
        y = height * s
        half = 0.5 * width * (1.0 - 0.85 * s)
        # tangent along the blade and the normal across it
        t = (dx * 2.0 * bend * s, height, dz * 2.0 * bend * s)
        n = (t[1] * side[1] - t[2] * 0.0, t[2] * side[0] - t[0] * side[1], t[0] * 0.0 - t[1] * side[0])
        ln = math.sqrt(sum(c * c for c in n))
        n = tuple(c / ln for c in n)
        for u, sign in ((0.0, -1.0), (1.0, 1.0)):
            positions.append((cx + sign * half * side[0], y, cz + sign * half * side[1]))
            normals.append(n)
            uvs.append((u, 1.0 - s))
    for k in range(segments):
        a = 2 * k
        indices += [a, a + 1, a + 2, a + 1, a + 3, a + 2]
    return positions, normals, uvs, indices


def tuft(count, height, width, bend, radius, seed):
    """`count` blades around a small circle, leaning outwards with some variation."""
    positions, normals, uvs, indices = [], [], [], []
    for i in range(count):
        angle = 2.0 * math.pi * (i + 0.37 * ((seed * 7 + i * 3) % 5) / 5.0) / count
        direction = (math.cos(angle), math.sin(angle))
        base = (radius * direction[0], radius * direction[1])
        h = height * (0.85 + 0.15 * ((seed + i * 5) % 4) / 3.0)
        p, n, t, ix = blade(base, direction, h, width, bend * (0.7 + 0.3 * (i % 3) / 2.0))
        offset = len(positions)
        positions += p
        normals += n
        uvs += t
        indices += [offset + j for j in ix]
    return positions, normals, uvs, indices


def cube(size):
    """A closed cube standing on the ground, 24 vertices with face normals."""
    h = 0.5 * size
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    positions, normals, uvs, indices = [], [], [], []
    for n, u, v in faces:
        offset = len(positions)
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            positions.append(tuple(h * (n[i] + a * u[i] + b * v[i]) + (h if i == 1 else 0.0) for i in range(3)))
            normals.append(n)
            uvs.append((0.5 * (a + 1), 0.5 * (b + 1)))
        indices += [offset, offset + 1, offset + 2, offset, offset + 2, offset + 3]
    return positions, normals, uvs, indices


def png(width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) gives (r, g, b)."""
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def write(name, mesh, with_normals=True, with_uvs=False, material=None, image=None):
    positions, normals, uvs, indices = mesh
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    views = [(0, len(blob))]
    attributes = {"POSITION": 0}
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                  "min": [min(p[i] for p in positions) for i in range(3)],
                  "max": [max(p[i] for p in positions) for i in range(3)]}]
    for key, data, kind, fmt in (("NORMAL", normals if with_normals else None, "VEC3", "<3f"),
                                 ("TEXCOORD_0", uvs if with_uvs else None, "VEC2", "<2f")):
        if data is None:
            continue
        chunk = b"".join(struct.pack(fmt, *d) for d in data)
        attributes[key] = len(accessors)
        views.append((len(blob), len(chunk)))
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(data), "type": kind})
        blob += chunk
    chunk = b"".join(struct.pack("<H", i) for i in indices)
    chunk += b"\x00" * (-len(chunk) % 4)
    views.append((len(blob), 2 * len(indices)))
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
    blob += chunk
    primitive = {"attributes": attributes, "indices": len(accessors) - 1}
    doc = {"asset": {"version": "2.0", "generator": "meadow tests/data/gltf/make_plants.py"},
           "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": name, "mesh": 0}],
           "meshes": [{"name": name, "primitives": [primitive]}],
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
           "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": n} for o, n in views],
           "accessors": accessors}
    if material is not None:
        primitive["material"] = 0
        doc["materials"] = [material]
    if image is not None:
        doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}]
        doc["samplers"] = [{"magFilter": 9729, "minFilter": 9729}]
        doc["textures"] = [{"source": 0, "sampler": 0}]
    (HERE / (name + ".gltf")).write_text(json.dumps(doc, separators=(",", ":")) + "\n")


def main():
    # The example: three curved blades, 0.6 m, positions, normals and indices, no texture.
    blades = tuft(3, 0.6, 0.05, 0.18, 0.02, 1)
    write("three_blades", blades)
    # A tall, sparse reed (1.8 m, five narrow blades), simulated stiff by its scene.
    write("reed", tuft(5, 1.8, 0.03, 0.25, 0.03, 2))
    # A small, dense tuft (0.15 m, twelve blades), soft.
    write("low_tuft", tuft(12, 0.15, 0.02, 0.06, 0.015, 3))
    # A textured plant: four blades whose base-colour texture is orange at the tips and blue at
    # the base (v = 0 is the tip), times a factor that keeps the blue but halves red nowhere.
    texture = png(8, 8, lambda x, y: (255, 140, 0) if y < 4 else (20, 60, 255))
    write("painted", tuft(4, 0.5, 0.08, 0.12, 0.02, 4), with_uvs=True,
          material={"name": "painted", "pbrMetallicRoughness": {
              "baseColorTexture": {"index": 0}, "baseColorFactor": [1.0, 1.0, 1.0, 1.0],
              "metallicFactor": 0.0}}, image=texture)
    # Not a plant: a closed 1 m cube with a red base colour (like the Khronos sample Box).
    write("red_cube", cube(1.0), material={"name": "red", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.0, 0.0, 1.0], "metallicFactor": 0.0}})


if __name__ == "__main__":
    main()
