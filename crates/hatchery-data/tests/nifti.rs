//! NIfTI loading: the shared MNI152 template and hand-written files.

use std::io::Write;
use std::path::{Path, PathBuf};

use hatchery_data::DataError;
use hatchery_data::nifti_file::{MAX_VOXELS, load_nifti};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data")
        .join(rel)
}

/// The fields of a NIfTI-1 header our tests vary; everything else is zero.
struct Header {
    dims: Vec<i16>,
    datatype: i16,
    bitpix: i16,
    pixdim: [f32; 3],
    slope: f32,
    inter: f32,
    sform_offset: Option<[f32; 3]>,
    qform_offset: Option<[f32; 3]>,
    big_endian: bool,
}

impl Header {
    fn new(dims: &[i16], datatype: i16, bitpix: i16) -> Self {
        Header {
            dims: dims.to_vec(),
            datatype,
            bitpix,
            pixdim: [1.0; 3],
            slope: 0.0,
            inter: 0.0,
            sform_offset: None,
            qform_offset: None,
            big_endian: false,
        }
    }

    /// 348-byte header, 4-byte extender (no extensions), then `data` (already in the file's
    /// byte order).
    fn file(&self, data: &[u8]) -> Vec<u8> {
        let mut h = vec![0u8; 352];
        let be = self.big_endian;
        let i32_ = |h: &mut Vec<u8>, at: usize, v: i32| {
            h[at..at + 4].copy_from_slice(&if be { v.to_be_bytes() } else { v.to_le_bytes() })
        };
        let i16_ = |h: &mut Vec<u8>, at: usize, v: i16| {
            h[at..at + 2].copy_from_slice(&if be { v.to_be_bytes() } else { v.to_le_bytes() })
        };
        let f32_ = |h: &mut Vec<u8>, at: usize, v: f32| {
            h[at..at + 4].copy_from_slice(&if be { v.to_be_bytes() } else { v.to_le_bytes() })
        };
        i32_(&mut h, 0, 348);
        i16_(&mut h, 40, self.dims.len() as i16);
        for (i, &d) in self.dims.iter().enumerate() {
            i16_(&mut h, 42 + 2 * i, d);
        }
        i16_(&mut h, 70, self.datatype);
        i16_(&mut h, 72, self.bitpix);
        f32_(&mut h, 76, 1.0); // pixdim[0]: qfac
        for i in 0..3 {
            f32_(&mut h, 80 + 4 * i, self.pixdim[i]);
        }
        f32_(&mut h, 108, 352.0);
        f32_(&mut h, 112, self.slope);
        f32_(&mut h, 116, self.inter);
        if let Some(q) = self.qform_offset {
            i16_(&mut h, 252, 1);
            for (i, &q) in q.iter().enumerate() {
                f32_(&mut h, 268 + 4 * i, q);
            }
        }
        if let Some(s) = self.sform_offset {
            i16_(&mut h, 254, 1);
            // Rows of a scaling matrix with the translation in the last column.
            for (i, &t) in s.iter().enumerate() {
                f32_(&mut h, 280 + 16 * i + 4 * i, self.pixdim[i]);
                f32_(&mut h, 280 + 16 * i + 12, t);
            }
        }
        h[344..348].copy_from_slice(b"n+1\0");
        h.extend_from_slice(data);
        h
    }
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(bytes).unwrap();
    enc.finish().unwrap()
}

