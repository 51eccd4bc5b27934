"""PSNR of a decoded level against its source, for bench/texture/bc7_vs_bc7e.sh (run with the
virtual environment of scripts/py-checkers.sh, for numpy).

    psnr_rgba.py REF.ppm DECODED.rgba [REF_ALPHA.pgm]

REF.ppm: the source's R, G, B (binary PPM, maxval 255; REF_ALPHA.pgm its alpha, binary PGM), as
`oiiotool --iconfig oiio:UnassociatedAlpha 1 IN.png --ch R,G,B -o REF.ppm` writes them: PNM has no
alpha, so nothing is premultiplied. DECODED.rgba: width x height texels of R, G, B, A bytes, rows
top down (tests/texture/checkers/bc_decode.py's level<N>.rgba).
Prints the PSNR in dB over R, G, B, and with REF_ALPHA over R, G, B, A: 10 log10(255^2 / MSE),
the MSE over every texel's channels together (99 when equal).
"""
import sys

import numpy as np


def pnm(path, magic, channels):
    data = open(path, "rb").read()
    fields = data.split(maxsplit=4)  # magic, width, height, maxval, pixels (one whitespace byte skipped)
    if len(fields) < 5 or fields[0] != magic or fields[3] != b"255":
        sys.exit(f"psnr_rgba: {path}: not a binary {magic.decode()} with maxval 255")
    w, h = int(fields[1]), int(fields[2])
    pixels = np.frombuffer(data, np.uint8, w * h * channels, len(data) - w * h * channels)
    return w, h, pixels.reshape(h, w, channels)


def psnr(a, b):
    mse = np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2)
    return 10 * np.log10(255.0**2 / mse) if mse > 0 else 99.0


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: psnr_rgba.py REF.ppm DECODED.rgba [REF_ALPHA.pgm]")
    w, h, ref = pnm(sys.argv[1], b"P6", 3)
    dec = np.fromfile(sys.argv[2], np.uint8)
    if dec.size != w * h * 4:
        sys.exit(f"psnr_rgba: {sys.argv[2]}: {dec.size} bytes, not {w}x{h} RGBA")
    dec = dec.reshape(h, w, 4)
    out = [psnr(ref, dec[..., :3])]
    if len(sys.argv) == 4:
        aw, ah, alpha = pnm(sys.argv[3], b"P5", 1)
        if (aw, ah) != (w, h):
            sys.exit(f"psnr_rgba: {sys.argv[3]}: {aw}x{ah}, not {w}x{h}")
        out.append(psnr(np.concatenate([ref, alpha], axis=2), dec))
    print(" ".join(f"{v:.3f}" for v in out))


if __name__ == "__main__":
    main()
