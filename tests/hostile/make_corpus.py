#!/usr/bin/env python3
"""Writes raylab's hostile-file corpus (tests/hostile/xml, tests/hostile/gltf).

Most files are small and written out here in full; the large or binary ones
(deep nesting, GLB containers, a lying PNG) are generated. Run it from
anywhere: `python3 tests/hostile/make_corpus.py`. The expected error of each
file (the place it must name) is in tests/hostile/expected.tsv, kept by hand.
"""

import base64
import json
import pathlib
import struct
import zlib

HERE = pathlib.Path(__file__).resolve().parent
XML = HERE / "xml"
GLTF = HERE / "gltf"


def write(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data if isinstance(data, bytes) else data.encode())


def b64(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def triangle_gltf(**overrides):
    """A valid one-triangle glTF with an embedded buffer; `overrides` replace
    top-level members."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    data = positions + indices
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "buffers": [{"byteLength": len(data), "uri": b64(data)}],
    }
    doc.update(overrides)
    return doc


def glb(json_bytes, bin_bytes=None, total=None, version=2):
    pad = lambda b, c: b + c * (-len(b) % 4)
    body = pad(json_bytes, b" ")
    chunks = struct.pack("<I4s", len(body), b"JSON") + body
    if bin_bytes is not None:
        b = pad(bin_bytes, b"\0")
        chunks += struct.pack("<I4s", len(b), b"BIN\0") + b
    length = total if total is not None else 12 + len(chunks)
    return struct.pack("<4sII", b"glTF", version, length) + chunks


def png(ihdr, idat):
    """A PNG file of the given IHDR and IDAT chunk data."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


def png_header(width, height):
    """A PNG whose header claims width × height but whose data is one byte."""
    return png(struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0), zlib.compress(b"\0"))


def xml_corpus():
    seed = '<scene>\n  <camera eye="0 1 5" toward="0 0 -1" theta="30" width="64" height="48"/>\n  <sphere center="0 0 0" radius="1" color="red"/>\n</scene>\n'
    write(XML / "empty.xml", "")
    write(XML / "truncated.xml", seed[: seed.index('radius="1"') + 5])
    write(XML / "not_xml.xml", "this is not a scene at all {\n}\n")
    write(XML / "binary_garbage.xml", bytes(range(256)) * 4)
    write(XML / "not_utf8.xml", b'<scene>\n  <sphere name="caf\xe9"/>\n</scene>\n')
    write(XML / "wrong_type_radius.xml", seed.replace('radius="1"', 'radius="big"'))
    write(XML / "wrong_type_triple.xml", seed.replace('eye="0 1 5"', 'eye="0 1"'))
    write(XML / "wrong_type_color.xml", seed.replace('color="red"', 'color="reddish-ish"'))
    write(XML / "unknown_element.xml", seed.replace("<sphere", "<spheroid"))
    write(XML / "unclosed_quote.xml", seed.replace('radius="1"', 'radius="1'))
    write(XML / "second_root.xml", seed + "<scene/>\n")
    depth = 10_000
    write(XML / "deep_nesting.xml", "<scene>\n" + "<group>" * depth + "</group>" * depth + "\n</scene>\n")
    laughs = ['<!DOCTYPE scene [', ' <!ENTITY lol "lol">']
    for i in range(1, 10):
        prev = f"&lol{i - 1};" if i > 1 else "&lol;"
        laughs.append(f' <!ENTITY lol{i} "{prev * 10}">')
    laughs.append("]>")
    write(XML / "billion_laughs.xml", "\n".join(laughs) + '\n<scene>\n  <sphere name="&lol9;"/>\n</scene>\n')
    write(XML / "external_entity.xml", '<!DOCTYPE scene [ <!ENTITY secret SYSTEM "file:///etc/passwd"> ]>\n<scene>\n  <sphere name="&secret;"/>\n</scene>\n')
    write(XML / "huge_number.xml", seed.replace('radius="1"', 'radius="1e400"'))
    write(XML / "long_number.xml", seed.replace('radius="1"', 'radius="' + "9" * 100_000 + '"'))
    write(XML / "huge_image.xml", seed.replace('width="64"', 'width="4000000000"'))
    write(XML / "huge_image_area.xml", seed.replace('width="64" height="48"', 'width="16384" height="16384"'))
    write(XML / "nan_radius.xml", seed.replace('radius="1"', 'radius="NaN"'))
    write(XML / "inf_eye.xml", seed.replace('eye="0 1 5"', 'eye="0 inf 5"'))
    write(XML / "neg_inf_theta.xml", seed.replace('theta="30"', 'theta="-inf"'))
    write(XML / "nan_color.xml", seed.replace('color="red"', 'color="NaN 0 0"'))
    write(XML / "nan_light.xml", seed.replace("</scene>", '  <light type="point" position="0 5 0" intensity="nan"/>\n</scene>'))
    write(XML / "zero_toward.xml", seed.replace('toward="0 0 -1"', 'toward="0 0 0"'))
    write(XML / "mesh_missing_file.xml", seed.replace("</scene>", '  <mesh src="no-such-model.glb"/>\n</scene>'))
    write(XML / "mesh_network_uri.xml", seed.replace("</scene>", '  <mesh src="https://example.com/model.glb"/>\n</scene>'))
    write(XML / "mesh_device.xml", seed.replace("</scene>", '  <mesh src="/dev/zero"/>\n</scene>'))
    write(XML / "mesh_hostile_model.xml", seed.replace("</scene>", '  <mesh src="../gltf/index_out_of_range.gltf"/>\n</scene>'))


