#!/usr/bin/env python3
"""Writes the starting corpus of every fuzz target into fuzz/seeds/<target>/: small fixtures of
the repository (tests/fixtures, ../shared/cases when present, graphs/*.ron) and a few hand-made
files for variants the fixtures lack. Standard library only.

Run from the repository root: python3 fuzz/make_seeds.py
The committed corpus (fuzz/corpus/<target>/) was grown from these by the fuzzer and minimised
with `cargo fuzz cmin`; see docs/fuzzing.md.
"""

import glob
import gzip
import lzma
import os
import shutil
import struct
import zlib

OUT = "fuzz/seeds"
MAX_FIXTURE = 40_000  # bytes; larger fixtures are left out


def put(target, name, data):
    os.makedirs(os.path.join(OUT, target), exist_ok=True)
    with open(os.path.join(OUT, target, name), "wb") as f:
        f.write(data)


def copy(target, patterns):
    for pattern in patterns:
        for path in sorted(glob.glob(pattern)):
            if os.path.isfile(path) and os.path.getsize(path) <= MAX_FIXTURE:
                with open(path, "rb") as f:
                    put(target, os.path.basename(path), f.read())


# ---------------------------------------------------------------- NIfTI


def nifti(dims, datatype, bitpix, data, sform=None, qform=None, pixdim=(1, 1, 1), slope=0.0):
    h = bytearray(348)
    struct.pack_into("<i", h, 0, 348)
    dim = [len(dims)] + list(dims) + [1] * (7 - len(dims))
    struct.pack_into("<8h", h, 40, *dim)
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, -1.0 if qform else 1.0, *pixdim, 0, 0, 0, 0)
    struct.pack_into("<f", h, 108, 352.0)  # vox_offset
    struct.pack_into("<ff", h, 112, slope, 0.0)
    if qform:
        struct.pack_into("<h", h, 252, 1)
        struct.pack_into("<6f", h, 256, *qform)
    if sform:
        struct.pack_into("<h", h, 254, 2)
        struct.pack_into("<12f", h, 280, *[v for row in sform for v in row])
    h[344:348] = b"n+1\0"
    return bytes(h) + b"\0\0\0\0" + data


def mgh_seeds():
    copy("mgh", ["tests/fixtures/world/*.mgz", "tests/fixtures/world/*.mgh"])


def nifti_seeds():
    copy("nifti", ["tests/fixtures/world/*.nii*", "../shared/cases/*.nii*"])
    u8 = bytes(range(8))
    put("nifti", "u8_2x2x2.nii", nifti((2, 2, 2), 2, 8, u8))
    i16 = struct.pack("<27h", *range(-13, 14))
    sform = [[-2, 0, 0, 3], [0, 2, 0, -1], [0, 0, 2, 5]]
    put("nifti", "i16_sform.nii", nifti((3, 3, 3), 4, 16, i16, sform=sform, slope=2.0))
    f64 = struct.pack("<8d", *[0.5 * i for i in range(8)])
    qform = (0.0, 0.0, 0.7071, 10, -5, 2)
    put("nifti", "f64_qform.nii.gz", gzip.compress(nifti((2, 2, 2), 64, 64, f64, qform=qform), mtime=0))
    put("nifti", "u8_4d.nii", nifti((2, 2, 2, 2), 2, 8, bytes(16)))


# ---------------------------------------------------------------- VTI


def b64(data):
    import base64

    return base64.b64encode(data).decode()


def vti(arrays, extent="0 1 0 1 0 1", attrs="", appended=None, piece_extent=None):
    ext = piece_extent or extent
    text = (
        f'<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" {attrs}>\n'
        f'<ImageData WholeExtent="{extent}" Origin="0 0 0" Spacing="1 1 1">\n'
        f'<Piece Extent="{ext}">\n<PointData Scalars="v">\n{arrays}\n</PointData>\n</Piece>\n</ImageData>\n'
    )
    if appended is not None:
        return (text + '<AppendedData encoding="raw">\n_').encode() + appended + b"\n</AppendedData>\n</VTKFile>\n"
    return (text + "</VTKFile>\n").encode()


def lz4_literals(data):
    """A raw LZ4 block of literals only (what VTK's LZ4 compressor could write)."""
    n = len(data)
    if n < 15:
        return bytes([n << 4]) + data
    rest, ext = n - 15, bytearray()
    while rest >= 255:
        ext.append(255)
        rest -= 255
    ext.append(rest)
    return bytes([0xF0]) + bytes(ext) + data


