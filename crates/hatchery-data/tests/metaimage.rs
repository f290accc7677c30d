//! MetaImage reading from small hand-written headers: the header variants `load_metaimage`
//! accepts and the errors of bad files. Expected geometries were checked against SimpleITK 2.5
//! reading the same headers.

use std::io::Write;
use std::path::{Path, PathBuf};

use hatchery_data::metaimage_file::load_metaimage;
use hatchery_data::{DataError, VolumeData, load_volume};

/// 2 x 3 x 4 voxels of value = index (x fastest).
const N: usize = 24;
const HEAD: &str = "ObjectType = Image\nNDims = 3\nDimSize = 2 3 4\n";

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A `.mha`: header lines ending with `ElementDataFile = LOCAL`, then `data`.
fn mha(dir: &Path, name: &str, fields: &str, data: &[u8]) -> PathBuf {
    let mut bytes = format!("{fields}ElementDataFile = LOCAL\n").into_bytes();
    bytes.extend_from_slice(data);
    write(dir, name, &bytes)
}

fn index_bytes() -> Vec<u8> {
    (0..N as u8).collect()
}

fn zlib(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(bytes).unwrap();
    enc.finish().unwrap()
}

fn assert_index_values(v: &VolumeData) {
    assert_eq!(v.dims, [2, 3, 4]);
    let want: Vec<f32> = (0..N).map(|i| i as f32).collect();
    assert_eq!(v.values_f32(), want);
}

fn assert_affine(v: &VolumeData, want: [[f64; 4]; 3]) {
    let m = v.geometry.to_world();
    for (r, row) in want.iter().enumerate() {
        for (c, &w) in row.iter().enumerate() {
            assert!(
                (m.col(c)[r] - w).abs() < 1e-9,
                "{} != {want:?}",
                v.geometry.describe()
            );
        }
    }
}

fn error(path: &Path) -> String {
    let e = load_metaimage(path).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
    assert!(!e.contains('\n'), "{e}");
    e
}

#[test]
fn geometry_is_itk_lps_in_ras() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    let p = mha(
        d,
        "plain.mha",
        &format!("{HEAD}ElementType = MET_UCHAR\n"),
        &data,
    );
    let v = load_metaimage(&p).unwrap();
    assert_index_values(&v);
    assert_eq!((v.spacing(), v.origin()), ([1.0; 3], [0.0; 3]));
    assert!(v.placement.contains("ITK LPS"), "{}", v.placement);

    // SimpleITK reads this header as spacing (2, 3, 4), origin (1, 2, 3) and the direction
    // matrix (row-major) (0, -1, 0, 1, 0, 0, 0, 0, 1): the file's triples are its columns.
    // In RAS: rows x and y negated.
    let fields = format!(
        "{HEAD}ElementSize = 2 3 4\nPosition = 1 2 3\nOrientation = 0 1 0 -1 0 0 0 0 1\n\
         AnatomicalOrientation = RAI\nElementType = MET_UCHAR\n"
    );
    let v = load_metaimage(&mha(d, "rotated.mha", &fields, &data)).unwrap();
    assert_affine(
        &v,
        [
            [0.0, 3.0, 0.0, -1.0],
            [-2.0, 0.0, 0.0, -2.0],
            [0.0, 0.0, 4.0, 3.0],
        ],
    );
    // ElementSpacing wins over ElementSize; Offset and TransformMatrix are the usual names.
    let fields = format!(
        "{HEAD}ElementSize = 9 9 9\nElementSpacing = 2 3 4\nOffset = 1 2 3\n\
         TransformMatrix = 0 1 0 -1 0 0 0 0 1\nElementType = MET_UCHAR\n"
    );
    let v2 = load_metaimage(&mha(d, "rotated2.mha", &fields, &data)).unwrap();
    assert_eq!(v2.geometry, v.geometry);
}

