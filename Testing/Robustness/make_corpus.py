#!/usr/bin/env python3
"""Writes a corpus of damaged and extreme input files for shockfilter.

    make_corpus.py OUTDIR SHOCKFILTER

Every kind of file is one entry of OUTDIR/corpus.json: the file, the command
that reads it (image, surface or sharpen), what must happen ("refuse": exit 2
with one line; "ok": exit 0; "any": either) and, for the meshes at extreme
scales, the scale (their result must be the unit mesh's result, scaled).
Valid small files of every format are written here byte by byte (standard
library only), then damaged: truncated, bytes flipped, header fields set to
zero, negative or huge values, lengths and counts that lie. The JPEG base is
made by the program itself (shockfilter image base.png base.jpg).
run_corpus.py runs them.
"""
import json
import os
import struct
import subprocess
import sys
import zlib

OUT = sys.argv[1]
PROGRAM = sys.argv[2]
KINDS = []
W, H = 24, 16


def add(name, data, command, expect, **extra):
    path = os.path.join(OUT, name)
    with open(path, "wb") as f:
        f.write(data)
    KINDS.append(dict(name=name, command=command, expect=expect, **extra))


# --- PNG ---------------------------------------------------------------------------
def chunk(kind, data, crc=None):
    crc = zlib.crc32(kind + data) if crc is None else crc
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc & 0xFFFFFFFF)


def ihdr(w=W, h=H, depth=8, colour=2, comp=0, filt=0, interlace=0):
    return struct.pack(">IIBBBBB", w, h, depth, colour, comp, filt, interlace)


