"""The depth channel Z of an EXR image as tetray writes it (docs/outputs.md: scanline, Z a float
per pixel, the distance along the view axis, +inf where nothing was hit), read with numpy alone:
Debian 12 has no Python OpenEXR module. Reads the lossless compressions the split study asks
tetray for: `exr_compression: none`, `zips` or `zip`.
"""

import struct
import zlib

import numpy as np

_HALF, _FLOAT = 1, 2
_BYTES = {0: 4, _HALF: 2, _FLOAT: 4}
_COMPRESSIONS = {0: ("none", 1), 2: ("zips", 1), 3: ("zip", 16)}  # code: name, lines per block


def _header(data):
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    if data[4] != 2 or data[5] & 0x1E:  # version 2, single-part scanline, short names
        raise ValueError("not a single-part scanline OpenEXR file")
    position, attributes = 8, {}
    while data[position] != 0:
        name_end = data.index(b"\0", position)
        type_end = data.index(b"\0", name_end + 1)
        (size,) = struct.unpack_from("<i", data, type_end + 1)
        start = type_end + 5
        attributes[data[position:name_end].decode()] = data[start:start + size]
        position = start + size
    return attributes, position + 1


def _channels(chlist):
    """[(name, pixel type)] in file order (alphabetical)."""
    channels, position = [], 0
    while chlist[position] != 0:
        end = chlist.index(b"\0", position)
        (pixel_type,) = struct.unpack_from("<i", chlist, end + 1)
        channels.append((chlist[position:end].decode(), pixel_type))
        position = end + 1 + 16
    return channels


def _undo_zip(block, expected):
    """OpenEXR's ZIP: zlib, then a byte predictor and an interleave of the two halves."""
    packed = np.frombuffer(zlib.decompress(block), dtype=np.uint8).astype(np.int64)
    if len(packed) != expected:
        raise ValueError("a ZIP block of the wrong size")
    packed[1:] -= 128
    restored = (np.cumsum(packed) & 0xFF).astype(np.uint8)
    half = (len(restored) + 1) // 2
    out = np.empty_like(restored)
    out[0::2], out[1::2] = restored[:half], restored[half:]
    return out


def read_depth(path):
    """(height, width) float32: the Z channel of the EXR at `path`."""
    data = open(path, "rb").read()
    attributes, position = _header(data)
    channels = _channels(attributes["channels"])
    if ("Z", _FLOAT) not in channels:
        raise ValueError(f"{path}: no float Z channel")
    x0, y0, x1, y1 = struct.unpack("<4i", attributes["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    code = attributes["compression"][0]
    if code not in _COMPRESSIONS:
        raise ValueError(f"{path}: compression {code} is not none, zips or zip "
                         "(give the scene's output exr_compression: none)")
    lines_per_block = _COMPRESSIONS[code][1]
    blocks = (height + lines_per_block - 1) // lines_per_block
    offsets = struct.unpack_from(f"<{blocks}Q", data, position)
    line_bytes = sum(_BYTES[t] for _, t in channels) * width
    # Z's byte range within one line: channels are stored one after another, line by line.
    z_start = sum(_BYTES[t] for name, t in channels[:channels.index(("Z", _FLOAT))]) * width
    depth = np.empty((height, width), dtype=np.float32)
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        lines = min(lines_per_block, y0 + height - y)
        block = data[offset + 8:offset + 8 + size]
        expected = line_bytes * lines
        raw = (np.frombuffer(block, dtype=np.uint8) if size == expected
               else _undo_zip(block, expected))  # a block stored as is when packing grows it
        rows = raw.reshape(lines, line_bytes)[:, z_start:z_start + 4 * width]
        depth[y - y0:y - y0 + lines] = np.ascontiguousarray(rows).view("<f4")
    return depth
