//! Graph inputs from numpy buffers: volumes, label maps with names, meshes, name tables.
//! The Python half hands over flat, C-contiguous buffers with i (x) fastest (what
//! `np.ravel(order="F")` gives for an array indexed `[i, j, k]`); this module copies them while
//! the caller holds the GIL and checks their sizes.

use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::mesh::MeshData;
use hatchery_data::segmentation::LabelData;
use hatchery_data::voxels::Voxels;
use numpy::{PyReadonlyArray1, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::collections::BTreeMap;

/// The voxel → world transform of a 4×4 affine (RAS+ mm, as nibabel's `img.affine`); `None`:
/// 1 mm voxels with voxel (0, 0, 0) at the origin. Errors: a last row other than (0, 0, 0, 1),
/// a zero, non-finite or singular matrix.
pub fn geometry(affine: Option<[[f64; 4]; 4]>) -> Result<Geometry, String> {
    let Some(a) = affine else {
        return Ok(Geometry::default());
    };
    if a[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(format!(
            "the affine's last row must be (0, 0, 0, 1), got {:?}",
            a[3]
        ));
    }
    Geometry::from_affine([a[0], a[1], a[2]]).map_err(|e| e.to_string())
}

fn checked_len(dims: [u32; 3], len: usize) -> Result<(), String> {
    let want = dims.iter().map(|&d| d as u128).product::<u128>();
    if want != len as u128 {
        return Err(format!(
            "dims {dims:?} need {want} voxels, the buffer holds {len}"
        ));
    }
    Ok(())
}

/// A volume from a flat voxel buffer of a type the loaders keep (uint8, int8, uint16, int16,
/// float32), kept in that type. Errors: another dtype, a size that does not match `dims`, a
/// dim under 2, a bad affine.
pub fn volume(
    voxels: &Bound<'_, PyAny>,
    dims: [u32; 3],
    affine: Option<[[f64; 4]; 4]>,
) -> Result<VolumeData, String> {
    let geometry = geometry(affine)?;
    let voxels = copy_voxels(voxels)?;
    checked_len(dims, voxels.len())?;
    let mut v = VolumeData::from_voxels(dims, geometry, voxels).map_err(|e| e.to_string())?;
    v.placement = if affine.is_some() {
        "affine given in memory".into()
    } else {
        "in memory, no affine (1 mm voxels at the origin)".into()
    };
    Ok(v)
}

fn copy_voxels(array: &Bound<'_, PyAny>) -> Result<Voxels, String> {
    macro_rules! try_type {
        ($t:ty, $variant:ident) => {
            if let Ok(a) = array.extract::<PyReadonlyArray1<'_, $t>>() {
                return Ok(Voxels::$variant(slice(&a)?.to_vec()));
            }
        };
    }
    try_type!(u8, U8);
    try_type!(i8, I8);
    try_type!(u16, U16);
    try_type!(i16, I16);
    try_type!(f32, F32);
    Err(format!(
        "voxels of type {} are not kept (uint8, int8, uint16, int16 or float32)",
        dtype_name(array)
    ))
}

fn dtype_name(array: &Bound<'_, PyAny>) -> String {
    array
        .getattr("dtype")
        .and_then(|d| d.str())
        .map(|s| s.to_string())
        .unwrap_or_else(|_| "unknown".into())
}

fn slice<'a, T: numpy::Element>(a: &'a PyReadonlyArray1<'_, T>) -> Result<&'a [T], String> {
    a.as_slice()
        .map_err(|_| format!("the buffer of {} values is not contiguous", a.len()))
}

/// A label map from a flat uint16 id buffer, objects named from `names` (id → name; ids not
/// named are "object N"). Errors: sizes, a bad affine, a name for id 0 (background).
pub fn labels(
    ids: &PyReadonlyArray1<'_, u16>,
    dims: [u32; 3],
    affine: Option<[[f64; 4]; 4]>,
    names: Option<BTreeMap<i64, String>>,
) -> Result<LabelData, String> {
    let geometry = geometry(affine)?;
    let ids = slice(ids)?.to_vec();
    checked_len(dims, ids.len())?;
    if dims.iter().any(|&d| d < 2) {
        return Err(format!(
            "label map dims must be at least 2 along every axis, got {dims:?}"
        ));
    }
    let mut data = LabelData::new(dims, geometry, ids);
    if let Some(names) = names {
        data.name_objects(&name_table(names)?);
    }
    Ok(data)
}

/// An id → name table. Errors: an id outside 1–65535.
pub fn name_table(names: BTreeMap<i64, String>) -> Result<BTreeMap<u16, String>, String> {
    names
        .into_iter()
        .map(|(id, name)| match u16::try_from(id) {
            Ok(i) if i > 0 => Ok((i, name)),
            _ => Err(format!(
                "object id {id} (named {name:?}) is not in 1–65535 (0 is the background)"
            )),
        })
        .collect()
}

/// A mesh from flat float32 vertex positions (x, y, z per vertex, world mm), uint32 triangle
/// indices and optional float32 normals. Errors: lengths not multiples of 3, indices out of
/// range, non-finite positions.
pub fn mesh(
    vertices: &PyReadonlyArray1<'_, f32>,
    faces: &PyReadonlyArray1<'_, u32>,
    normals: Option<&PyReadonlyArray1<'_, f32>>,
) -> Result<MeshData, String> {
    let triples =
        |v: &[f32]| -> Vec<[f32; 3]> { v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect() };
    let v = slice(vertices)?;
    if v.len() % 3 != 0 {
        return Err(format!(
            "{} vertex coordinates: not (x, y, z) triples",
            v.len()
        ));
    }
    let f = slice(faces)?;
    if f.len() % 3 != 0 {
        return Err(format!("{} face indices: not triangles", f.len()));
    }
    let normals = match normals {
        Some(n) => {
            let n = slice(n)?;
            if n.len() != v.len() {
                return Err(format!(
                    "{} normal components for {} vertex coordinates",
                    n.len(),
                    v.len()
                ));
            }
            Some(triples(n))
        }
        None => None,
    };
    MeshData::new(triples(v), normals, f.to_vec()).map_err(|e| e.to_string())
}
