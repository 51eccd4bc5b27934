"""Decodes every mip level of a block-compressed .dds with PyPI's texture2ddecoder 1.0.6 (K0lb3's
C++ decoders, from AssetStudio's Texture2DDecoder; installed by scripts/py-checkers.sh, run with
that environment's python): a decoder that shares no code with matforge's (lib/texture) nor with
the encoders it judges (bc7enc, libsquish). The DDS is parsed here, not by matforge's reader.

    bc_decode.py IN.dds OUT_DIR

IN: "DDS ", the 124-byte DDS_HEADER (height at 12, width at 16, mipMapCount at 28, counted when
its flag 0x20000 is set, else one level; FourCC "DX10" at 84), the 20-byte DDS_HEADER_DXT10
(dxgiFormat, a 2D texture, not a cube, one array element), then each level's blocks, largest
first, nothing after. dxgiFormat: 71/72 BC1, 77/78 BC3, 80 BC4, 83 BC5, 98/99 BC7 (UNORM/SRGB;
the sRGB flag changes no code: the decoded codes are the stored ones).
Writes OUT_DIR/level<N>.rgba (width x height texels, rows top down, R, G, B, A bytes) and
OUT_DIR/levels.json [{"width", "height", "file"}]; prints {"format", "srgb", "levels"}.
Exits 1 with a message on anything it cannot decode (the library reads blocks unchecked: the
data's length is checked here first).

What the library returns, per texel B, G, R, A in memory (turned into R, G, B, A here):
  BC1  R, G, B of the colour block, A 255 always: the 3-colour mode's fourth index (transparent
       black in Direct3D) gives opaque black (0, 0, 0, 255), so BC1's 1-bit alpha is not decoded.
       Interpolation with integer division: (2*c0 + c1) / 3, (c0 + c1) / 2.
  BC3  R, G, B as BC1 (also its 3-colour mode when c0 <= c1, which Direct3D ignores in BC3),
       A from the alpha block ((6*a0 + a1) / 7 ..., integer division).
  BC4  R = the decoded channel, G = 0, B = 0, A = 255.
  BC5  R = the first block, G = the second, B = 0, A = 255 (no Z is rebuilt).
  BC7  R, G, B, A of the block, rotation applied; a reserved mode (first byte 0) gives 0, 0, 0, 0.
"""
import json
import os
import struct
import sys

import texture2ddecoder

# dxgiFormat -> (name, sRGB, bytes per 4x4 block, decoder)
FORMATS = {
    71: ("bc1", False, 8, texture2ddecoder.decode_bc1),
    72: ("bc1", True, 8, texture2ddecoder.decode_bc1),
    77: ("bc3", False, 16, texture2ddecoder.decode_bc3),
    78: ("bc3", True, 16, texture2ddecoder.decode_bc3),
    80: ("bc4", False, 8, texture2ddecoder.decode_bc4),
    83: ("bc5", False, 16, texture2ddecoder.decode_bc5),
    98: ("bc7", False, 16, texture2ddecoder.decode_bc7),
    99: ("bc7", True, 16, texture2ddecoder.decode_bc7),
}


def fail(message):
    sys.exit("bc_decode: " + message)


def main():
    if len(sys.argv) != 3:
        fail("usage: bc_decode.py IN.dds OUT_DIR")
    path, out_dir = sys.argv[1], sys.argv[2]
    data = open(path, "rb").read()
    if len(data) < 148 or data[:4] != b"DDS " or struct.unpack_from("<I", data, 4)[0] != 124:
        fail(f"{path}: not a DDS (magic 'DDS ' and a 124-byte header)")
    flags, height, width = struct.unpack_from("<3I", data, 8)
    mips = max(1, struct.unpack_from("<I", data, 28)[0]) if flags & 0x20000 else 1
    if data[84:88] != b"DX10":
        fail(f"{path}: no DX10 header (FourCC {data[84:88]!r})")
    dxgi, dimension, misc, array_size = struct.unpack_from("<4I", data, 128)
    if dxgi not in FORMATS:
        fail(f"{path}: dxgiFormat {dxgi} is none of {sorted(FORMATS)}")
    if dimension != 3 or misc & 0x4 or array_size != 1:
        fail(f"{path}: not one 2D texture (dimension {dimension}, miscFlag {misc:#x}, arraySize {array_size})")
    if not 0 < width <= 65536 or not 0 < height <= 65536 or mips > 17:
        fail(f"{path}: size {width}x{height} with {mips} levels")
    name, srgb, block_bytes, decode = FORMATS[dxgi]
    os.makedirs(out_dir, exist_ok=True)
    offset, levels = 148, []
    for n in range(mips):
        w, h = max(1, width >> n), max(1, height >> n)
        size = ((w + 3) // 4) * ((h + 3) // 4) * block_bytes
        if offset + size > len(data):
            fail(f"{path}: level {n} ({w}x{h}) needs {size} bytes at {offset}, the file has {len(data)}")
        bgra = decode(data[offset:offset + size], w, h)
        offset += size
        rgba = bytearray(bgra)
        rgba[0::4], rgba[2::4] = bgra[2::4], bgra[0::4]
        file = f"level{n}.rgba"
        with open(os.path.join(out_dir, file), "wb") as f:
            f.write(rgba)
        levels.append({"width": w, "height": h, "file": file})
    if offset != len(data):
        fail(f"{path}: {len(data) - offset} bytes after the last of {mips} levels")
    with open(os.path.join(out_dir, "levels.json"), "w") as f:
        json.dump(levels, f)
    print(json.dumps({"format": name, "srgb": srgb, "levels": mips}))


if __name__ == "__main__":
    main()