def vti_seeds():
    copy("vti", ["tests/fixtures/vti/*.vti", "../shared/cases/*.vti"])
    put("vti", "ascii.vti", vti('<DataArray type="Float32" Name="v" format="ascii">0 1 2 3 4 5 nan inf</DataArray>'))
    raw = bytes(range(8))
    put(
        "vti",
        "appended_raw.vti",
        vti('<DataArray type="UInt8" Name="v" format="appended" offset="0"/>', appended=struct.pack("<I", 8) + raw),
    )
    put(
        "vti",
        "binary_u16.vti",
        vti(f'<DataArray type="UInt16" Name="v" format="binary">{b64(struct.pack("<I", 16) + struct.pack("<8H", *range(8)))}</DataArray>'),
    )
    values = struct.pack("<8i", *range(-4, 4))
    for name, compressor, block in [
        ("zlib", "vtkZLibDataCompressor", zlib.compress(values)),
        ("lz4", "vtkLZ4DataCompressor", lz4_literals(values)),
        ("lzma", "vtkLZMADataCompressor", lzma.compress(values, format=lzma.FORMAT_XZ, check=lzma.CHECK_CRC32)),
    ]:
        header = struct.pack("<4I", 1, 32, 32, len(block))
        put(
            "vti",
            f"compressed_{name}.vti",
            vti(
                f'<DataArray type="Int32" Name="v" format="binary">{b64(header)}{b64(block)}</DataArray>',
                attrs=f'compressor="{compressor}" header_type="UInt32"',
            ),
        )
    two_pieces = (
        '<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0">\n'
        '<ImageData WholeExtent="0 2 0 1 0 1" Origin="1 2 3" Spacing="1 -1 2" Direction="0 1 0 1 0 0 0 0 1">\n'
        '<Piece Extent="0 1 0 1 0 1"><CellData Scalars="c"><DataArray type="Int8" Name="c" format="ascii">-1</DataArray></CellData>'
        '<PointData><DataArray type="Float64" Name="v" format="ascii">0 1 2 3 4 5 6 7</DataArray></PointData></Piece>\n'
        '<Piece Extent="1 2 0 1 0 1"><PointData><DataArray type="Float64" Name="v" format="ascii">1 2 3 4 5 6 7 8</DataArray></PointData></Piece>\n'
        "</ImageData>\n</VTKFile>\n"
    )
    put("vti", "two_pieces.vti", two_pieces.encode())


# ---------------------------------------------------------------- NRRD


def nrrd_seeds():
    copy("nrrd", ["tests/fixtures/world/*.nrrd", "tests/fixtures/world/*.nhdr"])
    head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nspacings: 1 2 3\nencoding: raw\n\n"
    put("nrrd", "raw_u8.nrrd", head.encode() + bytes(range(8)))
    head = (
        "NRRD0005\ntype: short\ndimension: 3\nspace: right-anterior-superior\nsizes: 2 2 2\n"
        "space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (1,2,3)\nendian: big\nencoding: gzip\n\n"
    )
    put("nrrd", "gzip_i16.nrrd", head.encode() + gzip.compress(struct.pack(">8h", *range(-4, 4)), mtime=0))
    head = (
        "NRRD0004\ntype: float\ndimension: 4\nsizes: 2 2 2 2\nkinds: list domain domain domain\n"
        "axis mins: 0 0 0 0\ncenters: ??? cell cell node\nencoding: ascii\n\n"
    )
    put("nrrd", "ascii_4d.nrrd", head.encode() + b" ".join(str(i).encode() for i in range(16)) + b"\n")
    # Detached: the data file is the input itself, its data at the end.
    head = "NRRD0004\ntype: double\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\nbyte skip: -1\ndata file: input.nrrd\n\n"
    put("nrrd", "detached_self.nrrd", head.encode() + struct.pack("<8d", *range(8)))
    head = "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: gz\nline skip: 10\ndata file: LIST\ninput.nrrd\n"
    body = gzip.compress(struct.pack("<8H", *range(8)), mtime=0)
    put("nrrd", "detached_list.nrrd", head.encode() + b"\n" + body)
    head = "NRRD0004\ntype: int\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\nbyte skip: 4\ndata file: inp%03d.nrrd 1 1 1\n\n"
    put("nrrd", "detached_pattern.nrrd", head.encode() + bytes(36))


# ---------------------------------------------------------------- MetaImage


