#!/usr/bin/env python3
"""Runs texplore over other projects' own test suites and judges every file against
independent decoders (issue 38 section 4; the results are in docs/robustness.md).

    python3 scripts/suites.py --suites DIR --texplore target/release/texplore [--jobs 2]
        [--only png,jpeg,tiff,exr,mesh] [--csv out.csv] [--show bad]

DIR holds the suites, one folder per project, as `fetch` brings them (see SUITES below for
the folders read): image-png's tests (PngSuite), jpeg-decoder's tests, libjpeg-turbo's
testimages, image-tiff's tests, openexr-images, exrs's tests, and the OBJ and PLY models of
tinyobjloader, tobj, assimp, trimesh, ply-rs, happly and tinyply.

Each image is read with `texplore image-info FILE -o OUT.exr` (the texels exactly as texplore
holds them), each mesh with `texplore mesh-info FILE --json`, under a 60 s timeout; the
process's peak memory is recorded. The references, none of them texplore's own decoders:

- PNG: pypng (pure Python; checks every chunk's CRC and the zlib stream), samples / (2^depth - 1).
- JPEG: libjpeg-turbo 3.1 through imagecodecs (`jpeg8_decode`: baseline, progressive,
  arithmetic, 12-bit and lossless), libjpeg's default (fancy) upsampling.
- TIFF: tifffile (with imagecodecs for the codecs) for the samples; the photometric
  conversions below are the harness's: min-is-white inverted, palette through the colour map,
  CMYK naive (R = (1 - C)(1 - K)), YCbCr by the TIFF 6.0 formulas, unsigned integers /
  (2^bits - 1), signed integers offset by 2^(bits - 1) then / (2^bits - 1), floats as they are.
- OpenEXR: the OpenEXR library's Python binding (channels as stored): RGB, or Y as grey, or
  Y/RY/BY turned into RGB by the Rec. 709 weights (chroma repeated from its subsampled grid).
- Meshes: trimesh (`force='mesh'`, `process=False`): the triangle count.

Images are read by content (a PNG named .jpg is a PNG), as texplore reads them.

Verdicts. Handled: `match`; `both-refuse`; `refuses-invalid` (a file its suite names invalid,
or one of KNOWN_INVALID); `no-surface` (a mesh the reference reads with no triangles: a point
cloud, lines only, an empty file, which texplore refuses as such); `survived` (a damaged file
from a crash-test or fuzzer folder: only surviving counts). Mishandled: `wrong-size`,
`wrong-pixels`, `refuses-valid`, `accepts-corrupt`, `crash`, `timeout`, `memory` (a peak above
MAX_PEAK_MIB), `unclear` (refused without an error). Counted apart: `unsupported` (a valid file
refused with a message naming its variant as not supported). Pixels are compared in the encoded
domain (integer sources, [0, 1]) or the linear one (float sources), alpha ignored.
"""

import argparse
import re
import concurrent.futures as futures
import csv
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# (suite folder, kind, file suffixes); the suite's files under that folder, recursively.
SUITES = [
    ("image-png/tests", "png", (".png",)),
    ("jpeg-decoder/tests", "jpeg", (".jpg", ".jpeg")),
    ("libjpeg-turbo/testimages", "jpeg", (".jpg",)),
    ("image-tiff/tests", "tiff", (".tif", ".tiff", "")),
    ("openexr-images", "exr", (".exr",)),
    ("exrs/tests", "exr", (".exr",)),
    ("tinyobjloader", "mesh", (".obj",)),
    ("tobj", "mesh", (".obj",)),
    ("assimp", "mesh", (".obj", ".ply")),
    ("trimesh", "mesh", (".obj", ".ply")),
    ("ply-rs", "mesh", (".ply",)),
    ("happly", "mesh", (".ply",)),
    ("tinyply", "mesh", (".ply",)),
]

TIMEOUT = 60.0
# The most one file may take (issue 38 saw 170 MB at most; images up to the 1 GiB texture budget
# would need more, none of the suites' does).
MAX_PEAK_MIB = 1024


