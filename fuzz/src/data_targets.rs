//! What each hatchery-data fuzz target does with one input: write it to a scratch file (the
//! readers take paths, and NRRD, MetaImage and DICOM read other files next to it), read it with
//! the format's reader, and check the outcome.
//!
//! This file is compiled twice: by the fuzz crate (`fuzz/src/lib.rs`) and by
//! `crates/hatchery-data/tests/fuzz_corpus.rs` (`#[path]`), so the replay test runs exactly
//! what the fuzzer ran. It uses only `hatchery_data`, `tempfile` and `std`.

use std::path::{Path, PathBuf};

use hatchery_data::dicom_series::load_dicom_series;
use hatchery_data::mesh_file::load_mesh;
use hatchery_data::metaimage_file::load_metaimage;
use hatchery_data::nifti_file::load_nifti;
use hatchery_data::nrrd_file::load_nrrd;
use hatchery_data::tiff_stack::load_tiff_stack;
use hatchery_data::vti_file::load_vti;
use hatchery_data::{DataError, MeshData, VolumeData};

/// A private folder for the inputs: each target writes its file(s) under fixed names in its
/// own sub-folder, so every run sees the same folder contents.
pub struct Scratch {
    dir: tempfile::TempDir,
}

impl Default for Scratch {
    fn default() -> Self {
        Self::new()
    }
}

impl Scratch {
    pub fn new() -> Self {
        let dir = tempfile::Builder::new()
            .prefix("hatchery-fuzz-")
            .tempdir()
            .expect("cannot make a scratch folder");
        Scratch { dir }
    }

    fn folder(&self, name: &str) -> PathBuf {
        let folder = self.dir.path().join(name);
        std::fs::create_dir_all(&folder).expect("cannot make a scratch sub-folder");
        folder
    }

    fn file(&self, folder: &str, name: &str, data: &[u8]) -> PathBuf {
        let path = self.folder(folder).join(name);
        std::fs::write(&path, data).expect("cannot write a scratch file");
        path
    }
}

/// One target: reads one input and returns the reader's error message, if any (for people
/// looking at a corpus); panics only on a bug.
pub type Target = fn(&Scratch, &[u8]) -> Result<(), String>;

/// Every hatchery-data target by name (the fuzz target names, and the folder names under
/// `fuzz/corpus` and `fuzz/regressions`).
pub const TARGETS: [(&str, Target); 11] = [
    ("nifti", nifti),
    ("mgh", mgh),
    ("vti", vti),
    ("nrrd", nrrd),
    ("metaimage", metaimage),
    ("dicom", dicom),
    ("dicom2", dicom2),
    ("tiff", tiff),
    ("obj", obj),
    ("ply", ply),
    ("stl", stl),
];

/// A single-file NIfTI-1 or NIfTI-2 volume (gzip or not, told by the content).
pub fn nifti(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_nifti(&s.file("nifti", "input.nii", data)))
}

/// A FreeSurfer MGH volume (MGZ when gzip, told by the content).
pub fn mgh(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(hatchery_data::mgh_file::load_mgh(&s.file(
        "mgh",
        "input.mgz",
        data,
    )))
}

/// A VTK XML ImageData file, its default array.
pub fn vti(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_vti(&s.file("vti", "input.vti", data), None))
}

/// A NRRD file; a `data file` field may name the input itself.
pub fn nrrd(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_nrrd(&s.file("nrrd", "input.nrrd", data)))
}

/// A MetaImage file; `ElementDataFile` may be LOCAL or name the input itself.
pub fn metaimage(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_metaimage(&s.file("metaimage", "input.mha", data)))
}

/// A DICOM series of one file, loaded by naming the file (its folder is scanned too).
pub fn dicom(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_dicom_series(&s.file("dicom", "a.dcm", data)))
}

/// A DICOM series of two files, loaded by naming their folder. The input is a little-endian
/// u16 length `n`, then the first file's `n` bytes, then the second file (fewer bytes than
/// promised: all of them go to the first file).
pub fn dicom2(s: &Scratch, data: &[u8]) -> Result<(), String> {
    let (first, second) = match data {
        [a, b, rest @ ..] => rest.split_at((u16::from_le_bytes([*a, *b]) as usize).min(rest.len())),
        _ => (data, &[][..]),
    };
    s.file("dicom2", "a.dcm", first);
    let b = s.file("dicom2", "b.dcm", second);
    check_volume(load_dicom_series(b.parent().unwrap_or(Path::new("."))))
}

/// A multi-page TIFF stack.
pub fn tiff(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_volume(load_tiff_stack(&s.file("tiff", "input.tif", data)))
}

pub fn obj(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_mesh(load_mesh(&s.file("obj", "input.obj", data)))
}

pub fn ply(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_mesh(load_mesh(&s.file("ply", "input.ply", data)))
}

pub fn stl(s: &Scratch, data: &[u8]) -> Result<(), String> {
    check_mesh(load_mesh(&s.file("stl", "input.stl", data)))
}

/// A loaded volume keeps its invariants; an error names a file and is one line.
fn check_volume(result: Result<VolumeData, DataError>) -> Result<(), String> {
    let v = result.map_err(check_error)?;
    let count = v.dims.iter().map(|&d| d as usize).product::<usize>();
    assert_eq!(v.voxel_count(), count, "dims {:?}", v.dims);
    assert!(v.dims.iter().all(|&d| d >= 2), "dims {:?}", v.dims);
    Ok(())
}

/// A loaded mesh has triangles, in-range indices, finite positions and a normal per vertex;
/// an error names a file and is one line.
fn check_mesh(result: Result<MeshData, DataError>) -> Result<(), String> {
    let m = result.map_err(check_error)?;
    assert!(m.triangle_count() > 0);
    assert_eq!(m.normals.len(), m.positions.len());
    assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
    assert!(m.positions.iter().flatten().all(|c| c.is_finite()));
    Ok(())
}

fn check_error(e: DataError) -> String {
    // `Invalid` is the variant for in-memory data: a reader must say which file was bad.
    assert!(
        !matches!(e, DataError::Invalid(_)),
        "error without a file: {e}"
    );
    let message = e.to_string();
    assert!(
        !message.contains('\n'),
        "error message of several lines: {message:?}"
    );
    message
}
