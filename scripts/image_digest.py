#!/usr/bin/env python3
"""Prints a SHA-256 of the pixels of each image named (raylab's EXR or PNG output), one line each.

The digest covers what the image shows, not how the file happens to be laid out: the exr crate stores an
EXR's chunks in whatever order its threads finish them, so the same pixels give different file bytes, and
both formats carry provenance text (the scene file's absolute path), which depends on where the checkout
is. So an EXR digest is of its header without the `comments` attribute and its chunks sorted by position;
a PNG digest is of its IHDR and IDAT chunks. Standard library only."""
import hashlib
import struct
import sys


def exr_digest(data):
    assert data[:4] == b'\x76\x2f\x31\x01', 'not an EXR'
    assert not data[5] & 0x10, 'a multi-part EXR'
    digest = hashlib.sha256(data[4:8])
    pos, attributes = 8, {}
    while data[pos] != 0:
        name_end = data.index(b'\0', pos)
        type_end = data.index(b'\0', name_end + 1)
        size = struct.unpack_from('<i', data, type_end + 1)[0]
        start = type_end + 5
        name = data[pos:name_end].decode()
        attributes[name] = data[start:start + size]
        if name != 'comments':
            digest.update(data[pos:start + size])
        pos = start + size
    tiled = attributes.get('type') == b'tiledimage' or bool(data[5] & 0x02)
    if 'chunkCount' in attributes:
        count = struct.unpack('<i', attributes['chunkCount'])[0]
    else:
        assert not tiled, 'a tiled EXR without chunkCount'
        _, y0, _, y1 = struct.unpack('<4i', attributes['dataWindow'])
        lines = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 256, 8: 256, 9: 32}[attributes['compression'][0]]
        count = (y1 - y0 + lines) // lines
    coordinates = 16 if tiled else 4
    pos += 1 + 8 * count  # past the offset table, which depends on the order
    chunks = []
    for _ in range(count):
        size = struct.unpack_from('<i', data, pos + coordinates)[0]
        end = pos + coordinates + 4 + size
        chunks.append(data[pos:end])
        pos = end
    assert pos == len(data), f'{len(data) - pos} bytes after the last chunk'
    position = lambda chunk: struct.unpack_from(f'<{coordinates // 4}i', chunk)[::-1]
    for chunk in sorted(chunks, key=position):
        digest.update(chunk)
    return digest.hexdigest()


def png_digest(data):
    assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
    digest, pos = hashlib.sha256(), 8
    while pos < len(data):
        length, kind = struct.unpack_from('>I4s', data, pos)
        if kind in (b'IHDR', b'IDAT'):
            digest.update(data[pos:pos + 12 + length])
        pos += 12 + length
    return digest.hexdigest()


for path in sys.argv[1:]:
    data = open(path, 'rb').read()
    try:
        print(exr_digest(data) if path.endswith('.exr') else png_digest(data))
    except (AssertionError, KeyError, struct.error) as error:
        sys.exit(f'{path}: cannot read: {error}')
