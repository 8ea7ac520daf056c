#!/usr/bin/env python3
"""Bad library files for the robustness corpus, made from a good one.

    mutate_library.py GOOD.mlib OUT_DIR CASE...     writes OUT_DIR/CASE.mlib for each CASE
    mutate_library.py --list                         prints the cases

The container (precompute/library/library_file.h), little-endian:
    header  "MEADOWLB", u32 formatVersion, u32 sectionCount, u64 inputHash, u64 tableChecksum
    table   sectionCount x {u32 tag, u32 reserved, u64 offset, u64 size, u64 checksum}
    payload sections, each on an 8-byte boundary; checksums are FNV-1a 64.
Cases that lie inside the container recompute every checksum, so that the loader's checks of the
sections' contents are reached instead of the checksum's.
"""
import struct
import sys

HEADER = 32
ENTRY = 32


_checksums = {}


def fnv1a64(data):
    data = bytes(data)
    if data in _checksums:  # sections repeat across cases; hashing megabytes in Python is slow
        return _checksums[data]
    h = 0xCBF29CE484222325
    for b in data:
        h ^= b
        h = (h * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    _checksums[data] = h
    return h


def parse(blob):
    magic, version, count, input_hash, _ = struct.unpack_from("<8sIIQQ", blob, 0)
    assert magic == b"MEADOWLB", "not a meadow library"
    sections = []
    for i in range(count):
        tag, _, offset, size, _ = struct.unpack_from("<4sIQQQ", blob, HEADER + i * ENTRY)
        sections.append([tag.decode(), bytearray(blob[offset:offset + size])])
    return version, input_hash, sections


def build(version, input_hash, sections):
    """A well-formed container (every checksum right) holding `sections` in order."""
    table, payload = b"", b""
    offset = HEADER + ENTRY * len(sections)
    for tag, data in sections:
        pad = (-offset) % 8
        payload += b"\0" * pad
        offset += pad
        table += struct.pack("<4sIQQQ", tag.encode(), 0, offset, len(data), fnv1a64(data))
        payload += bytes(data)
        offset += len(data)
    header = struct.pack("<8sIIQQ", b"MEADOWLB", version, len(sections), input_hash, fnv1a64(table))
    return bytearray(header + table + payload)


def entry(blob, tag):
    count = struct.unpack_from("<I", blob, 12)[0]
    for i in range(count):
        at = HEADER + i * ENTRY
        if blob[at:at + 4] == tag.encode():
            return at
    raise KeyError(tag)


def fix_table_checksum(blob):
    count = struct.unpack_from("<I", blob, 12)[0]
    struct.pack_into("<Q", blob, 24, fnv1a64(bytes(blob[HEADER:HEADER + count * ENTRY])))
    return blob


def section(sections, tag):
    for s in sections:
        if s[0] == tag:
            return s[1]
    raise KeyError(tag)


def rebuilt(good, change):
    """The good library decoded, changed by change(sections), and written whole again."""
    version, input_hash, sections = parse(good)
    change(sections)
    return build(version, input_hash, sections)


def set_u32(data, at, value):
    struct.pack_into("<I", data, at, value)


def set_f32(data, at, value):
    struct.pack_into("<f", data, at, value)


def flip(blob, at):
    blob = bytearray(blob)
    blob[at] ^= 0x10
    return blob


def clump_mesh_index_at(clmp):
    """Offset of the first triangle index in CLMP: count, name, plants, vertex floats, indices."""
    at = 4
    name_length = struct.unpack_from("<I", clmp, at)[0]
    at += 4 + name_length + 4
    floats = struct.unpack_from("<I", clmp, at)[0]
    at += 4 + 4 * floats
    return at + 4  # past the index count


def clump_graph_arrays_at(clmp):
    """Offsets of the first clump's motion-graph nodeLevel (u8s) and naturalNext (u32s) arrays in
    CLMP, past their counts (precompute/library/clump_section.cpp)."""
    at = 4  # clump count
    u32 = lambda: struct.unpack_from("<I", clmp, at)[0]
    at += 4 + u32()  # name
    at += 4  # plants
    at += 4 + 4 * u32()  # vertex data
    at += 4 + 4 * u32()  # indices
    at += 4  # bounding radius
    at += 4 + 4 * 5  # frames, modes per LOD
    at += 4 + 4 * u32()  # vertex blocks
    at += 4 + u32() * 4 * 6  # blocks: offset and five ranks each
    for _ in range(3):  # basis, coordinates, error per mode
        at += 4 + 4 * u32()
    at += 4 * 4  # node, level, edge counts, blend frames
    node_level = at + 4
    at += 4 + u32()  # nodeLevel
    at += 4 + u32()  # nodeAlive
    natural_next = at + 4
    return node_level, natural_next


CASES = {
    # Truncated files.
    "empty": lambda g: bytearray(),
    "truncated_header": lambda g: g[:20],
    "truncated_table": lambda g: g[:HEADER + ENTRY + 7],
    "truncated_payload": lambda g: g[: len(g) * 3 // 5],
    "truncated_last_byte": lambda g: g[:-1],
    # Bit flips: in the magic, the header's counts, the table and a section's bytes.
    "bitflip_magic": lambda g: flip(g, 2),
    "bitflip_section_count": lambda g: flip(g, 14),
    "bitflip_table": lambda g: flip(g, HEADER + 9),
    "bitflip_payload": lambda g: flip(g, len(g) // 2),
    "bitflip_last_byte": lambda g: flip(g, len(g) - 1),
    # Format versions other than this meadow's.
    "older_version": lambda g: (lambda b: (set_u32(b, 8, struct.unpack_from("<I", b, 8)[0] - 1), b)[1])(bytearray(g)),
    "future_version": lambda g: (lambda b: (set_u32(b, 8, 999), b)[1])(bytearray(g)),
    # A table that lies about where sections are (its own checksum recomputed).
    "section_size_lie": lambda g: fix_table_checksum(
        (lambda b: (struct.pack_into("<Q", b, entry(b, "CLMP") + 16, len(g)), b)[1])(bytearray(g))),
    "section_offset_lie": lambda g: fix_table_checksum(
        (lambda b: (struct.pack_into("<Q", b, entry(b, "SKYD") + 8, 1 << 62), b)[1])(bytearray(g))),
    "section_size_overflow": lambda g: fix_table_checksum(
        (lambda b: (struct.pack_into("<Q", b, entry(b, "TFLD") + 16, (1 << 64) - 8), b)[1])(bytearray(g))),
    "huge_section_count": lambda g: (lambda b: (set_u32(b, 12, 1 << 30), b)[1])(bytearray(g)),
    # Well-formed containers whose sections lie (every checksum recomputed).
    "missing_section": lambda g: rebuilt(g, lambda s: s.remove(next(x for x in s if x[0] == "SKYD"))),
    "duplicate_section": lambda g: rebuilt(g, lambda s: s.append(["TFLD", section(s, "TFLD")])),
    "section_shortened": lambda g: rebuilt(g, lambda s: section(s, "LODS").__delitem__(slice(-4, None))),
    "section_trailing_bytes": lambda g: rebuilt(g, lambda s: section(s, "CLMP").extend(b"\0\0\0\0")),
    "scene_not_json": lambda g: rebuilt(g, lambda s: section(s, "SCNE").__setitem__(slice(0, 1), b"#")),
    "scene_not_object": lambda g: rebuilt(g, lambda s: [x for x in s if x[0] == "SCNE"][0].__setitem__(1, bytearray(b"[1, 2]"))),
    "clump_count_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "CLMP"), 0, 1000)),
    "clump_name_length_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "CLMP"), 4, 0xFFFFFFF0)),
    "triangle_index_out_of_range": lambda g: rebuilt(
        g, lambda s: set_u32(section(s, "CLMP"), clump_mesh_index_at(section(s, "CLMP")), 0x7FFFFFFF)),
    "graph_level_out_of_range": lambda g: rebuilt(
        g, lambda s: section(s, "CLMP").__setitem__(clump_graph_arrays_at(section(s, "CLMP"))[0], 200)),
    "graph_successor_out_of_range": lambda g: rebuilt(
        g, lambda s: set_u32(section(s, "CLMP"), clump_graph_arrays_at(section(s, "CLMP"))[1], 0x7FFFFFFF)),
    "atlas_size_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "ATLS"), 0, 16384)),
    "instance_count_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "TFLD"), 0, 0xFFFFFFFF)),
    "instance_mesh_out_of_range": lambda g: rebuilt(g, lambda s: set_u32(section(s, "TFLD"), 4 + 24, 4096)),
    "instance_position_nan": lambda g: rebuilt(g, lambda s: set_f32(section(s, "TFLD"), 4, float("nan"))),
    "light_count_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "LITE"), 0, 7)),
    "sky_frame_count_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "SKYD"), 16, 100000)),
    "sky_time_nan": lambda g: rebuilt(g, lambda s: set_f32(section(s, "SKYD"), 20, float("nan"))),
    "rock_count_lie": lambda g: rebuilt(g, lambda s: set_u32(section(s, "ROCK"), 0, 65)),
    # FARS: clump count, then the first clump's area, coverage gains (20 f32), sample count and first
    # sample (x, y, z, normal, albedo, vertex): its first gain at 8, its vertex at 4 + 4 + 80 + 4 + 20.
    "far_gain_nan": lambda g: rebuilt(g, lambda s: set_f32(section(s, "FARS"), 8, float("nan"))),
    "far_sample_vertex_out_of_range": lambda g: rebuilt(g, lambda s: set_u32(section(s, "FARS"), 112, 0x7FFFFFFF)),
}


def main(argv):
    if argv[1:] == ["--list"]:
        print("\n".join(CASES))
        return 0
    good = bytearray(open(argv[1], "rb").read())
    for case in argv[3:]:
        with open("%s/%s.mlib" % (argv[2], case), "wb") as f:
            f.write(CASES[case](bytearray(good)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