def files(root):
    """Every (path, kind) of the selection, sorted."""
    out = []
    for folder, kind, suffixes in SUITES:
        base = Path(root) / folder
        if not base.is_dir():
            print(f"missing suite folder {base}", file=sys.stderr)
            continue
        for p in sorted(base.rglob("*")):
            if not p.is_file() or p.is_symlink():
                continue
            suffix = p.suffix.lower()
            if suffix in suffixes and suffix:
                out.append((p, kind))
            elif "" in suffixes and "fuzz_images" in p.parts:
                # image-tiff's fuzzer finds have no extension.
                out.append((p, kind))
    return out


def run(cmd):
    """(exit code, None on a timeout or a signal's negative number, stdout, stderr, peak RSS in
    MiB). The peak comes from GNU time, which starts the command from its own small process: a
    child forked from this harness would report the harness's own peak (Linux keeps the
    largest resident size across exec)."""
    with tempfile.NamedTemporaryFile("r") as stats:
        p = subprocess.Popen(
            ["/usr/bin/time", "-f", "%M %x", "-o", stats.name] + cmd,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        try:
            out, err = p.communicate(timeout=TIMEOUT)
            timed_out = False
        except subprocess.TimeoutExpired:
            p.kill()
            out, err = p.communicate()
            timed_out = True
        text = Path(stats.name).read_text()
    peak = 0.0
    code = p.returncode
    for line in text.splitlines():
        if "terminated by signal" in line:
            code = -int(line.split()[-1])
        parts = line.split()
        if len(parts) == 2 and parts[0].isdigit():
            peak = int(parts[0]) / 1024
    return (None if timed_out else code), out.decode(errors="replace"), err.decode(errors="replace"), peak


# ---------- references ----------


class Refused(Exception):
    pass


def srgb_encode(v):
    v = np.clip(np.nan_to_num(v, nan=0.0), 0.0, 1.0)
    return np.where(v <= 0.0031308, v * 12.92, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def rgb3(a):
    """H x W x C samples to H x W x 3 (grey repeated, alpha and extra samples dropped)."""
    if a.ndim == 2:
        a = a[:, :, None]
    c = a.shape[2]
    if c < 3:
        return np.repeat(a[:, :, :1], 3, axis=2)
    return a[:, :, :3]


def png_without_bad_ancillary(data):
    """The PNG with every ancillary chunk whose CRC is wrong left out, as libpng reads by
    default (a bad critical chunk is kept: the decoder refuses it)."""
    import zlib

    out, i = [data[:8]], 8
    while i + 12 <= len(data):
        n = int.from_bytes(data[i : i + 4], "big")
        kind = data[i + 4 : i + 8]
        end = i + 12 + n
        if end > len(data):
            break
        crc = int.from_bytes(data[end - 4 : end], "big")
        if zlib.crc32(data[i + 4 : end - 4]) == crc or not kind[0] & 0x20:
            out.append(data[i:end])
        i = end
        if kind == b"IEND":
            return b"".join(out)
    out.append(data[i:])
    return b"".join(out)


def ref_png(path):
    import png

    data = Path(path).read_bytes()
    try:
        r = png.Reader(bytes=png_without_bad_ancillary(data))
        w, h, rows, info = r.read()
        a = np.array([np.asarray(row, dtype=np.float64) for row in rows])
        if a.size != w * h * info["planes"]:
            raise ValueError(f"{a.size} samples for {w} x {h}")
    except Exception as e:  # noqa: BLE001 - any failure is the reference's refusal
        raise Refused(f"{type(e).__name__}: {e}") from None
    if "palette" in info and info["planes"] == 1:
        # Indices past the palette are black, as libpng (and image-png) read them.
        pal = np.zeros((256, 3))
        entries = np.array([p[:3] for p in info["palette"]], dtype=np.float64) / 255
        pal[: len(entries)] = entries
        return pal[a.reshape(h, w).astype(np.int64)], "encoded", 1.01 / 255
    a = a.reshape(h, w, info["planes"]) / float(2 ** info["bitdepth"] - 1)
    return rgb3(a), "encoded", 1.01 / 255


def ref_jpeg(path):
    import imagecodecs

    data = Path(path).read_bytes()
    try:
        a = imagecodecs.jpeg8_decode(data)
    except Exception as e:  # noqa: BLE001
        raise Refused(f"{type(e).__name__}: {e}") from None
    if a.dtype == np.uint8:
        a = a.astype(np.float64) / 255
        if a.ndim == 3 and a.shape[2] == 4:
            # libjpeg hands over Adobe's CMYK as stored (inverted): R = C K, naive, no profile.
            a = a[:, :, :3] * a[:, :, 3:4]
    else:
        bits = jpeg_precision(data) or 16
        a = a.astype(np.float64) / (2**bits - 1)
    # Lossy decoders differ by their IDCTs' rounding; lossless must match to the sample.
    lossless = jpeg_is_lossless(data)
    return rgb3(a), "encoded", (1.01 / 255 if lossless else "lossy")


def jpeg_frame(data):
    """(marker, precision) of the first start-of-frame segment."""
    i = 2
    while i + 4 <= len(data):
        if data[i] != 0xFF:
            i += 1
            continue
        m = data[i + 1]
        if m in (0xFF, 0x01) or 0xD0 <= m <= 0xD8:
            i += 2 if m != 0xFF else 1
            continue
        n = int.from_bytes(data[i + 2 : i + 4], "big")
        if 0xC0 <= m <= 0xCF and m not in (0xC4, 0xC8, 0xCC):
            return m, data[i + 4] if i + 4 < len(data) else None
        i += 2 + n
    return None, None


def jpeg_precision(data):
    return jpeg_frame(data)[1]


def jpeg_is_lossless(data):
    return jpeg_frame(data)[0] in (0xC3, 0xC7, 0xCB, 0xCF)


def ref_tiff(path):
    import tifffile

    try:
        with tifffile.TiffFile(str(path)) as t:
            page = t.pages.first
            a = page.asarray()
            photometric = int(page.photometric)
            fmt = int(page.sampleformat)
            bits = page.bitspersample
            planar = int(page.planarconfig)
            cmap = page.colormap
            spp = page.samplesperpixel
            tags = page.tags
            compression = int(page.compression)
            if planar == 2 and a.ndim == 3 and spp > 1:
                a = np.moveaxis(a, 0, -1)
            if a.ndim == 4:  # a depth axis (SGI's image depth): the first slice
                a = a[0]
    except Exception as e:  # noqa: BLE001
        raise Refused(f"{type(e).__name__}: {e}") from None
    try:
        v, domain, tol = tiff_rgb(a, photometric, fmt, bits, cmap, spp, tags)
        # JPEG-compressed TIFF (old and new style) is lossy: decoders differ by their IDCTs'
        # rounding and chroma upsampling, as for JPEG files.
        return v, domain, ("lossy" if compression in (6, 7) else tol)
    except Exception as e:  # noqa: BLE001 - a fuzzed file's tags that make no sense
        raise Refused(f"{type(e).__name__}: {e}") from None


def tiff_rgb(a, photometric, fmt, bits, cmap, spp, tags):
    """The reference's conversion of TIFF samples to RGB (see the module's documentation)."""
    a = np.asarray(a)
    if isinstance(bits, tuple):
        bits = bits[0]
    if a.ndim == 3 and a.shape[-1] != spp and a.shape[0] == spp:
        a = np.moveaxis(a, 0, -1)
    if fmt == 3:  # IEEE float
        domain, tol = "linear", "float"
        v = a.astype(np.float64)
    else:
        domain, tol = "encoded", 1.01 / 255
        if a.dtype == bool:
            v = a.astype(np.float64)
        elif fmt == 2:  # signed
            n = a.dtype.itemsize * 8 if bits > 8 * a.dtype.itemsize else bits
            v = (a.astype(np.float64) + 2 ** (n - 1)) / (2**n - 1)
        else:
            v = a.astype(np.float64) / (2**bits - 1)
    if photometric in (0, 1) and v.ndim == 3:
        # Grey, whatever the number of samples: libtiff reads the first sample of a min-is-black
        # or min-is-white image with more samples as the grey level and the rest as extra
        # samples ("Defining non-color channels as ExtraSamples", and `tiff2rgba` of image-tiff's
        # seq-3c-i8 is grey), as ImageMagick does.
        v = v[:, :, :1]
    if photometric == 0:  # min-is-white
        v = 1 - v if fmt != 3 else v
    elif photometric == 3 and cmap is not None:  # palette
        idx = a.astype(np.int64)
        if idx.ndim == 3:
            idx = idx[:, :, 0]
        m = np.asarray(cmap, dtype=np.float64) / 65535
        v = np.moveaxis(m[:, np.clip(idx, 0, m.shape[1] - 1)], 0, -1)
    elif photometric == 5:  # separated (CMYK)
        if v.ndim == 3 and v.shape[2] >= 4:
            k = v[:, :, 3:4]
            v = (1 - v[:, :, :3]) * (1 - k)
        elif v.ndim == 3:
            v = 1 - v[:, :, :3]
    elif photometric == 6 and a.dtype == np.uint8 and "JPEGTables" not in tags:
        # tifffile hands uncompressed YCbCr over as it is stored only when not subsampled.
        coef = tags["YCbCrCoefficients"].value if "YCbCrCoefficients" in tags else (0.299, 0.587, 0.114)
        lr, lg, lb = (float(c) for c in coef)
        y, cb, cr = (v[:, :, i] * 255 for i in range(3))
        rbw = tags["ReferenceBlackWhite"].value if "ReferenceBlackWhite" in tags else None
        if rbw is not None:
            rbw = [float(x) for x in rbw]
            y = (y - rbw[0]) * 255 / (rbw[1] - rbw[0])
            cb = (cb - rbw[2]) * 127 / (rbw[3] - rbw[2])
            cr = (cr - rbw[4]) * 127 / (rbw[5] - rbw[4])
        else:
            cb, cr = cb - 128, cr - 128
        r = cr * (2 - 2 * lr) + y
        b = cb * (2 - 2 * lb) + y
        g = (y - lb * b - lr * r) / lg
        v = np.clip(np.stack([r, g, b], axis=2) / 255, 0, 1)
    return rgb3(v), domain, tol


def ref_exr(path):
    import OpenEXR

    try:
        f = OpenEXR.File(str(path), separate_channels=True)
        parts = [p for p in f.parts if p.header.get("type") not in (OpenEXR.deepscanline, OpenEXR.deeptile)]
    except Exception as e:  # noqa: BLE001
        raise Refused(f"{type(e).__name__}: {e}") from None

    def framed(part, v, kind):
        # The display window is the image; the data window's pixels go where it puts them,
        # the rest is 0 (as `image` and OpenEXR's viewers frame it).
        (dx0, dy0), (dx1, dy1) = part.header["displayWindow"]
        (ax0, ay0), _ = part.header["dataWindow"]
        out = np.zeros((dy1 - dy0 + 1, dx1 - dx0 + 1, 3))
        h, w = v.shape[:2]
        x0, y0 = ax0 - dx0, ay0 - dy0
        sx0, sy0 = max(0, -x0), max(0, -y0)
        ex, ey = min(w, out.shape[1] - x0), min(h, out.shape[0] - y0)
        if ex > sx0 and ey > sy0:
            out[y0 + sy0 : y0 + ey, x0 + sx0 : x0 + ex] = v[sy0:ey, sx0:ex]
        return out, "linear", kind

    # As `image` picks: the first part with R, G and B; else Y with RY and BY; else Y.
    for part in parts:
        ch = part.channels
        if all(c in ch for c in "RGB"):
            v = np.stack([ch[c].pixels.astype(np.float64) for c in "RGB"], axis=2)
            return framed(part, v, "float")
    for part in parts:
        ch = part.channels
        if "Y" in ch and "RY" in ch and "BY" in ch:
            y = ch["Y"].pixels.astype(np.float64)
            h, w = y.shape

            def up(c):
                p = ch[c].pixels.astype(np.float64)
                sx, sy = ch[c].xSampling, ch[c].ySampling
                p = np.repeat(np.repeat(p, sy, axis=0), sx, axis=1)
                return p[:h, :w]

            ry, by = up("RY"), up("BY")
            r = (ry + 1) * y
            b = (by + 1) * y
            g = (y - 0.2126 * r - 0.0722 * b) / 0.7152
            return framed(part, np.stack([r, g, b], axis=2), "chroma")
    for part in parts:
        ch = part.channels
        if "Y" in ch:
            y = ch["Y"].pixels.astype(np.float64)
            return framed(part, np.repeat(y[:, :, None], 3, axis=2), "float")
    raise Refused("no RGB, Y or Y/RY/BY part that is not deep")


def ref_mesh(path):
    """The triangle count by trimesh; for a PLY trimesh refuses, by plyfile (a second,
    independent reader: trimesh refuses some valid files, such as a face element before the
    vertices)."""
    import trimesh

    try:
        m = trimesh.load(str(path), force="mesh", process=False)
        return len(m.faces) if hasattr(m, "faces") else 0
    except Exception as e:  # noqa: BLE001
        first = f"{type(e).__name__}: {e}"
    if str(path).lower().endswith(".ply"):
        import plyfile

        try:
            ply = plyfile.PlyData.read(str(path))
            if "face" not in ply or "vertex" not in ply:
                return 0
            face = ply["face"]
            name = next(p.name for p in face.properties if p.name in ("vertex_indices", "vertex_index"))
            return int(sum(max(len(f) - 2, 0) for f in face[name]))
        except Exception as e:  # noqa: BLE001
            first += f"; plyfile: {type(e).__name__}: {e}"
    raise Refused(first)


REFERENCES = {"png": ref_png, "jpeg": ref_jpeg, "tiff": ref_tiff, "exr": ref_exr}


# ---------- texplore ----------


def read_exr(path):
    import OpenEXR

    f = OpenEXR.File(str(path), separate_channels=True)
    ch = f.parts[0].channels
    return np.stack([ch[c].pixels.astype(np.float64) for c in "RGB"], axis=2)


def compare(ours, ref, domain, tol):
    """'' when they agree, else what differs."""
    if ours.shape != ref.shape:
        return f"size {ours.shape[1]}x{ours.shape[0]}, reference {ref.shape[1]}x{ref.shape[0]}"
    if domain == "encoded":
        a = srgb_encode(ours)
        b = np.clip(ref, 0, 1)
    else:
        a = ours
        b = np.where(np.isfinite(ref) & (ref >= 0), ref, 0.0)
    d = np.abs(a - b)
    worst = np.unravel_index(np.argmax(d), d.shape) if d.size else (0, 0, 0)
    where = f"pixel ({worst[1]}, {worst[0]}): {a[worst[0], worst[1]]} vs {b[worst[0], worst[1]]}"
    if tol == "lossy":
        # IDCT and upsampling differ between decoders by a level or two, far more at none.
        if d.max() * 255 > 12 or d.mean() * 255 > 1.0:
            return f"max {d.max() * 255:.1f}/255, mean {d.mean() * 255:.2f}/255 at {where}"
        return ""
    if tol == "float":
        lim = 1e-3 * np.maximum(np.abs(b), 1e-3)
        if (d > lim).any():
            return f"{int((d > lim).sum())} samples differ, worst at {where}"
        return ""
    if tol == "chroma":
        # Chroma is stored at a quarter of the samples; decoders upsample it differently.
        lum = lambda x: x @ np.array([0.2126, 0.7152, 0.0722])
        dl = np.abs(lum(a) - lum(b)) / np.maximum(lum(np.abs(b)), 1e-3)
        rel = d.mean() / max(np.abs(b).mean(), 1e-6)
        if np.median(dl) > 1e-2 or rel > 0.1:
            return f"luminance median rel. error {np.median(dl):.3g}, RGB mean rel. error {rel:.3g}"
        return ""
    if d.max() > tol:
        return f"max {d.max() * 255:.2f}/255 at {where}"
    return ""


# Folders of damaged files kept to test that a decoder survives them (jpeg-decoder's crash
# tests, image-tiff's and exrs's fuzzer finds): judged on surviving alone (no crash, hang or
# memory escape), whatever either decoder makes of the damage.
SURVIVAL = ("crashtest", "fuzz_images", "fuzzed")
# Files their suite names as invalid (`invalid`, `malformed`, `_err`): refusing them is right
# even where the reference is lenient.
INVALID = ("invalid", "malformed", "_err_")

# Invalid by their format's text, read by a lenient reference: a refusal is right, and so is a
# reading that agrees with the reference. Each with the reason.
KNOWN_INVALID = {
    "assimp/test/models/OBJ/number_formats.obj": "'3.1+e2' is not a number",
    "assimp/test/models/PLY/Wuson.ply": "a header line that is neither a keyword nor a comment",
    "trimesh/models/fuze_ascii.ply": "face lines hold 6 values more than the header declares",
    "assimp/test/models-nonbsd/PLY/ant-half.ply": "declares 912 faces and holds 259 (truncated)",
    "tinyobjloader/models/issue-140-zero-face-idx.obj": "face index 0 (OBJ indices start at 1)",
    "image-png/tests/bugfixes/x_consecutive_idat.png": "a gAMA chunk between two IDAT chunks (PNG: "
    "'multiple IDAT chunks shall be consecutive'); image-png's results list it as an expected failure",
}

MAGIC = [
    (b"\x89PNG", "png"),
    (b"\xff\xd8", "jpeg"),
    (b"II*\x00", "tiff"),
    (b"MM\x00*", "tiff"),
    (b"II+\x00", "tiff"),
    (b"MM\x00+", "tiff"),
    (b"v/1\x01", "exr"),
]


def sniff(path, kind):
    """The image format from the file's first bytes (texplore reads by content, so a PNG named
    .jpg is a PNG), else the suite's."""
    with open(path, "rb") as f:
        head = f.read(8)
    return next((k for m, k in MAGIC if head.startswith(m)), kind)


def judge(texplore, path, kind, tmp, rel):
    survival = any(part in SURVIVAL for part in Path(rel).parts)
    invalid = any(w in rel.lower() for w in INVALID) or rel in KNOWN_INVALID
    if kind == "mesh":
        code, out, err, rss = run([texplore, "mesh-info", str(path), "--json"])
    else:
        kind = sniff(path, kind)
        out_exr = Path(tmp) / (str(abs(hash(str(path)))) + ".exr")
        code, out, err, rss = run([texplore, "image-info", str(path), "-o", str(out_exr)])
    err = err.strip().replace("\n", " | ")
    if code == 1 and "texture budget" in err:
        # Refused from the header by a stated limit (1 GiB of texels): not a decoding question.
        return "over-budget", "", rss, err
    if code is None:
        return "timeout", f"over {TIMEOUT:.0f} s", rss, err
    if code not in (0, 1) or "panicked" in err:
        return "crash", f"exit {code}", rss, err
    if rss > MAX_PEAK_MIB:
        return "memory", f"peak {rss:.0f} MiB", rss, err
    if code != 0 and not err.startswith("error: ") and "error:" not in err:
        return "unclear", "refused without an error message", rss, err
    try:
        ref = ref_mesh(path) if kind == "mesh" else REFERENCES[kind](path)
    except Refused as e:
        if code == 0 and survival:
            return "survived", f"decoded what the reference refuses ({e})"[:200], rss, err
        if code == 0 and not invalid:
            return "accepts-corrupt", f"reference: {e}"[:200], rss, err
        return "both-refuse", "", rss, err
    except MemoryError:
        return ("both-refuse" if code != 0 else "survived"), "too large for the reference", rss, err
    except Exception as e:  # noqa: BLE001 - the reference failing on a damaged file
        if code == 0 and not survival:
            return "accepts-corrupt", f"reference: {type(e).__name__}: {e}"[:200], rss, err
        return ("both-refuse" if code != 0 else "survived"), "", rss, err
    if code != 0:
        if survival:
            return "survived", "refused", rss, err
        if invalid:
            return "refuses-invalid", "", rss, err
        if re.search(r"(is|are) not supported\W*$", err):
            return "unsupported", "", rss, err
        if kind == "mesh" and ref == 0:
            # Nothing to render: a point cloud, lines only, or an empty file.
            return "no-surface", "", rss, err
        return "refuses-valid", "", rss, err
    if kind == "mesh":
        import json

        tri = json.loads(out)["triangles"]
        if tri != ref:
            return ("survived" if survival else "wrong-size"), f"{tri} triangles, reference {ref}", rss, err
        return "match", "", rss, err
    v, domain, tol = ref
    ours = read_exr(out_exr)
    out_exr.unlink(missing_ok=True)
    diff = compare(ours, v, domain, tol)
    if diff and survival:
        return "survived", diff, rss, err
    if diff:
        return ("wrong-size" if diff.startswith("size") else "wrong-pixels"), diff, rss, err
    return "match", "", rss, err


BAD = {
    "wrong-size",
    "wrong-pixels",
    "refuses-valid",
    "accepts-corrupt",
    "crash",
    "timeout",
    "memory",
    "unclear",
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--suites", required=True)
    ap.add_argument("--texplore", required=True)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="")
    ap.add_argument("--csv")
    ap.add_argument("--show", default="bad", help="bad, unsupported, all or none")
    args = ap.parse_args()
    texplore = str(Path(args.texplore).resolve())
    only = set(filter(None, args.only.split(",")))
    todo = [(p, k) for p, k in files(args.suites) if not only or k in only]
    results = []
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp, futures.ThreadPoolExecutor(args.jobs) as pool:
        jobs = {
            pool.submit(judge, texplore, p, k, tmp, str(Path(p).relative_to(args.suites))): (p, k)
            for p, k in todo
        }
        for j in futures.as_completed(jobs):
            p, k = jobs[j]
            try:
                verdict, detail, rss, err = j.result()
            except Exception as e:  # noqa: BLE001 - a harness bug must not hide the rest
                verdict, detail, rss, err = "harness-error", repr(e)[:200], 0, ""
            results.append((str(Path(p).relative_to(args.suites)), k, verdict, detail, rss, err))
    results.sort()
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["file", "kind", "verdict", "detail", "peak_mib", "texplore_stderr"])
            for r in results:
                w.writerow([r[0], r[1], r[2], r[3], f"{r[4]:.0f}", r[5][:300]])
    for r in results:
        bad = r[2] in BAD or r[2] == "harness-error"
        if args.show == "all" or (args.show == "bad" and bad) or (
            args.show == "unsupported" and r[2] == "unsupported"
        ):
            print(f"{r[2]:16} {r[0]}: {r[3]} [{r[5][:160]}]")
    kinds = sorted({r[1] for r in results})
    verdicts = sorted({r[2] for r in results})
    print(f"\n{len(results)} files in {time.time() - t0:.0f} s, peak {max(r[4] for r in results):.0f} MiB")
    print("kind      " + " ".join(f"{v:>15}" for v in verdicts))
    for k in kinds:
        row = [sum(1 for r in results if r[1] == k and r[2] == v) for v in verdicts]
        print(f"{k:9} " + " ".join(f"{n:>15}" for n in row))
    bad = sum(1 for r in results if r[2] in BAD or r[2] == "harness-error")
    uns = sum(1 for r in results if r[2] == "unsupported")
    print(f"mishandled: {bad}; refused as not supported: {uns}")


if __name__ == "__main__":
    main()