def png_flat_1bit(width, height):
    """A real, decodable 1-bit grey PNG of zeros: about 8,000 texels per byte."""
    row = b"\0" * (1 + (width + 7) // 8)
    return png(struct.pack(">IIBBBBB", width, height, 1, 0, 0, 0, 0), zlib.compress(row * height, 9))


def textured_gltf(png_bytes):
    """The triangle with `png_bytes` as its base colour texture."""
    doc = triangle_gltf()
    doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()}]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    return doc


def gltf_corpus():
    ok = json.dumps(triangle_gltf(), indent=1)
    write(GLTF / "empty.gltf", "")
    write(GLTF / "truncated.gltf", ok[: len(ok) // 2])
    write(GLTF / "not_json.gltf", "<scene/>\n")
    write(GLTF / "wrong_types.gltf", json.dumps(triangle_gltf(accessors="three")))
    write(GLTF / "gltf_1.gltf", json.dumps({"asset": {"version": "1.0"}}))
    deep = "[" * 100_000 + "]" * 100_000
    write(GLTF / "deep_json.gltf", '{"asset": {"version": "2.0"}, "extras": ' + deep + "}")
    doc = triangle_gltf()
    doc["meshes"][0]["primitives"][0]["indices"] = 99
    write(GLTF / "index_out_of_range.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["nodes"] = [{"children": [1]}, {"mesh": 5}]
    write(GLTF / "node_mesh_out_of_range.gltf", json.dumps(doc))
    # Vertex indices that point past the three positions.
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 60000) + b"\0\0"
    doc = triangle_gltf(buffers=[{"byteLength": len(data), "uri": b64(data)}])
    write(GLTF / "vertex_index_out_of_range.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["accessors"][0]["count"] = 4_000_000_000
    write(GLTF / "accessor_count_huge.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["accessors"][0]["byteOffset"] = 32
    write(GLTF / "accessor_overruns_view.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["bufferViews"][1]["byteLength"] = 600
    write(GLTF / "view_overruns_buffer.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["bufferViews"][1]["byteOffset"] = 2**63
    write(GLTF / "view_offset_huge.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["buffers"][0]["byteLength"] = 4 * 2**30
    write(GLTF / "claims_4gb_buffer.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["buffers"] = [{"byteLength": 4 * 2**30 - 1, "uri": "tiny.bin"}]
    write(GLTF / "tiny.bin", b"\0" * 48)
    write(GLTF / "external_claims_4gb.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["buffers"] = [{"byteLength": 48, "uri": "no-such-buffer.bin"}]
    write(GLTF / "missing_external_buffer.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["buffers"] = [{"byteLength": 48, "uri": "https://example.com/buffer.bin"}]
    write(GLTF / "network_buffer_uri.gltf", json.dumps(doc))
    doc = triangle_gltf()
    # 1 GiB of zeros for the asking, were devices read.
    doc["buffers"] = [{"byteLength": 2**30, "uri": "../../../../../../../../dev/zero"}]
    write(GLTF / "device_buffer_uri.gltf", json.dumps(doc))
    doc = triangle_gltf(extensionsUsed=["EXT_raylab_does_not_know"], extensionsRequired=["EXT_raylab_does_not_know"])
    write(GLTF / "unknown_required_extension.gltf", json.dumps(doc))
    data = struct.pack("<9f", 0, 0, 0, float("nan"), 0, 0, 0, float("inf"), 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
    write(GLTF / "nan_positions.gltf", json.dumps(triangle_gltf(buffers=[{"byteLength": len(data), "uri": b64(data)}])))
    doc = triangle_gltf()
    doc["nodes"] = [{"mesh": 0, "matrix": [1e38] * 16}]
    write(GLTF / "overflowing_matrix.gltf", json.dumps(doc))
    doc = triangle_gltf()
    doc["nodes"] = [{"mesh": 0, "scale": [1e30, 1e30, 1e30]}, ]
    write(GLTF / "huge_scale.gltf", json.dumps(doc))
    doc = triangle_gltf()
    n = 10_000
    doc["nodes"] = [{"children": [i + 1]} for i in range(n)] + [{"mesh": 0}]
    write(GLTF / "deep_node_chain.gltf", json.dumps(doc, separators=(",", ":")))
    doc = triangle_gltf()
    doc["nodes"] = [{"children": [1]}, {"children": [0], "mesh": 0}]
    write(GLTF / "node_cycle.gltf", json.dumps(doc))
    write(GLTF / "image_claims_40_gigapixels.gltf", json.dumps(textured_gltf(png_header(200_000, 200_000))))
    # Accessors without a bufferView are zeros, so nothing in the file bounds
    # their count: 16 meshes of 393,216 such vertices would decode 6.3M.
    doc = triangle_gltf()
    count = 3 * 2**17
    doc["accessors"].append({"componentType": 5126, "count": count, "type": "VEC3"})
    doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": 2}}]} for _ in range(16)]
    doc["nodes"] = [{"mesh": i} for i in range(16)]
    doc["scenes"] = [{"nodes": list(range(16))}]
    write(GLTF / "viewless_accessors_add_up.gltf", json.dumps(doc))
    # One 1,200-vertex accessor read by 2,000 primitives: 2.4M vertices
    # decoded from a 14 KB buffer.
    data = struct.pack("<3600f", *([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] * 400))
    doc = triangle_gltf(buffers=[{"byteLength": len(data), "uri": b64(data)}])
    doc["bufferViews"] = [{"buffer": 0, "byteOffset": 0, "byteLength": len(data)}]
    doc["accessors"] = [{"bufferView": 0, "componentType": 5126, "count": 1200, "type": "VEC3"}]
    doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}}] * 2000}]
    write(GLTF / "shared_accessor_read_2000_times.gltf", json.dumps(doc, separators=(",", ":")))
    # Unlike the lying PNG above, this one decodes: 90 million texels (361 MB
    # as RGBA8) from 14 KB.
    write(GLTF / "image_flat_90_megapixels.gltf", json.dumps(textured_gltf(png_flat_1bit(9500, 9500))))
    body = json.dumps(triangle_gltf(buffers=[{"byteLength": 48}])).encode()
    write(GLTF / "glb_claims_4gb.glb", glb(body, b"\0" * 48, total=2**32 - 1))
    write(GLTF / "glb_truncated.glb", glb(body, b"\0" * 48)[:40])
    write(GLTF / "glb_version_1.glb", glb(body, b"\0" * 48, version=1))
    write(GLTF / "glb_bin_too_short.glb", glb(body, b"\0" * 8))
    lying = bytearray(glb(body, b"\0" * 48))
    json_len = struct.unpack_from("<I", lying, 12)[0]
    struct.pack_into("<I", lying, 12 + 8 + json_len, 0xFFFFFFF0)
    write(GLTF / "glb_chunk_claims_4gb.glb", bytes(lying))


if __name__ == "__main__":
    xml_corpus()
    gltf_corpus()
