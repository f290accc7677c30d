//! Unit tests of the reader on files written here; tests/vti.rs reads files VTK wrote.

use super::*;
use glam::{DMat3, DVec3};
use std::io::Write;

const FROG: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../../shared/data/volumes/frog_tissues.vti"
);

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = c
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &b)| n | (b as u32) << (16 - 8 * i));
        for i in 0..4 {
            s.push(if i <= c.len() {
                A[(n >> (18 - 6 * i) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    s
}

fn zlib(bytes: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

/// A VTKFile around one data array element (`data` is its text content).
fn vti(file_attrs: &str, extent: &str, set: &str, array_attrs: &str, data: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" {file_attrs}>
  <ImageData WholeExtent="{extent}" Origin="1 2 3" Spacing="0.5 2 -1.5" Direction="1 0 0 0 1 0 0 0 1">
<Piece Extent="{extent}">
  <{set} Scalars="v">
    <DataArray Name="v" {array_attrs}>{data}</DataArray>
    <DataArray type="Float32" Name="other" format="ascii">9</DataArray>
  </{set}>
</Piece>
  </ImageData>
</VTKFile>
"#
    )
}

pub(super) fn write(dir: &tempfile::TempDir, name: &str, content: &[u8]) -> std::path::PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, content).unwrap();
    path
}

/// 4 x 3 x 2 values x + 10 y + 100 z, x fastest.
fn small_values() -> Vec<f32> {
    (0..2)
        .flat_map(|z| (0..3).flat_map(move |y| (0..4).map(move |x| (x + 10 * y + 100 * z) as f32)))
        .collect()
}

fn check_small(v: &VolumeData) {
    assert_eq!(v.dims, [4, 3, 2]);
    // Spacing -1.5 along z: a positive spacing, z flipped in the direction.
    assert_eq!(v.spacing(), [0.5, 2.0, 1.5]);
    assert_eq!(
        v.geometry.direction,
        DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0))
    );
    // Extent starts at (2, 0, 1): origin = Origin + Direction · (Spacing ⊙ lower corner).
    assert_eq!(v.origin(), [2.0, 2.0, 1.5]);
    assert_eq!(
        v.placement,
        "VTK Origin/Spacing/Direction, extent 2..5 0..2 1..2, point data `v`"
    );
    assert_eq!(v.values_f32(), small_values());
    assert_eq!(v.value(3, 2, 1), 123.0);
}

const SMALL_EXTENT: &str = "2 5 0 2 1 2";

fn f32_bytes(big_endian: bool) -> Vec<u8> {
    small_values()
        .iter()
        .flat_map(|v| {
            if big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        })
        .collect()
}

#[test]
fn frog_labels() {
    let v = load_vti(Path::new(FROG), None).unwrap();
    assert_eq!(v.dims, [500, 470, 136]);
    assert_eq!(v.spacing(), [1.0, 1.0, 1.5]);
    assert_eq!(v.origin(), [0.0; 3]);
    assert_eq!(v.value_range, [0.0, 29.0]);
    assert!(v.values_f32().iter().all(|x| x.fract() == 0.0));
    // Counted independently (Python: xml + base64 + zlib from the standard library).
    let counts = crate::labels::label_counts(&v);
    assert_eq!(counts[&0], 30_805_713);
    assert_eq!(counts[&13], 438_052);
    assert_eq!(counts[&10], 204_672);
    assert_eq!(counts[&21], 4);
    assert!(!counts.contains_key(&18));
    assert_eq!(counts.values().sum::<u64>(), 500 * 470 * 136);
    assert_eq!(v.value(250, 235, 68), 6.0);
}

#[test]
fn ascii_point_data() {
    let dir = tempfile::tempdir().unwrap();
    let text: Vec<String> = small_values().iter().map(|v| v.to_string()).collect();
    let body = vti(
        "byte_order=\"LittleEndian\"",
        SMALL_EXTENT,
        "PointData",
        r#"type="Float32" format="ascii""#,
        &format!("\n  {}\n", text.join(" ")),
    );
    check_small(&load_vti(&write(&dir, "a.vti", body.as_bytes()), None).unwrap());
}

