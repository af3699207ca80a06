# SPDX-License-Identifier: MIT
"""valid_image.py FILE [TEXT...]: FILE is a PNG or SVG that decodes, is not blank, and (SVG) holds
every TEXT in its <text> elements"""
import struct, sys, zlib
import xml.etree.ElementTree as ET
path, texts = sys.argv[1], sys.argv[2:]
data = open(path, "rb").read()
if path.endswith(".png"):
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "signature"
    pos, chunks, idat = 8, [], b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body, crc = data[pos + 8:pos + 8 + n], struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]
        assert zlib.crc32(kind + body) == crc, f"CRC of {kind}"
        chunks.append(kind)
        idat += body if kind == b"IDAT" else b""
        pos += 12 + n
    assert chunks[0] == b"IHDR" and chunks[-1] == b"IEND", chunks
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    channels = {2: 3, 6: 4}[ctype]
    raw = zlib.decompress(idat)
    assert depth == 8 and w > 100 and h > 100 and len(raw) == h * (1 + w * channels), "size"
    assert len(set(raw[1:1 + w * channels * h // 2])) > 8, "blank"
else:
    root = ET.fromstring(data)
    assert root.tag == "{http://www.w3.org/2000/svg}svg", root.tag
    words = " ".join(t.text or "" for t in root.iter("{http://www.w3.org/2000/svg}text"))
    missing = [t for t in texts if t not in words]
    assert not missing, f"no text {missing} in {words[:300]}"
    assert len(list(root.iter())) > 50, "too few elements"