def metaimage_seeds():
    copy("metaimage", ["tests/fixtures/world/*.mha", "tests/fixtures/world/*.mhd"])
    head = (
        "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
        "ElementSpacing = 1 2 3\nOffset = 1 2 3\nTransformMatrix = 0 1 0 1 0 0 0 0 1\nElementDataFile = LOCAL\n"
    )
    put("metaimage", "local_u8.mha", head.encode() + bytes(range(8)))
    head = (
        "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_DOUBLE\nBinaryDataByteOrderMSB = True\n"
        "CompressedData = True\nElementDataFile = LOCAL\n"
    )
    put("metaimage", "zlib_f64.mha", head.encode() + zlib.compress(struct.pack(">8d", *range(8))))
    head = "NDims = 3\nDimSize = 2 2 2\nElementType = MET_FLOAT\nHeaderSize = -1\nElementDataFile = input.mha\n"
    put("metaimage", "tail_f32.mha", head.encode() + struct.pack("<8f", *range(8)))


# ---------------------------------------------------------------- DICOM


def dicom_seeds():
    files = sorted(glob.glob("tests/fixtures/world/dicom_series/*.dcm"))
    copy("dicom", files[:3])
    # Compressed pixel data (RLE, JPEG Lossless with VR UN attributes, JPEG 2000, JPEG-LS, 32-bit)
    # and private UN sequences: single files for the header paths, pairs (a series) for the
    # codecs, which only a stack of two slices reaches.
    for folder in (
        "dicom_series_rle",
        "dicom_series_jpegll",
        "dicom_series_j2k",
        "dicom_series_rle32",
        "dicom_series_be32",
        "dicom_series_jls",
        "dicom_series_jlsnear",
        "dicom_series_un_sequence",
    ):
        pair = []
        for path in sorted(glob.glob(f"tests/fixtures/world/{folder}/*.dcm"))[:2]:
            with open(path, "rb") as f:
                pair.append(f.read())
            put("dicom", f"{folder}_{os.path.basename(path)}", pair[-1])
        if len(pair) == 2:
            put("dicom2", f"{folder}_pair", struct.pack("<H", len(pair[0])) + pair[0] + pair[1])
    data = []
    for path in files[:4]:
        with open(path, "rb") as f:
            data.append(f.read())
    if len(data) >= 2:
        put("dicom2", "pair01", struct.pack("<H", len(data[0])) + data[0] + data[1])
        put("dicom2", "pair23", struct.pack("<H", len(data[2])) + data[2] + data[3])
        put("dicom2", "same_twice", struct.pack("<H", len(data[0])) + data[0] + data[0])


# ---------------------------------------------------------------- TIFF


def tiff(pages, bits=8, fmt=1, big=False, compression=1, description=None):
    """A multi-page grayscale TIFF; `pages` is a list of (width, height, raw bytes)."""
    e = ">" if big else "<"
    out = bytearray(b"MM\0*" if big else b"II*\0") + struct.pack(e + "I", 0)
    offsets = []
    for width, height, raw in pages:
        if compression == 8:
            raw = zlib.compress(raw)
        data_at = len(out)
        out += raw
        if len(out) % 2:
            out += b"\0"
        extra_at = len(out)
        out += struct.pack(e + "IIII", 72, 1, 72, 1)
        desc_at = len(out)
        desc = (description or "").encode() + b"\0"
        out += desc
        if len(out) % 2:
            out += b"\0"
        tags = [
            (256, 4, 1, width),
            (257, 4, 1, height),
            (258, 3, 1, bits),
            (259, 3, 1, compression),
            (262, 3, 1, 1),
            (273, 4, 1, data_at),
            (277, 3, 1, 1),
            (278, 4, 1, height),
            (279, 4, 1, len(raw)),
            (282, 5, 1, extra_at),
            (283, 5, 1, extra_at + 8),
            (296, 3, 1, 3),
            (339, 3, 1, fmt),
        ]
        if description:
            tags.append((270, 2, len(desc), desc_at))
        tags.sort()
        offsets.append(len(out))
        out += struct.pack(e + "H", len(tags))
        for tag, typ, count, value in tags:
            if typ == 3 and count == 1:
                out += struct.pack(e + "HHIHH", tag, typ, count, value, 0)
            else:
                out += struct.pack(e + "HHII", tag, typ, count, value)
        out += struct.pack(e + "I", 0)
    struct.pack_into(e + "I", out, 4, offsets[0])
    for here, nxt in zip(offsets, offsets[1:]):
        count = struct.unpack_from(e + "H", out, here)[0]
        struct.pack_into(e + "I", out, here + 2 + 12 * count, nxt)
    return bytes(out)