#[test]
fn inline_binary_both_header_encodings_and_byte_orders() {
    let dir = tempfile::tempdir().unwrap();
    for big_endian in [false, true] {
        let data = f32_bytes(big_endian);
        let n = data.len() as u32;
        let header = if big_endian {
            n.to_be_bytes()
        } else {
            n.to_le_bytes()
        };
        let joint = base64(&[&header[..], &data].concat());
        let separate = base64(&header) + &base64(&data);
        let order = if big_endian {
            "BigEndian"
        } else {
            "LittleEndian"
        };
        for text in [joint, separate] {
            let body = vti(
                &format!("byte_order=\"{order}\" header_type=\"UInt32\""),
                SMALL_EXTENT,
                "PointData",
                r#"type="Float32" format="binary""#,
                &text,
            );
            check_small(&load_vti(&write(&dir, "b.vti", body.as_bytes()), None).unwrap());
        }
    }
}

/// Compressed blocks: several full ones and a partial one, or all full (`np` = 0).
fn compressed(data: &[u8], block: usize, wide: bool) -> String {
    let blocks: Vec<Vec<u8>> = data.chunks(block).map(zlib).collect();
    let mut header = vec![
        blocks.len() as u64,
        block as u64,
        (data.len() % block) as u64,
    ];
    header.extend(blocks.iter().map(|b| b.len() as u64));
    let header: Vec<u8> = header
        .iter()
        .flat_map(|&n| {
            if wide {
                n.to_le_bytes().to_vec()
            } else {
                (n as u32).to_le_bytes().to_vec()
            }
        })
        .collect();
    base64(&header) + &base64(&blocks.concat())
}

#[test]
fn zlib_inline_partial_and_full_last_block() {
    let dir = tempfile::tempdir().unwrap();
    let data = f32_bytes(false);
    // 96 bytes: blocks of 40 leave a partial last block, blocks of 32 do not.
    for (block, wide) in [(40, false), (32, false), (32, true), (96, false)] {
        let body = vti(
            &format!(
                "byte_order=\"LittleEndian\" header_type=\"{}\" compressor=\"vtkZLibDataCompressor\"",
                if wide { "UInt64" } else { "UInt32" }
            ),
            SMALL_EXTENT,
            "PointData",
            r#"type="Float32" format="binary""#,
            &compressed(&data, block, wide),
        );
        check_small(&load_vti(&write(&dir, "c.vti", body.as_bytes()), None).unwrap());
    }
}

#[test]
fn appended_raw_and_base64() {
    let dir = tempfile::tempdir().unwrap();
    let data = f32_bytes(false);
    let mut raw = (data.len() as u32).to_le_bytes().to_vec();
    raw.extend(&data);
    let head = |encoding: &str, offset: usize| {
        format!(
            r#"<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">
<ImageData WholeExtent="{SMALL_EXTENT}" Origin="1 2 3" Spacing="0.5 2 -1.5">
<Piece Extent="{SMALL_EXTENT}"><PointData>
<DataArray type="Float32" Name="v" format="appended" offset="{offset}"/>
</PointData></Piece></ImageData>
<AppendedData encoding="{encoding}">
   _"#
        )
    };
    // Raw: binary bytes that are not XML, behind 5 bytes of some other array.
    let mut file = head("raw", 5).into_bytes();
    file.extend([b'<', 0xff, 0, b'&', b'>']);
    file.extend(&raw);
    file.extend(b"\n</AppendedData>\n</VTKFile>\n");
    check_small(&load_vti(&write(&dir, "raw.vti", &file), None).unwrap());

    let text = base64(&raw);
    let file = format!(
        "{}AAAA{text}\n</AppendedData>\n</VTKFile>\n",
        head("base64", 4)
    );
    check_small(&load_vti(&write(&dir, "b64.vti", file.as_bytes()), None).unwrap());
}