def rows(w=W, h=H, channels=3, depth=8, filter_byte=0):
    row = bytes([filter_byte]) + bytes((x * 9 + 40) % 256 for x in range(w * channels * depth // 8))
    return row * h


SIG = b"\x89PNG\r\n\x1a\n"


def png(header=None, idat=None, extra=b"", end=True):
    header = ihdr() if header is None else header
    idat = zlib.compress(rows()) if idat is None else idat
    data = SIG + chunk(b"IHDR", header) + extra + chunk(b"IDAT", idat)
    return data + (chunk(b"IEND", b"") if end else b"")


def png_kinds():
    good = png()
    add("png_valid.png", good, "image", "ok")
    add("png_grey16.png", png(ihdr(colour=0, depth=16), zlib.compress(rows(channels=1, depth=16))), "image", "ok")
    add("png_grey_alpha.png", png(ihdr(colour=4), zlib.compress(rows(channels=2))), "image", "ok")
    add("png_rgba.png", png(ihdr(colour=6), zlib.compress(rows(channels=4))), "image", "ok")
    add("png_text_chunk.png", png(extra=chunk(b"tEXt", b"Comment\0hello")), "image", "ok")
    # CRC damage in every chunk kind.
    for at, label in [(8 + 8 + 13, "ihdr"), (len(good) - 12 - 4 - 1, "idat"), (len(good) - 1, "iend")]:
        bad = bytearray(good)
        bad[at] ^= 0xFF
        add("png_bad_crc_%s.png" % label, bytes(bad), "image", "refuse")
    add("png_bad_crc_text.png", png(extra=chunk(b"tEXt", b"a\0b", crc=1)), "image", "refuse")
    # Image data damaged, with correct CRCs.
    compressed = bytearray(zlib.compress(rows()))
    for offset in (2, len(compressed) // 2, len(compressed) - 5):
        bad = bytearray(compressed)
        bad[offset] ^= 0x5A
        add("png_bad_deflate_%d.png" % offset, png(idat=bytes(bad)), "image", "refuse")
    add("png_not_zlib.png", png(idat=b"\x00" * 40), "image", "refuse")
    add("png_bad_filter_5.png", png(idat=zlib.compress(rows(filter_byte=5))), "image", "refuse")
    add("png_bad_filter_255.png", png(idat=zlib.compress(rows(filter_byte=255))), "image", "refuse")
    add("png_short_idat.png", png(idat=zlib.compress(rows()[: len(rows()) // 2])), "image", "refuse")
    add("png_long_idat.png", png(idat=zlib.compress(rows() + rows())), "image", "refuse")
    add("png_empty_idat.png", png(idat=b""), "image", "refuse")
    add("png_no_idat.png", SIG + chunk(b"IHDR", ihdr()) + chunk(b"IEND", b""), "image", "refuse")
    add("png_split_idat.png", SIG + chunk(b"IHDR", ihdr()) + chunk(b"IDAT", zlib.compress(rows())[:20]) +
        chunk(b"tEXt", b"a\0b") + chunk(b"IDAT", zlib.compress(rows())[20:]) + chunk(b"IEND", b""), "image", "refuse")
    split = zlib.compress(rows())
    add("png_idat_in_pieces.png", SIG + chunk(b"IHDR", ihdr()) + chunk(b"IDAT", split[:7]) +
        chunk(b"IDAT", split[7:30]) + chunk(b"IDAT", split[30:]) + chunk(b"IEND", b""), "image", "ok")
    # IHDR fields.
    for w, h in [(0, H), (W, 0), (0, 0), (2**31 - 1, 1), (1, 2**31 - 1), (2**32 - 1, 2**32 - 1), (1000001, 1)]:
        add("png_size_%dx%d.png" % (w, h), png(ihdr(w, h)), "image", "refuse")
    for depth, colour in [(3, 0), (8, 1), (4, 2), (16, 3), (1, 4), (8, 5), (2, 6), (0, 0), (32, 2), (8, 7)]:
        add("png_depth%d_colour%d.png" % (depth, colour), png(ihdr(depth=depth, colour=colour)), "image", "refuse")
    add("png_compression_1.png", png(ihdr(comp=1)), "image", "refuse")
    add("png_filter_method_1.png", png(ihdr(filt=1)), "image", "refuse")
    add("png_interlace_2.png", png(ihdr(interlace=2)), "image", "refuse")
    add("png_interlace_flat_data.png", png(ihdr(interlace=1)), "image", "refuse")
    add("png_ihdr_12_bytes.png", SIG + chunk(b"IHDR", ihdr()[:12]) + chunk(b"IDAT", zlib.compress(rows())) +
        chunk(b"IEND", b""), "image", "refuse")
    add("png_no_ihdr.png", SIG + chunk(b"IDAT", zlib.compress(rows())) + chunk(b"IEND", b""), "image", "refuse")
    add("png_two_ihdr.png", png(extra=chunk(b"IHDR", ihdr())), "image", "refuse")
    add("png_palette_without_plte.png", png(ihdr(colour=3), zlib.compress(rows(channels=1))), "image", "refuse")
    big = bytes([0]) + bytes((x * 7) % 256 for x in range(3000 * 3))
    add("png_large_for_memory.png", png(ihdr(3000, 3000), zlib.compress(big * 3000, 9)), "image", "memory")
    add("png_huge_declared.png", png(ihdr(20000, 20000, colour=0), zlib.compress(b"\0" * 20001 * 4)), "image", "refuse")
    add("png_chunk_length_huge.png", SIG + struct.pack(">I", 0x7FFFFFF0) + b"IHDR" + ihdr() + b"\0" * 4, "image", "refuse")
    add("png_chunk_length_negative.png", SIG + struct.pack(">I", 0xFFFFFFFF) + b"IHDR" + ihdr(), "image", "refuse")
    add("png_no_iend.png", png(end=False), "image", "refuse")
    for cut in (4, 8, 12, 20, 33, len(good) // 2, len(good) - 13, len(good) - 1):
        add("png_truncated_%d.png" % cut, good[:cut], "image", "refuse")
    add("png_wrong_signature.png", b"\x89PNX" + good[4:], "image", "refuse")
    add("png_text_file.png", b"hello, I am not a picture\n", "image", "refuse")
    add("png_empty.png", b"", "image", "refuse")


# --- PNM, BMP -----------------------------------------------------------------------
def pnm_kinds():
    pixels = bytes((i * 7) % 256 for i in range(W * H * 3))
    add("pnm_valid.ppm", b"P6\n%d %d\n255\n" % (W, H) + pixels, "image", "ok")
    add("pnm_valid_comments.pgm", b"P5\n# made by a test\n%d %d # size\n255\n" % (W, H) + pixels[: W * H], "image", "ok")
    for name, header in [("hang_x", b"P6\nx"), ("hang_no_maxval", b"P5\n4 4 \n"), ("hang_negative", b"P6\n-5 x"),
                         ("only_magic", b"P6"), ("magic_newline", b"P6\n"), ("letters", b"P6\nab cd\n255\n"),
                         ("zero_size", b"P6\n0 0\n255\n"), ("maxval_0", b"P5\n4 4\n0\n" + b"\0" * 16),
                         ("maxval_16bit", b"P5\n4 4\n65535\n" + b"\0" * 32), ("ascii_p3", b"P3\n2 2\n255\n1 2 3 4 5 6 7 8 9 10 11 12\n"),
                         ("p7", b"P7\nWIDTH 2\n"), ("huge", b"P6\n65000 65000\n255\n" + b"\0" * 100),
                         ("overflow", b"P6\n99999999999999999999 2\n255\n"), ("truncated_data", b"P6\n%d %d\n255\n" % (W, H) + pixels[:100]),
                         ("comment_forever", b"P6\n# " + b"x" * 5000), ("no_space_before_data", b"P5\n4 4\n255")]:
        add("pnm_%s.ppm" % name, header, "image", "refuse")


def bmp(w=W, h=H, bits=24, offset=54, info=40, data=None, planes=1, compression=0):
    row = ((w * bits + 31) // 32) * 4 if w > 0 and bits > 0 else 0
    data = bytes((i * 3) % 256 for i in range(row * abs(h))) if data is None else data
    header = b"BM" + struct.pack("<IHHI", offset + len(data), 0, 0, offset)
    if info == 12:  # the OS/2 BITMAPCOREHEADER: 16-bit sizes
        dib = struct.pack("<IHHHH", info, w & 0xFFFF, h & 0xFFFF, planes, bits)
    else:
        dib = struct.pack("<IiiHHIIiiII", info, w, h, planes, bits, compression, len(data), 2835, 2835, 0, 0)
    return header + dib + data


def bmp_kinds():
    add("bmp_valid.bmp", bmp(), "image", "ok")
    add("bmp_valid_core_header.bmp", bmp(info=12, offset=26), "image", "ok")
    grey_table = b"".join(bytes((i, i, i, 0)) for i in range(256))
    add("bmp_valid_8bit.bmp", bmp(bits=8, offset=54 + 1024, data=grey_table + bytes(((W + 3) // 4 * 4) * H)),
        "image", "ok")
    add("bmp_top_down.bmp", bmp(h=-H), "image", "any")
    for name, data in [("huge", bmp(65000, 65000, data=b"\0" * 64)), ("zero_width", bmp(0, H, data=b"")),
                       ("zero_height", bmp(W, 0, data=b"")), ("negative_width", bmp(-W, H, data=b"\0" * 64)),
                       ("int_min_height", bmp(W, -2**31, data=b"\0" * 64)), ("truncated_data", bmp()[:100]),
                       ("truncated_header", bmp()[:20]), ("bits_0", bmp(bits=0, data=b"\0" * 64)),
                       ("bits_7", bmp(bits=7, data=b"\0" * 64)), ("offset_beyond", bmp(offset=10**6)),
                       ("not_bm", b"XM" + bmp()[2:]), ("info_size_0", bmp(info=0)),
                       # the fuzz search's 30-byte file: an 8-bit 40-byte header ending after the bit count
                       # (VTK 9.2 read it through a null pointer: no colour table)
                       ("header_ends_after_bits", bmp(bits=8)[:30]),
                       ("info_size_124", bmp(info=124)), ("info_size_108", bmp(info=108)),
                       ("compressed_rle8", bmp(bits=8, compression=1)),
                       ("core_negative_width", bmp(w=0x8000, info=12, offset=26, data=b"\0" * 64)),
                       ("offset_inside_header", bmp(offset=20))]:
        add("bmp_%s.bmp" % name, data, "image", "refuse")


# --- TIFF ---------------------------------------------------------------------------
def tiff(w=W, h=H, spp=3, bits=8, strip_offset=None, entries=None, next_ifd=0, data=None, strip_bytes=None):
    data = bytes((i * 5) % 256 for i in range(w * h * spp * bits // 8)) if data is None else data
    strip_offset = 8 if strip_offset is None else strip_offset
    strip_bytes = len(data) if strip_bytes is None else strip_bytes
    if entries is None:
        entries = [(256, 4, 1, w), (257, 4, 1, h), (258, 3, 1, bits), (259, 3, 1, 1), (262, 3, 1, 2 if spp == 3 else 1),
                   (273, 4, 1, strip_offset), (277, 3, 1, spp), (278, 4, 1, h), (279, 4, 1, strip_bytes)]
    ifd = struct.pack("<H", len(entries))
    for tag, kind, count, value in entries:
        ifd += struct.pack("<HHI", tag, kind, count) + (struct.pack("<HH", value, 0) if kind == 3 else struct.pack("<I", value))
    ifd_offset = 8 + len(data)
    ifd += struct.pack("<I", next_ifd if next_ifd >= 0 else ifd_offset)
    return b"II*\0" + struct.pack("<I", ifd_offset) + data + ifd


def tiff_kinds():
    add("tiff_valid.tif", tiff(), "image", "ok")
    add("tiff_grey.tif", tiff(spp=1), "image", "ok")
    for name, data, expect in [("huge", tiff(65000, 65000, data=b"\0" * 64, strip_bytes=2**32 - 1), "refuse"),
                               ("zero_width", tiff(0, H, data=b""), "refuse"), ("zero_height", tiff(W, 0, data=b""), "refuse"),
                               ("ifd_beyond_file", b"II*\0" + struct.pack("<I", 10**6) + b"\0" * 32, "refuse"),
                               ("ifd_loop", tiff(next_ifd=-1), "any"), ("strip_beyond_file", tiff(strip_offset=10**6), "any"),
                               ("strip_bytes_huge", tiff(strip_bytes=2**31), "any"), ("truncated_half", tiff()[: len(tiff()) // 2], "refuse"),
                               ("truncated_header", tiff()[:6], "refuse"), ("bits_0", tiff(bits=0, data=b"\0" * 64), "any"),
                               ("spp_0", tiff(spp=0, data=b"\0" * 64), "any"), ("spp_100", tiff(spp=100, data=b"\0" * 64), "any"),
                               ("width_twice", tiff(entries=[(256, 4, 1, 2**24), (257, 4, 1, 255), (258, 3, 1, 8),
                                   (273, 4, 1, 8), (277, 3, 1, 1), (279, 4, 1, 64), (256, 4, 1, W)]), "refuse"),
                               ("no_entries", b"II*\0" + struct.pack("<I", 8) + struct.pack("<HI", 0, 0), "refuse"),
                               ("bigtiff", b"II+\0" + b"\0" * 32, "refuse"), ("compression_unknown", tiff(entries=[
                                   (256, 4, 1, W), (257, 4, 1, H), (258, 3, 1, 8), (259, 3, 1, 60000), (273, 4, 1, 8),
                                   (277, 3, 1, 1), (279, 4, 1, W * H)]), "any")]:
        add("tiff_%s.tif" % name, data, "image", expect)
    for name, data in tiff_vtk_overflow_kinds():
        add("tiff_%s.tif" % name, data, "image", "refuse")


def tiff_vtk_overflow_kinds():
    """TIFF files VTK 9.2's reader writes or reads past its buffers for (the fuzz search's heap corruption)."""
    grey_alpha = bytes((i * 5) % 256 for i in range(W * H * 2))

    def entries(spp, photometric, compression, strip_bytes, w=W, offset=8):
        return [(256, 4, 1, w), (257, 4, 1, H), (258, 3, 1, 8), (259, 3, 1, compression), (262, 3, 1, photometric),
                (273, 4, 1, offset), (277, 3, 1, spp), (278, 4, 1, H), (279, 4, 1, strip_bytes)]
    # 2 samples per pixel read through libtiff's RGBA interface (old deflate code): 4 bytes per pixel into 3
    deflated = zlib.compress(grey_alpha)
    yield "two_samples_rgba_path", tiff(data=deflated, entries=entries(2, 1, 32946, len(deflated)))
    yield "two_samples_grey_alpha", tiff(data=grey_alpha, entries=entries(2, 1, 1, len(grey_alpha)))
    yield "rgb_one_sample", tiff(spp=1, entries=entries(1, 2, 1, W * H))
    # two pages, the second twice as wide: VTK reads it with the first page's size
    first, second = bytes(W * H), bytes(2 * W * H)
    ifd1 = 8 + len(first) + len(second)
    def ifd(items, next_ifd):
        out = struct.pack("<H", len(items))
        for tag, kind, count, value in items:
            out += struct.pack("<HHI", tag, kind, count) + (struct.pack("<HH", value, 0) if kind == 3 else struct.pack("<I", value))
        return out + struct.pack("<I", next_ifd)
    page1 = entries(1, 1, 1, len(first))
    page2 = entries(1, 1, 1, len(second), w=2 * W, offset=8 + len(first))
    ifd2 = ifd1 + len(ifd(page1, 0))
    yield "pages_differ", b"II*\0" + struct.pack("<I", ifd1) + first + second + ifd(page1, ifd2) + ifd(page2, 0)
    # a second page libtiff refuses (RowsPerStrip with 2 values): VTK reads it anyway
    # (the fuzz search's division by zero inside libtiff)
    page2 = entries(1, 1, 1, len(first))[:7] + [(278, 4, 2, H), (279, 4, 1, len(first))]
    ifd2 = ifd1 + len(ifd(page1, 0))
    yield "page_libtiff_refuses", b"II*\0" + struct.pack("<I", ifd1) + first + second + ifd(page1, ifd2) + ifd(page2, 0)


# --- VTK image files ----------------------------------------------------------------
def legacy_image(dims="4 3 1", count=12, values=None):
    values = " ".join(str(i) for i in range(count)) if values is None else values
    return ("# vtk DataFile Version 3.0\nimage\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS %s\nORIGIN 0 0 0\n"
            "SPACING 1 1 1\nPOINT_DATA %d\nSCALARS v float 1\nLOOKUP_TABLE default\n%s\n" % (dims, count, values)).encode()


def vti(extent="0 3 0 2 0 0", values=" ".join(str(i) for i in range(12)), count=12, spacing="1 1 1"):
    return ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
            '<ImageData WholeExtent="%s" Origin="0 0 0" Spacing="%s">\n<Piece Extent="%s">\n'
            '<PointData Scalars="v"><DataArray type="Float32" Name="v" format="ascii" NumberOfTuples="%d">%s</DataArray>'
            '</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n' % (extent, spacing, extent, count, values)).encode()


def vti_appended(extent="0 3 0 2 0 0", piece=None, count=12):
    """A .vti with raw appended Float32 data (a UInt32 byte count, then the values)."""
    import struct
    data = struct.pack("<I", 4 * count) + b"".join(struct.pack("<f", float(i)) for i in range(count))
    return ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian" '
            'header_type="UInt32">\n<ImageData WholeExtent="%s" Origin="0 0 0" Spacing="1 1 1">\n'
            '<Piece Extent="%s">\n<PointData Scalars="v"><DataArray type="Float32" Name="v" '
            'format="appended" offset="0"/></PointData>\n</Piece>\n</ImageData>\n'
            '<AppendedData encoding="raw">\n_' % (extent, piece or extent)).encode() + data + \
        b"\n</AppendedData>\n</VTKFile>\n"


def vtk_image_kinds():
    add("vtk_image_valid.vtk", legacy_image(), "image", "ok")
    for name, data in [("huge", legacy_image("65000 65000 65000")), ("negative", legacy_image("-4 3 1")),
                       ("zero", legacy_image("0 3 1")), ("short_data", legacy_image(values="1 2 3")),
                       ("letters_in_data", legacy_image(values="a b c d e f g h i j k l")),
                       ("truncated", legacy_image()[:90]), ("polydata", b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n"),
                       ("not_vtk", b"hello\n")]:
        add("vtk_image_%s.vtk" % name, data, "image", "refuse")
    add("vti_valid.vti", vti(), "image", "ok")
    add("vti_appended_valid.vti", vti_appended(), "image", "ok")
    full = vti_appended()
    cut = full.index(b"_") + 1
    for fraction in (0.1, 0.5, 0.95):
        # Cut inside the appended data: VTK would read the missing values as zeros.
        add("vti_appended_cut_%d.vti" % int(100 * fraction), full[:cut + int(fraction * (len(full) - cut - 30))],
            "image", "refuse")
    add("vti_piece_covers_half.vti", vti_appended(extent="0 3 0 5 0 0", piece="0 3 0 2 0 0"), "image", "refuse")
    add("vti_flat_axis_spacing_zero.vti", vti(spacing="1 1 0"), "image", "ok")  # a 2D image: z has no edges
    for name, data in [("huge", vti("0 64999 0 64999 0 64999")), ("inverted", vti("3 0 2 0 0 0")),
                       ("short_data", vti(values="1 2 3")), ("truncated", vti()[:150]), ("not_xml", b"hello\n"),
                       ("zero_spacing_along_y", vti(spacing="1 0 1")),
                       ("bad_tag", vti().replace(b"</ImageData>", b"</Image>"))]:
        add("vti_%s.vti" % name, data, "image", "refuse")


def jpeg_kinds():
    base = os.path.join(OUT, "png_valid.png")
    target = os.path.join(OUT, "jpeg_base.jpg")
    subprocess.run([PROGRAM, "image", base, target, "--time", "0"], check=True, capture_output=True)
    with open(target, "rb") as f:
        good = f.read()
    os.remove(target)
    add("jpeg_valid.jpg", good, "image", "ok")
    sof = min(good.find(m) for m in (b"\xff\xc0", b"\xff\xc1", b"\xff\xc2") if m in good)
    for name, h, w in [("huge", 65000, 65000), ("zero_height", 0, W), ("zero_width", H, 0)]:
        bad = bytearray(good)
        bad[sof + 5:sof + 9] = struct.pack(">HH", h, w)
        add("jpeg_%s.jpg" % name, bytes(bad), "image", "refuse")
    bad = bytearray(good)
    bad[sof + 9] = 0  # no components
    add("jpeg_no_components.jpg", bytes(bad), "image", "refuse")
    for cut in (2, 20, sof + 4, len(good) // 2, len(good) - 2):
        add("jpeg_truncated_%d.jpg" % cut, good[:cut], "image", "refuse")
    scan = good.index(b"\xff\xda")
    bad = bytearray(good)
    for k in range(scan + 20, len(good) - 10, 7):
        bad[k] ^= 0xA5
    add("jpeg_scan_garbage.jpg", bytes(bad), "image", "any")
    add("jpeg_no_sof.jpg", good[:2] + good[scan:], "image", "refuse")
    add("jpeg_only_soi.jpg", b"\xff\xd8", "image", "refuse")


# --- Meshes -------------------------------------------------------------------------
def rounded_box(n=6, rounding=0.4):
    """The surface of [-1, 1]^3, n x n squares per face, creases rounded; (points, triangles)."""
    ids, points, triangles = {}, [], []

    def point(lattice):
        if lattice not in ids:
            x = [2.0 * c / n - 1.0 for c in lattice]
            inner = 1.0 - rounding
            near = [min(max(c, -inner), inner) for c in x]
            d = sum((a - b) ** 2 for a, b in zip(x, near)) ** 0.5
            if d > 0:
                x = [b + rounding * (a - b) / d for a, b in zip(x, near)]
            ids[lattice] = len(points)
            points.append(x)
        return ids[lattice]

    for axis in range(3):
        for side in (0, n):
            for u in range(n):
                for v in range(n):
                    def corner(du, dv):
                        lattice = [0, 0, 0]
                        lattice[axis] = side
                        lattice[(axis + 1) % 3] = u + du
                        lattice[(axis + 2) % 3] = v + dv
                        return point(tuple(lattice))
                    q = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]
                    if side == 0:
                        q[1], q[3] = q[3], q[1]
                    triangles += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return points, triangles


def colour(p):
    return (220, 40, 30) if p[0] + 0.3 * p[1] > 0 else (30, 60, 200)


def off(points, triangles, colours=False, scale=1.0):
    lines = ["COFF" if colours else "OFF", "%d %d 0" % (len(points), len(triangles))]
    for p in points:
        text = " ".join(repr(c * scale) for c in p)
        lines.append(text + (" %d %d %d" % colour(p) if colours else ""))
    lines += ["3 %d %d %d" % t for t in triangles]
    return ("\n".join(lines) + "\n").encode()


def ply_ascii(points, triangles, face_lines=None, vertex_lines=None, count=None):
    vertex_lines = vertex_lines or ["%r %r %r %d %d %d" % (tuple(p) + colour(p)) for p in points]
    face_lines = face_lines or ["3 %d %d %d" % t for t in triangles]
    header = ("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (count or len(vertex_lines), len(face_lines)))
    return (header + "\n".join(vertex_lines + face_lines) + "\n").encode()


def ply_binary(points, triangles, vertices=None):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (vertices or len(points), len(triangles))).encode()
    body = b"".join(struct.pack("<fff", *p) for p in points)
    body += b"".join(struct.pack("<Biii", 3, *t) for t in triangles)
    return header + body


def obj(points, triangles, extra=""):
    return ("".join("v %r %r %r\n" % tuple(p) for p in points) + extra +
            "".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in triangles)).encode()


def stl_binary(points, triangles, count=None):
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *points[a], *points[b], *points[c], 0) for a, b, c in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles) if count is None else count) + body


def stl_ascii(points, triangles, value=None):
    facets = "".join("facet normal 0 0 0\nouter loop\n%s endloop\nendfacet\n" % "".join(
        "vertex %s %s %s\n" % tuple(value or repr(c) for c in points[i]) for i in t) for t in triangles)
    return ("solid s\n" + facets + "endsolid s\n").encode()


def vtp(points, triangles, npoints=None, coordinate=None):
    coords = " ".join(coordinate or repr(c) for p in points for c in p)
    conn = " ".join(str(i) for t in triangles for i in t)
    offsets = " ".join(str(3 * (k + 1)) for k in range(len(triangles)))
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n<PolyData>\n'
            '<Piece NumberOfPoints="%d" NumberOfPolys="%d">\n<Points><DataArray type="Float64" NumberOfComponents="3" '
            'format="ascii">%s</DataArray></Points>\n<Polys><DataArray type="Int64" Name="connectivity" format="ascii">%s'
            '</DataArray><DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray></Polys>\n</Piece>\n'
            '</PolyData>\n</VTKFile>\n' % (npoints or len(points), len(triangles), coords, conn, offsets)).encode()


def legacy_mesh(points, triangles, npoints=None, cell_line=None):
    text = "# vtk DataFile Version 3.0\nmesh\nASCII\nDATASET POLYDATA\nPOINTS %d double\n" % (npoints or len(points))
    text += "\n".join("%r %r %r" % tuple(p) for p in points)
    text += "\nPOLYGONS %d %d\n" % (len(triangles), 4 * len(triangles))
    text += "\n".join(cell_line or ["3 %d %d %d" % t for t in triangles]) + "\n"
    return text.encode()


def mesh_kinds():
    P, T = rounded_box()
    add("off_valid.off", off(P, T), "sharpen", "ok")
    add("coff_valid.off", off(P, T, colours=True), "surface", "ok")
    for name, data in [("header_only", b"OFF\n"), ("counts_lie", b"OFF\n8 12 0\n0 0 0\n"), ("huge_counts", b"OFF\n2000000000 2000000000 0\n"),
                       ("negative_count", b"OFF\n-3 1 0\n"), ("face_2_vertices", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
                       ("face_0_vertices", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n"), ("face_missing_vertex", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"),
                       ("nan", b"OFF\n3 1 0\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), ("inf", b"OFF\n3 1 0\ninf 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                       ("overflow", b"OFF\n3 1 0\n1e999 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), ("binary", b"OFF BINARY\n"),
                       ("not_off", b"PLY\n"), ("colour_out_of_range", b"COFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n"),
                       ("extra_data", off(P, T) + b"1 2 3\n"), ("nul_bytes", b"OFF\n3 1 0\n0 0 0\n1 \0 0\n0 1 0\n3 0 1 2\n"),
                       ("truncated", off(P, T)[:400])]:
        add("off_%s.off" % name, data, "sharpen", "refuse")
    add("ply_ascii_valid.ply", ply_ascii(P, T), "surface", "ok")
    # What VTK's readers would change or drop: refused, not read wrong.
    for kind in ("float", "ushort"):
        add("ply_colours_%s.ply" % kind, ply_ascii(P, T).replace(b"property uchar", b"property " + kind.encode()),
            "surface", "refuse")
    strips = ply_ascii(P, T).replace(b"element face", b"element tristrips")
    add("ply_tristrips.ply", strips, "sharpen", "refuse")
    mixed = obj(P, T, extra="vn 0 0 1\n").replace(b"f 1 2 3\n", b"f 1//1 2//1 3//1\n", 1)
    add("obj_mixed_face_forms.obj", mixed, "sharpen", "refuse")
    add("ply_binary_valid.ply", ply_binary(P, T), "sharpen", "ok")
    faces = ["3 %d %d %d" % t for t in T]
    for name, data in [("face_0_vertices", ply_ascii(P, T, face_lines=faces[:-1] + ["0"])),
                       ("face_1_vertex", ply_ascii(P, T, face_lines=faces[:-1] + ["1 0"])),
                       ("face_2_vertices", ply_ascii(P, T, face_lines=faces[:-1] + ["2 0 1"])),
                       ("face_missing_vertex", ply_ascii(P, T, face_lines=faces[:-1] + ["3 0 1 100000"])),
                       ("face_256_vertices", ply_ascii(P, T, face_lines=faces[:-1] + ["256 " + " ".join(["0"] * 256)])),
                       ("nan", ply_ascii(P, T, vertex_lines=["nan 0 0 1 2 3"] + ["%r %r %r 1 2 3" % tuple(p) for p in P[1:]])),
                       ("letters", ply_ascii(P, T, vertex_lines=["a b c 1 2 3"] + ["%r %r %r 1 2 3" % tuple(p) for p in P[1:]])),
                       ("count_lies", ply_ascii(P, T, count=len(P) + 5)), ("count_huge", ply_ascii(P, T, count=2**31 - 2)), ("binary_truncated", ply_binary(P, T)[:-100]),
                       ("binary_huge_count", ply_binary(P, T, vertices=2**31 - 1)), ("no_end_header", b"ply\nformat ascii 1.0\nelement vertex 3\n"),
                       ("no_vertex_element", b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"),
                       ("not_ply", b"plx\n"), ("blank_line", ply_ascii(P, T).replace(b"end_header\n", b"end_header\n\n"))]:
        add("ply_%s.ply" % name, data, "sharpen", "refuse")
    add("obj_valid.obj", obj(P, T), "sharpen", "ok")
    for name, data in [("nan", obj(P, T).replace(b"v ", b"v nan ", 1)), ("inf", obj(P, T).replace(b"v ", b"v inf ", 1)),
                       ("letters", b"v a b c\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), ("face_missing_vertex", obj(P, T, "f 1 2 99999\n")),
                       ("tcoord_missing", obj(P, T, "f 1/5 2/5 3/5\n")), ("normal_missing", obj(P, T, "f 1//7 2//7 3//7\n")),
                       ("long_material", obj(P, T, "usemtl " + "m" * 200 + "\n")), ("no_vertices", b"f 1 2 3\n"),
                       ("negative_id_too_far", obj(P, T, "f -1 -2 -99999\n"))]:
        add("obj_%s.obj" % name, data, "sharpen", "refuse")
    add("stl_binary_valid.stl", stl_binary(P, T), "sharpen", "ok")
    add("stl_ascii_valid.stl", stl_ascii(P, T), "sharpen", "ok")
    for name, data, expect in [("count_huge", stl_binary(P, T, count=2**32 - 1), "refuse"), ("truncated", stl_binary(P, T)[:500], "refuse"),
                               ("short_header", b"\0" * 40, "refuse"), ("ascii_nan", stl_ascii(P, T, value="nan"), "refuse"),
                               ("ascii_letters", stl_ascii(P, T, value="x"), "refuse"), ("empty_solid", b"solid s\nendsolid s\n", "refuse")]:
        add("stl_%s.stl" % name, data, "sharpen", expect)
    add("vtp_valid.vtp", vtp(P, T), "sharpen", "ok")
    add("vtp_blanks_around_count.vtp", vtp(P, T).replace(b'NumberOfPoints="', b'NumberOfPoints=' + b" " * 2000000 + b'"'),
        "sharpen", "ok")  # valid XML; the count check reads it without recursion
    for name, data in [("points_lie", vtp(P, T, npoints=len(P) + 10)), ("points_huge", vtp(P, T, npoints=2000000000)),
                       ("points_negative", vtp(P, T).replace(b'NumberOfPoints="', b'NumberOfPoints="-')),
                                              ("polys_huge", vtp(P, T).replace(b'NumberOfPolys="%d"' % len(T), b'NumberOfPolys="2000000000"')), ("truncated", vtp(P, T)[:300]), ("nan", vtp(P, T, coordinate="nan")),
                       ("not_xml", b"not xml\n"), ("bad_tag", vtp(P, T).replace(b"</PolyData>", b"</Poly>"))]:
        add("vtp_%s.vtp" % name, data, "sharpen", "refuse")
    add("vtk_mesh_valid.vtk", legacy_mesh(P, T), "sharpen", "ok")
    for name, data in [("points_lie", legacy_mesh(P, T, npoints=len(P) + 10)), ("cell_missing_point", legacy_mesh(P, T, cell_line=["3 0 1 99999"] * len(T))),
                       ("letters", legacy_mesh(P, T, cell_line=["3 a b c"] * len(T))), ("truncated", legacy_mesh(P, T)[:200]),
                       ("polygons_huge", legacy_mesh(P, T).replace(b"POLYGONS %d %d" % (len(T), 4 * len(T)), b"POLYGONS 2000000000 8000000000")),
                       ("huge_points", b"# vtk DataFile Version 3.0\nm\nASCII\nDATASET POLYDATA\nPOINTS 2000000000 double\n0 0 0\n")]:
        add("vtk_mesh_%s.vtk" % name, data, "sharpen", "refuse")
    # Extreme scales: the result must be the unit result scaled, or a refusal.
    for exponent in (-300, -200, -100, -30, 30, 80, 100, 200, 300):
        scale = 10.0 ** exponent
        add("scale_1e%d_sharpen.off" % exponent, off(P, T, scale=scale), "sharpen", "scaled", scale=scale, unit="off_valid.off")
        add("scale_1e%d_surface.off" % exponent, off(P, T, colours=True, scale=scale), "surface", "scaled", scale=scale,
            unit="coff_valid.off")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for make in (png_kinds, pnm_kinds, bmp_kinds, tiff_kinds, vtk_image_kinds, jpeg_kinds, mesh_kinds):
        make()
    with open(os.path.join(OUT, "corpus.json"), "w") as f:
        json.dump(KINDS, f, indent=0)
    print("%d kinds of file in %s" % (len(KINDS), OUT))
