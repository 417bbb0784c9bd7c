#!/usr/bin/env python3
"""numpy.load of the .npy files that tests/io/python/fixture.cpp wrote gives the waterfall exactly (compared with
the raw values the fixture wrote itself); the JSON sidecar describes it; the PNG files decode (Python's zlib,
CRC-32 of every chunk) to the grey levels the fixture computed. Exit status 0 when every check holds."""
import json
import struct
import sys
import zlib

import numpy as np

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def read_png(path):
    data = open(path, "rb").read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: signature")
    at, idat, header, chunks = 8, b"", None, []
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunks.append((kind, length))
        body = data[at + 8:at + 8 + length]
        crc = struct.unpack(">I", data[at + 8 + length:at + 12 + length])[0]
        check(zlib.crc32(kind + body) == crc, f"{path}: CRC of {kind}")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    idats = [n for kind, n in chunks if kind == b"IDAT"]
    check(all(n <= 1 << 20 for n in idats) and all(n == 1 << 20 for n in idats[:-1]),
          f"{path}: IDAT chunks of 1 MiB, the last one shorter ({idats})")
    if path.endswith("wide.png"):
        check(len(idats) == 3, f"{path}: 2.1 MB of noise in three IDAT chunks ({idats})")
    width, height, depth, colour, _, _, interlace = header
    check(colour == 0 and interlace == 0, f"{path}: greyscale, not interlaced")
    raw = zlib.decompress(idat)
    bpp = depth // 8
    rows = np.frombuffer(raw, np.uint8).reshape(height, 1 + width * bpp)
    check(np.all(rows[:, 0] == 0), f"{path}: filter bytes")
    pixels = rows[:, 1:]
    if bpp == 2:
        pixels = pixels.copy().view(">u2").reshape(height, width)
    return pixels


def main():
    side = json.load(open("waterfall.json"))
    shape = tuple(side["shape"])
    for name, raw, dtype in (("waterfall.npy", "waterfall_f64.raw", "<f8"), ("waterfall_f32.npy", "waterfall_f32.raw", "<f4")):
        a = np.load(name)
        truth = np.fromfile(raw, dtype=dtype).reshape(shape)
        check(a.dtype == np.dtype(dtype), f"{name}: dtype {a.dtype}")
        check(a.shape == shape and a.flags["C_CONTIGUOUS"], f"{name}: shape {a.shape}")
        check(np.array_equal(a, truth), f"{name}: values differ from the waterfall")
        check(a.max() > 0, f"{name}: an empty render")
    check(side["array_file"] == "waterfall.npy" and side["dtype"] == "<f8", "sidecar: file and dtype")
    check(shape[1] == 2 * side["samples_per_side"], "sidecar: two sides")
    check(len(side["poses"]) == shape[0], "sidecar: one pose per ping")
    check(abs(side["max_range_m"] - side["samples_per_side"] * side["sample_interval_s"] * side["sound_speed_mps"] / 2) < 1e-9,
          "sidecar: range of the last sample")
    check(abs(side["poses"][1]["time_s"] - 0.25) < 1e-12 and abs(side["poses"][0]["heading_deg"] - 120) < 1e-9,
          "sidecar: poses")
    for name, raw, dtype in (("grey8.png", "grey8.raw", np.uint8), ("grey16.png", "grey16.raw", "<u2"),
                             ("ramp.png", "ramp.raw", np.uint8), ("noise.png", "noise.raw", np.uint8),
                             ("wide.png", "wide.raw", np.uint8),
                             ("runs.png", "runs.raw", "<u2")):
        pixels = read_png(name)
        truth = np.fromfile(raw, dtype=dtype)
        check(pixels.size == truth.size and np.array_equal(pixels.reshape(-1).astype(np.int64), truth.astype(np.int64)),
              f"{name}: pixels differ")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"numpy.load: waterfall {shape} exact in float64 and float32; sidecar and 6 PNG files agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