#[test]
fn integer_types_and_cell_data() {
    let dir = tempfile::tempdir().unwrap();
    // Cell data: an extent of 5 x 4 x 3 points holds 4 x 3 x 2 cells.
    let data: Vec<u8> = small_values()
        .iter()
        .flat_map(|&v| (v as i16 - 50).to_le_bytes())
        .collect();
    let mut raw = (data.len() as u32).to_le_bytes().to_vec();
    raw.extend(&data);
    let body = vti(
        "byte_order=\"LittleEndian\"",
        "0 4 -1 2 0 2",
        "CellData",
        r#"type="Int16" format="binary""#,
        &base64(&raw),
    );
    let v = load_vti(&write(&dir, "cells.vti", body.as_bytes()), None).unwrap();
    assert_eq!(v.dims, [4, 3, 2]);
    // First cell centre: Origin + Direction · (Spacing ⊙ (0.5, -0.5, 0.5)).
    assert_eq!(v.origin(), [1.25, 1.0, 2.25]);
    assert_eq!(v.stored_type, "int16");
    assert_eq!(v.value(0, 0, 0), -50.0);
    assert_eq!(v.value(3, 2, 1), 73.0);
}

#[test]
fn bad_files_are_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let frog = std::fs::read(FROG).unwrap();
    let text = String::from_utf8(frog.clone()).unwrap();
    let start = text.find("format=\"binary\"").unwrap();
    let data_start = start + text[start..].find('>').unwrap() + 1;
    let data_end = text.find("</DataArray>").unwrap();
    let mut cases: Vec<(String, Vec<u8>)> = vec![
        ("garbage".into(), b"garbage".to_vec()),
        ("binary".into(), (0..=255u8).cycle().take(5000).collect()),
        ("empty".into(), Vec::new()),
    ];
    for cut in [10, 300, 1000, 200_000, frog.len() - 40] {
        cases.push((format!("file cut at {cut}"), frog[..cut].to_vec()));
    }
    // Well-formed XML whose data is cut short, inside the block header or the blocks.
    for keep in [0, 3, 2000, 200_000] {
        let mut t = text[..data_start].to_string();
        t.push_str(&text[data_start..][..keep.min(data_end - data_start)]);
        t.push_str(&text[data_end..]);
        cases.push((format!("data cut at {keep}"), t.into_bytes()));
    }
    // Corrupt compressed bytes (past the block header).
    let mut corrupt = frog.clone();
    for b in &mut corrupt[data_start + 8000..data_start + 8100] {
        *b = if *b == b'A' { b'B' } else { b'A' };
    }
    cases.push(("corrupt blocks".into(), corrupt));
    cases.push((
        "huge extent".into(),
        text.replace("0 499 0 469 0 135", "0 99999 0 99999 0 99999")
            .into_bytes(),
    ));
    cases.push((
        "extreme extent".into(),
        text.replace("0 499 0 469 0 135", "-9223372036854775808 0 0 469 0 135")
            .into_bytes(),
    ));
    cases.push((
        "reversed extent".into(),
        text.replace("0 499 0 469 0 135", "499 0 0 469 0 135")
            .into_bytes(),
    ));
    cases.push((
        "three components".into(),
        vti(
            "",
            SMALL_EXTENT,
            "PointData",
            r#"type="Float32" NumberOfComponents="3" format="ascii""#,
            "1 2 3",
        )
        .into_bytes(),
    ));
    cases.push((
        "poly data".into(),
        b"<VTKFile type=\"PolyData\"><PolyData/></VTKFile>".to_vec(),
    ));
    cases.push((
        "too few ascii values".into(),
        vti(
            "",
            SMALL_EXTENT,
            "PointData",
            r#"type="Float32" format="ascii""#,
            "1 2 3",
        )
        .into_bytes(),
    ));
    for (what, content) in cases {
        let path = write(&dir, "bad.vti", &content);
        let e = load_vti(&path, None).expect_err(&what).to_string();
        assert!(e.starts_with(&path.display().to_string()), "{what}: {e}");
        assert!(!e.contains('\n'), "{what}: {e}");
        match what.as_str() {
            "huge extent" => assert!(e.contains("more than the limit"), "{e}"),
            "three components" => assert!(e.contains("3 components"), "{e}"),
            "poly data" => assert!(e.contains("PolyData"), "{e}"),
            _ => {}
        }
    }
    let missing = dir.path().join("missing.vti");
    assert!(matches!(
        load_vti(&missing, None),
        Err(DataError::Io { .. })
    ));
}