def tiff_seeds():
    copy("tiff", ["tests/fixtures/world/*.tif"])
    put("tiff", "u8_2pages.tif", tiff([(2, 2, bytes(range(4))), (2, 2, bytes(range(4, 8)))]))
    put(
        "tiff",
        "u16_big_deflate.tif",
        tiff([(3, 2, struct.pack(">6H", *range(6)))] * 2, bits=16, big=True, compression=8),
    )
    put(
        "tiff",
        "f32_imagej.tif",
        tiff(
            [(2, 2, struct.pack("<4f", 0, 1.5, -2, 3))] * 3,
            bits=32,
            fmt=3,
            description="ImageJ=1.54f\nimages=3\nslices=3\nunit=micron\nspacing=2.5\n",
        ),
    )
    put("tiff", "i8.tif", tiff([(2, 2, bytes([0, 255, 128, 1]))] * 2, fmt=2))


# ---------------------------------------------------------------- meshes


def mesh_seeds():
    put("obj", "triangle.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    put(
        "obj",
        "quad_normals.obj",
        b"# a quad\no quad\nv 0 0 0\nv 1 0 0 # comment\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        b"vn 0 0 1\nmtllib none.mtl\nusemtl x\nf 1/1/1 2/2/1 3/3/1 4/4/1\r\n",
    )
    put(
        "obj",
        "two_objects.obj",
        b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\ng b\nv 0 0 1\nv 1 0 \\\n 1\nv 0 1 1\nf 4//  5 6\nl 1 2\n",
    )
    ply_ascii = (
        b"ply\r\nformat ascii 1.0\r\ncomment a unit square\r\nelement vertex 4\r\n"
        b"property float x\r\nproperty float y\r\nproperty float z\r\n"
        b"property float nx\r\nproperty float ny\r\nproperty float nz\r\n"
        b"element face 1\r\nproperty list uchar uint vertex_index\r\n"
        b"element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
        b"0 0 0 0 0 2\r\n1 0 0 0 0 2\r\n1 1 0 0 0 2\r\n0 1 0 0 0 2\r\n4 0 1 2 3\r\n0 1\r\n"
    )
    put("ply", "quad_ascii.ply", ply_ascii)
    for name, e in [("little", "<"), ("big", ">")]:
        head = (
            f"ply\nformat binary_{name}_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
            "property short flags\nend_header\n"
        ).encode()
        body = b"".join(struct.pack(e + "fffB", *p, 7) for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
        body += struct.pack(e + "Biiih", 3, 0, 1, 2, -1)
        put("ply", f"triangle_{name}.ply", head + body)
    copy("stl", ["../shared/cases/*.stl"])
    tri = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
    put("stl", "binary.stl", b"solid but binary".ljust(80, b" ") + struct.pack("<I", 2) + tri + tri)
    put("stl", "binary_count0.stl", bytes(80) + struct.pack("<I", 0) + tri)
    put(
        "stl",
        "ascii.stl",
        b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\n"
        b"endloop\nendfacet\nendsolid t\n",
    )


# ---------------------------------------------------------------- graphs


def graph_seeds():
    copy("graph", ["graphs/*.ron", "tests/fixtures/bad/*.ron"])
    put(
        "graph",
        "all_params.ron",
        b'(version: 1, nodes: [(id: "c", kind: "Camera", params: {"azimuth": 1, "projection": "ortho"}),'
        b' (id: "l", kind: "Light", params: {"direction": [0.0, 1.0, 0.0]}),'
        b' (id: "v", kind: "VolumeFile", params: {"path": "a.nii", "array": "x"}, editor: Some((x: 1.5, y: -2.0))),'
        b' (id: "m", kind: "MarchingCubes", params: {"iso": 0.25, "smooth": false}),'
        b' (id: "s", kind: "ShadedSurface", params: {"color": [1.0, 0.0, 0.0, 0.5]}),'
        b' (id: "o", kind: "SaveImage", params: {"path": "out.png"})],'
        b' edges: [(from: ("v", "volume"), to: ("m", "volume")), (from: ("m", "mesh"), to: ("s", "mesh")),'
        b' (from: ("c", "camera"), to: ("s", "camera")), (from: ("l", "light"), to: ("s", "light")),'
        b' (from: ("s", "image"), to: ("o", "image"))])\n',
    )


if __name__ == "__main__":
    if os.path.isdir(OUT):
        shutil.rmtree(OUT)
    nifti_seeds()
    mgh_seeds()
    vti_seeds()
    nrrd_seeds()
    metaimage_seeds()
    dicom_seeds()
    tiff_seeds()
    mesh_seeds()
    graph_seeds()
    for target in sorted(os.listdir(OUT)):
        files = os.listdir(os.path.join(OUT, target))
        size = sum(os.path.getsize(os.path.join(OUT, target, f)) for f in files)
        print(f"{target}: {len(files)} files, {size} bytes")