#[test]
fn data_layouts() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    let u8_head = format!("{HEAD}BinaryData = True\nElementType = MET_UCHAR\n");

    // zlib-compressed LOCAL data, and a gzip stream (MetaIO inflates both).
    let p = mha(
        d,
        "z.mha",
        &format!("{u8_head}CompressedData = True\n"),
        &zlib(&data),
    );
    assert_index_values(&load_metaimage(&p).unwrap());
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&data).unwrap();
    let p = mha(
        d,
        "gz.mha",
        &format!("{u8_head}CompressedData = True\n"),
        &gz.finish().unwrap(),
    );
    assert_index_values(&load_metaimage(&p).unwrap());

    // HeaderSize -1 in a .mha: the data ends the file.
    let mut tail = b"padding".to_vec();
    tail.extend(&data);
    let p = mha(d, "end.mha", &format!("{u8_head}HeaderSize = -1\n"), &tail);
    assert_index_values(&load_metaimage(&p).unwrap());

    // A .mhd with its data file in a subfolder, skipping a 5-byte header there.
    std::fs::create_dir(d.join("raw")).unwrap();
    let mut file = b"12345".to_vec();
    file.extend(&data);
    write(d, "raw/v.raw", &file);
    let p = write(
        d,
        "v.mhd",
        format!("{u8_head}HeaderSize = 5\nElementDataFile = raw/v.raw\n").as_bytes(),
    );
    assert_index_values(&load_metaimage(&p).unwrap());
    assert_index_values(&load_volume(&p).unwrap());
    // A compressed data file (ITK's .zraw).
    write(d, "v.zraw", &zlib(&data));
    let p = write(
        d,
        "z.mhd",
        format!("{u8_head}CompressedData = True\nElementDataFile = v.zraw\n").as_bytes(),
    );
    assert_index_values(&load_metaimage(&p).unwrap());
}

#[test]
fn element_types_and_byte_order() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let head = |ty: &str, msb: &str| format!("{HEAD}{msb}ElementType = {ty}\n");
    let be: Vec<u8> = (0..N as i16).flat_map(|v| (v - 3).to_be_bytes()).collect();
    for msb in [
        "BinaryDataByteOrderMSB = True\n",
        "ElementByteOrderMSB = True\n",
    ] {
        let v = load_metaimage(&mha(d, "be.mha", &head("MET_SHORT", msb), &be)).unwrap();
        assert_eq!((v.stored_type, v.value_range), ("int16", [-3.0, 20.0]));
    }
    let le: Vec<u8> = (0..N as u16)
        .flat_map(|v| (v * 100).to_le_bytes())
        .collect();
    let v = load_metaimage(&mha(d, "us.mha", &head("MET_USHORT", ""), &le)).unwrap();
    assert_eq!((v.stored_type, v.value(1, 0, 0)), ("uint16", 100.0));
    let i8s: Vec<u8> = (0..N as i8).map(|v| (v - 4) as u8).collect();
    let v = load_metaimage(&mha(d, "c.mha", &head("MET_CHAR", ""), &i8s)).unwrap();
    assert_eq!((v.stored_type, v.value(0, 0, 0)), ("int8", -4.0));
    // MET_LONG is 4 bytes in MetaIO; the wide types become f32.
    let cases: [(&str, Vec<u8>); 6] = [
        (
            "MET_LONG",
            (0..N as i32).flat_map(|v| (v * 2).to_le_bytes()).collect(),
        ),
        (
            "MET_UINT",
            (0..N as u32).flat_map(|v| (v * 2).to_le_bytes()).collect(),
        ),
        (
            "MET_INT",
            (0..N as i32).flat_map(|v| (v * 2).to_le_bytes()).collect(),
        ),
        (
            "MET_LONG_LONG",
            (0..N as i64).flat_map(|v| (v * 2).to_le_bytes()).collect(),
        ),
        (
            "MET_FLOAT",
            (0..N)
                .flat_map(|v| (v as f32 * 2.0).to_le_bytes())
                .collect(),
        ),
        (
            "MET_DOUBLE",
            (0..N)
                .flat_map(|v| (v as f64 * 2.0).to_le_bytes())
                .collect(),
        ),
    ];
    for (ty, bytes) in cases {
        let v = load_metaimage(&mha(d, "w.mha", &head(ty, ""), &bytes)).unwrap();
        assert_eq!(v.value(1, 2, 3), 46.0, "{ty}");
    }
}