/// Raw int16 values x + 10 y + 100 z on a 4x3x5 grid, x fastest (the NIfTI order).
fn int16_raw(big_endian: bool) -> Vec<u8> {
    let mut bytes = Vec::new();
    for z in 0..5i16 {
        for y in 0..3i16 {
            for x in 0..4i16 {
                let v = x + 10 * y + 100 * z;
                bytes.extend(if big_endian {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
        }
    }
    bytes
}

fn check_int16_volume(v: &hatchery_data::VolumeData) {
    assert_eq!(v.dims, [4, 3, 5]);
    for z in 0..5 {
        for y in 0..3 {
            for x in 0..4 {
                let raw = (x + 10 * y + 100 * z) as f32;
                assert_eq!(v.value(x, y, z), 2.0 * raw + 10.0, "at ({x},{y},{z})");
            }
        }
    }
    assert_eq!(v.value_range, [10.0, 2.0 * 423.0 + 10.0]);
}

#[test]
fn mni152_t1() {
    let v = load_nifti(&data("volumes/mni152_t1.nii.gz")).unwrap();
    assert_eq!(v.dims, [197, 233, 189]);
    assert_eq!(v.spacing(), [1.0, 1.0, 1.0]);
    // sform translation of the MNI152 2009a template.
    assert_eq!(v.origin(), [-98.0, -134.0, -72.0]);
    assert_eq!(v.value_range, [0.0, 255.0]);
    assert_eq!(v.voxel_count(), 197 * 233 * 189);
    // Spot values checked independently (gzip + byte offset 352 + x + 197 (y + 233 z)).
    assert_eq!(v.value(98, 116, 94), 198.0);
    assert_eq!(v.value(120, 100, 100), 219.0);
    assert_eq!(v.value(0, 0, 0), 0.0);
}

#[test]
fn mni152_tissue_maps() {
    let gm = load_nifti(&data("volumes/mni152_gm.nii.gz")).unwrap();
    let wm = load_nifti(&data("volumes/mni152_wm.nii.gz")).unwrap();
    for v in [&gm, &wm] {
        assert_eq!(v.dims, [197, 233, 189]);
        assert_eq!(v.value_range, [0.0, 255.0]);
    }
    assert_eq!(
        (gm.value(98, 116, 94), gm.value(120, 100, 100)),
        (126.0, 10.0)
    );
    assert_eq!(
        (wm.value(98, 116, 94), wm.value(120, 100, 100)),
        (124.0, 244.0)
    );
}

#[test]
fn int16_with_slope_and_intercept() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = Header::new(&[4, 3, 5], 4, 16);
    h.slope = 2.0;
    h.inter = 10.0;
    h.pixdim = [0.5, -2.0, 3.0]; // negative pixdim: spacing is its magnitude
    h.qform_offset = Some([1.0, 2.0, 3.0]);
    let bytes = h.file(&int16_raw(false));

    let v = load_nifti(&write(dir.path(), "a.nii", &bytes)).unwrap();
    check_int16_volume(&v);
    assert_eq!(v.spacing(), [0.5, 2.0, 3.0]);
    assert_eq!(v.origin(), [1.0, 2.0, 3.0]);

    // The same, compressed; the name does not matter, the content is sniffed.
    let gz = load_nifti(&write(dir.path(), "a.nii.gz", &gzip(&bytes))).unwrap();
    assert_eq!(gz, v);

    // Big-endian file.
    let mut h = Header::new(&[4, 3, 5], 4, 16);
    h.big_endian = true;
    h.slope = 2.0;
    h.inter = 10.0;
    let v = load_nifti(&write(dir.path(), "be.nii", &h.file(&int16_raw(true)))).unwrap();
    check_int16_volume(&v);
}

#[test]
fn float32_axis_order_spacing_and_sform() {
    let dir = tempfile::tempdir().unwrap();
    let f = |x: u32, y: u32, z: u32| x as f32 * 0.5 - y as f32 + z as f32 * 3.25;
    let mut raw = Vec::new();
    for z in 0..2 {
        for y in 0..4 {
            for x in 0..3 {
                raw.extend(f(x, y, z).to_le_bytes());
            }
        }
    }
    let mut h = Header::new(&[3, 4, 2], 16, 32);
    h.pixdim = [0.5, 2.0, 3.0];
    h.sform_offset = Some([-10.0, 20.0, 5.5]);
    h.qform_offset = Some([1.0, 1.0, 1.0]); // sform wins
    let v = load_nifti(&write(dir.path(), "f.nii", &h.file(&raw))).unwrap();
    assert_eq!(v.dims, [3, 4, 2]);
    assert_eq!(v.spacing(), [0.5, 2.0, 3.0]);
    assert_eq!(v.origin(), [-10.0, 20.0, 5.5]);
    for z in 0..2 {
        for y in 0..4 {
            for x in 0..3 {
                assert_eq!(v.value(x, y, z), f(x, y, z), "at ({x},{y},{z})");
            }
        }
    }
    // slope 0 (as written by Header::new) means no scaling.
    assert_eq!(v.value_range, [f(0, 3, 0), f(2, 0, 1)]);
}

#[test]
fn all_scalar_datatypes() {
    let dir = tempfile::tempdir().unwrap();
    // (datatype code, bitpix, encoder of a small integer)
    type Enc = fn(i32) -> Vec<u8>;
    let types: [(i16, i16, Enc); 10] = [
        (2, 8, |v| vec![v as u8]),
        (256, 8, |v| vec![(v - 4) as i8 as u8]),
        (4, 16, |v| (v as i16).to_le_bytes().to_vec()),
        (512, 16, |v| (v as u16).to_le_bytes().to_vec()),
        (8, 32, |v| v.to_le_bytes().to_vec()),
        (768, 32, |v| (v as u32).to_le_bytes().to_vec()),
        (1024, 64, |v| (v as i64).to_le_bytes().to_vec()),
        (1280, 64, |v| (v as u64).to_le_bytes().to_vec()),
        (16, 32, |v| (v as f32).to_le_bytes().to_vec()),
        (64, 64, |v| (v as f64).to_le_bytes().to_vec()),
    ];
    for (code, bitpix, enc) in types {
        let raw: Vec<u8> = (0..8).flat_map(enc).collect();
        let mut h = Header::new(&[2, 2, 2], code, bitpix);
        h.slope = 0.5;
        let v = load_nifti(&write(dir.path(), &format!("t{code}.nii"), &h.file(&raw))).unwrap();
        let offset = if code == 256 { -4.0 } else { 0.0 };
        let want: Vec<f32> = (0..8).map(|i| 0.5 * (i as f32 + offset)).collect();
        assert_eq!(v.values_f32(), want, "datatype {code}");
    }
    // RGB is not a scalar type.
    let h = Header::new(&[2, 2, 2], 128, 24);
    let e = load_nifti(&write(dir.path(), "rgb.nii", &h.file(&[0; 24]))).unwrap_err();
    assert!(matches!(e, DataError::Unsupported { .. }), "{e}");
    assert!(e.to_string().contains("rgb.nii"), "{e}");
}

#[test]
fn four_d_file_gives_first_volume() {
    let dir = tempfile::tempdir().unwrap();
    let raw: Vec<u8> = (0..16u8).collect();
    let v = load_nifti(&write(
        dir.path(),
        "t.nii",
        &Header::new(&[2, 2, 2, 2], 2, 8).file(&raw),
    ))
    .unwrap();
    assert_eq!(v.values_f32(), (0..8).map(|i| i as f32).collect::<Vec<_>>());
    assert!(
        v.placement.contains("the first of 2 volumes"),
        "{}",
        v.placement
    );
}

/// A vector field (dim[0] = 5, dim[5] = 3 values per voxel) is refused, not read as its first
/// component.
#[test]
fn several_values_per_voxel_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let raw = vec![0u8; 8 * 3];
    let e = load_nifti(&write(
        dir.path(),
        "vectors.nii",
        &Header::new(&[2, 2, 2, 1, 3], 2, 8).file(&raw),
    ))
    .unwrap_err();
    assert!(matches!(e, DataError::Unsupported { .. }), "{e}");
    assert!(e.to_string().contains("3 values per voxel"), "{e}");
    assert!(e.to_string().contains("vectors.nii"), "{e}");
}

#[test]
fn non_finite_values_are_kept_as_no_data() {
    let dir = tempfile::tempdir().unwrap();
    let vals = [1.0f32, f32::NAN, 3.0, -2.0, f32::INFINITY, 0.0, 5.0, 6.0];
    let raw: Vec<u8> = vals.iter().flat_map(|v| v.to_le_bytes()).collect();
    let v = load_nifti(&write(
        dir.path(),
        "nan.nii",
        &Header::new(&[2, 2, 2], 16, 32).file(&raw),
    ))
    .unwrap();
    assert!(v.values_f32()[1].is_nan());
    assert_eq!(v.values_f32()[4], f32::INFINITY);
    assert_eq!(
        v.value_range,
        [-2.0, 6.0],
        "the range is over finite values"
    );
}

/// Writes quaternion, offsets and qfac into a header made by `Header::file` (qform_code 1,
/// sform_code 0).
fn with_qform(mut file: Vec<u8>, bcd: [f32; 3], offset: [f32; 3], qfac: f32) -> Vec<u8> {
    let f32_at =
        |file: &mut Vec<u8>, at: usize, v: f32| file[at..at + 4].copy_from_slice(&v.to_le_bytes());
    file[252..254].copy_from_slice(&1i16.to_le_bytes());
    file[254..256].copy_from_slice(&0i16.to_le_bytes());
    f32_at(&mut file, 76, qfac);
    for i in 0..3 {
        f32_at(&mut file, 256 + 4 * i, bcd[i]);
        f32_at(&mut file, 268 + 4 * i, offset[i]);
    }
    file
}

#[test]
fn qform_quaternion_qfac_and_pixdim_rules() {
    let dir = tempfile::tempdir().unwrap();
    let raw = vec![0u8; 3 * 4 * 2];
    let mut h = Header::new(&[3, 4, 2], 2, 8);
    h.pixdim = [0.5, 2.0, 3.0];
    // 90° about z: (b, c, d) = (0, 0, sin 45°); qfac −1 flips k.
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let file = with_qform(h.file(&raw), [0.0, 0.0, s], [10.0, -5.0, 2.0], -1.0);
    let v = load_nifti(&write(dir.path(), "q.nii", &file)).unwrap();
    assert!(v.placement.starts_with("qform"), "{}", v.placement);
    let at = |ijk: [f32; 3]| v.voxel_to_world(glam::Vec3::from_array(ijk));
    let close =
        |a: glam::Vec3, b: [f32; 3]| (a - glam::Vec3::from_array(b)).abs().max_element() < 1e-4;
    // i (0.5 mm) turns to +y, j (2 mm) to −x, k (3 mm) to −z.
    assert!(close(at([0.0, 0.0, 0.0]), [10.0, -5.0, 2.0]));
    assert!(
        close(at([1.0, 0.0, 0.0]), [10.0, -4.5, 2.0]),
        "{}",
        at([1.0, 0.0, 0.0])
    );
    assert!(
        close(at([0.0, 1.0, 0.0]), [8.0, -5.0, 2.0]),
        "{}",
        at([0.0, 1.0, 0.0])
    );
    assert!(
        close(at([0.0, 0.0, 1.0]), [10.0, -5.0, -1.0]),
        "{}",
        at([0.0, 0.0, 1.0])
    );
    assert_eq!(v.spacing(), [0.5, 2.0, 3.0]);

    // A negative pixdim is a size, not a mirror: only qfac flips (nibabel refuses such a
    // qform, nifti1_io takes 1; hatchery takes the magnitude and says so).
    let mut negative = Header::new(&[3, 4, 2], 2, 8);
    negative.pixdim = [0.5, -2.0, 3.0];
    let file = with_qform(negative.file(&raw), [0.0, 0.0, s], [10.0, -5.0, 2.0], -1.0);
    let w = load_nifti(&write(dir.path(), "neg.nii", &file)).unwrap();
    assert_eq!(w.geometry, v.geometry);
    assert!(
        w.placement
            .contains("negative pixdim[2] = -2 taken as the magnitude"),
        "{}",
        w.placement
    );

    // Neither code: pixdim scaling, origin 0.
    let v = load_nifti(&write(dir.path(), "p.nii", &h.file(&raw))).unwrap();
    assert!(v.placement.starts_with("pixdim"), "{}", v.placement);
    assert_eq!(v.origin(), [0.0; 3]);
    assert!(v.geometry.is_axis_aligned());
}

/// Asserts the error message is one line and names the file.
fn assert_names(e: &DataError, name: &str) {
    let msg = e.to_string();
    assert!(msg.contains(name), "message does not name {name}: {msg}");
    assert!(!msg.contains('\n'), "multi-line message: {msg}");
    eprintln!("{msg}");
}

#[test]
fn bad_files_are_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();

    // Truncated gzip stream of the real template.
    let full = std::fs::read(data("volumes/mni152_t1.nii.gz")).unwrap();
    let path = write(dir.path(), "brain.nii.gz", &full[..full.len() / 2]);
    let e = load_nifti(&path).unwrap_err();
    assert_names(&e, "brain.nii.gz");
    assert!(e.to_string().contains("truncated"), "{e}");

    // Header claiming 30000^3 voxels (dims are 16-bit, so 100000 cannot be written).
    let path = write(
        dir.path(),
        "huge.nii",
        &Header::new(&[30000, 30000, 30000], 2, 8).file(&[]),
    );
    let e = load_nifti(&path).unwrap_err();
    assert_names(&e, "huge.nii");
    match e {
        DataError::TooLarge { voxels, limit, .. } => {
            assert_eq!(voxels, 27_000_000_000_000);
            assert_eq!(limit, MAX_VOXELS);
        }
        other => panic!("expected TooLarge, got {other}"),
    }

    // Uncompressed file with its data cut short.
    let bytes = Header::new(&[4, 3, 5], 4, 16).file(&int16_raw(false));
    let e = load_nifti(&write(dir.path(), "short.nii", &bytes[..bytes.len() - 7])).unwrap_err();
    assert_names(&e, "short.nii");
    assert!(e.to_string().contains("truncated"), "{e}");

    // A 2-D image and a volume one voxel thick.
    let e = load_nifti(&write(
        dir.path(),
        "flat.nii",
        &Header::new(&[4, 4], 2, 8).file(&[0; 16]),
    ))
    .unwrap_err();
    assert_names(&e, "flat.nii");
    let e = load_nifti(&write(
        dir.path(),
        "thin.nii",
        &Header::new(&[4, 4, 1], 2, 8).file(&[0; 16]),
    ))
    .unwrap_err();
    assert_names(&e, "thin.nii");

    // Negative dimension.
    let e = load_nifti(&write(
        dir.path(),
        "neg.nii",
        &Header::new(&[4, -4, 2], 2, 8).file(&[0; 32]),
    ))
    .unwrap_err();
    assert_names(&e, "neg.nii");

    // Header-only (.hdr/.img pair) magic.
    let mut bytes = Header::new(&[2, 2, 2], 2, 8).file(&[0; 8]);
    bytes[344..348].copy_from_slice(b"ni1\0");
    let e = load_nifti(&write(dir.path(), "pair.hdr", &bytes)).unwrap_err();
    assert_names(&e, "pair.hdr");
    assert!(matches!(e, DataError::Unsupported { .. }));

    // Not NIfTI at all, empty, compressed garbage, missing.
    let e = load_nifti(&write(dir.path(), "garbage.nii", &[7u8; 1000])).unwrap_err();
    assert_names(&e, "garbage.nii");
    let e = load_nifti(&write(dir.path(), "empty.nii", &[])).unwrap_err();
    assert_names(&e, "empty.nii");
    let e = load_nifti(&write(dir.path(), "junk.nii.gz", &gzip(&[1u8; 100]))).unwrap_err();
    assert_names(&e, "junk.nii.gz");
    let mut corrupt = gzip(&bytes);
    let mid = corrupt.len() / 2;
    corrupt[10..mid].iter_mut().for_each(|b| *b ^= 0x5a);
    let e = load_nifti(&write(dir.path(), "corrupt.nii.gz", &corrupt)).unwrap_err();
    assert_names(&e, "corrupt.nii.gz");
    let e = load_nifti(&dir.path().join("missing.nii")).unwrap_err();
    assert_names(&e, "missing.nii");
    assert!(matches!(e, DataError::Io { .. }));
}