#[test]
fn bad_files_are_refused_with_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = index_bytes();
    let u8_head = format!("{HEAD}ElementType = MET_UCHAR\n");
    let cases: [(&str, String, &[u8], &str); 14] = [
        (
            "truncated",
            u8_head.clone(),
            &data[..10],
            "10 of the 24 bytes",
        ),
        (
            "ndims",
            "NDims = 2\nDimSize = 6 4\nElementType = MET_UCHAR\n".into(),
            &data,
            "NDims = 2",
        ),
        (
            "dimsize",
            "NDims = 3\nDimSize = 6 4\nElementType = MET_UCHAR\n".into(),
            &data,
            "DimSize needs 3 numbers",
        ),
        (
            "zero",
            "NDims = 3\nDimSize = 6 0 4\nElementType = MET_UCHAR\n".into(),
            &data,
            "bad DimSize",
        ),
        (
            "huge",
            "NDims = 3\nDimSize = 5000 5000 5000\nElementType = MET_UCHAR\n".into(),
            &data,
            "more than the limit",
        ),
        (
            "type",
            format!("{HEAD}ElementType = MET_COMPLEX\n"),
            &data,
            "unknown ElementType `MET_COMPLEX`",
        ),
        (
            "array",
            format!("{HEAD}ElementType = MET_UCHAR_ARRAY\n"),
            &data,
            "only scalar",
        ),
        (
            "channels",
            format!("{u8_head}ElementNumberOfChannels = 3\n"),
            &data,
            "3 channels",
        ),
        (
            "ascii",
            format!("{u8_head}BinaryData = False\n"),
            b"0 1 2",
            "ASCII",
        ),
        (
            "mesh",
            "ObjectType = Mesh\nNDims = 3\n".into(),
            &data,
            "not an image",
        ),
        ("no-type", HEAD.into(), &data, "no `ElementType`"),
        (
            "spacing",
            format!("{u8_head}ElementSpacing = 1 0 1\n"),
            &data,
            "spacing must be positive",
        ),
        (
            "corrupt",
            format!("{u8_head}CompressedData = True\n"),
            b"not zlib at all, really not",
            "corrupt",
        ),
        (
            "end-compressed",
            format!("{u8_head}HeaderSize = -1\nCompressedData = True\n"),
            &data,
            "uncompressed",
        ),
    ];
    for (name, fields, body, want) in cases {
        let p = mha(d, &format!("{name}.mha"), &fields, body);
        let e = error(&p);
        assert!(e.contains(want), "{name}: {e}");
    }
    let p = write(d, "nodata.mha", u8_head.as_bytes());
    assert!(error(&p).contains("no `ElementDataFile`"));
    let p = write(d, "binary.mha", &[0u8, 1, 2, 3]);
    assert!(error(&p).contains("not a MetaImage file"));
    let p = write(
        d,
        "pattern.mhd",
        format!("{u8_head}ElementDataFile = s%03d.raw 1 4 1\n").as_bytes(),
    );
    assert!(error(&p).contains("patterns are not supported"));
    // A missing data file is an I/O error naming that file.
    let p = write(
        d,
        "gone.mhd",
        format!("{u8_head}ElementDataFile = gone.raw\n").as_bytes(),
    );
    match load_metaimage(&p).unwrap_err() {
        DataError::Io { path, .. } => assert!(path.ends_with("gone.raw")),
        other => panic!("{other}"),
    }
}
