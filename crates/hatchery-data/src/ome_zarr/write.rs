//! Writes a volume (and a label map on its grid) as an OME-Zarr 0.5 image (Zarr v3, zstd
//! chunks): `hatchery convert IN OUT.zarr`.
//!
//! OME-NGFF 0.5 places voxels by scale and translation only. A grid whose axes run along the
//! world axes (any order, any flips) is written exactly: the voxels are reordered so that array
//! axes z, y, x run along S, A, R with positive scales. A rotated (oblique) grid is written
//! along its nearest world axes, centred where it was, with a warning giving the rotation lost.

use std::path::Path;
use std::sync::Arc;

use glam::DVec3;
use rayon::prelude::*;
use serde_json::{Value, json};
use zarrs::array::codec::ZstdCodec;
use zarrs::array::{ArrayBuilder, data_type};
use zarrs::filesystem::FilesystemStore;
use zarrs::group::GroupBuilder;

use crate::DataError;
use crate::geometry::Geometry;
use crate::pyramid;
use crate::segmentation::LabelData;
use crate::volume::VolumeData;
use crate::voxels::Voxels;

/// Choices of `hatchery convert`.
#[derive(Clone, Debug)]
pub struct ConvertOptions {
    /// Chunk side in voxels (default 64, as bricks are).
    pub chunk: u32,
    /// The multiscale's name (default: the output file's stem).
    pub name: String,
    /// Levels below the full resolution: until every axis fits one chunk where `None`.
    pub levels: Option<u32>,
}

impl Default for ConvertOptions {
    fn default() -> Self {
        ConvertOptions {
            chunk: 64,
            name: String::new(),
            levels: None,
        }
    }
}

/// For world axis x, y, z: the voxel axis that runs along it and whether it runs backwards.
fn axis_map(g: &Geometry) -> ([usize; 3], [bool; 3], f64) {
    let mut voxel_axis = [0usize; 3];
    let mut flipped = [false; 3];
    let mut worst = 1.0f64;
    let mut taken = [false; 3];
    for w in 0..3 {
        // The voxel axis most nearly along world axis w (each used once).
        let (v, c) = (0..3)
            .filter(|&v| !taken[v])
            .map(|v| (v, g.direction.col(v)[w]))
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .expect("three axes");
        taken[v] = true;
        voxel_axis[w] = v;
        flipped[w] = c < 0.0;
        worst = worst.min(c.abs() / g.direction.col(v).length());
    }
    (
        voxel_axis,
        flipped,
        worst.clamp(-1.0, 1.0).acos().to_degrees(),
    )
}

/// The volume reordered so that voxel axes i, j, k run along world x, y, z with positive
/// spacing; the rotation dropped in degrees (0 for a grid along the world axes).
fn along_world_axes(v: &VolumeData) -> Result<(VolumeData, f64), DataError> {
    let (voxel_axis, flipped, angle) = axis_map(&v.geometry);
    let dims = v.dims;
    let out_dims = voxel_axis.map(|a| dims[a]);
    let spacing = voxel_axis.map(|a| v.geometry.spacing[a]);
    // Input voxel of output voxel `o`.
    let source = move |o: [u32; 3]| {
        let mut ijk = [0u32; 3];
        for w in 0..3 {
            let a = voxel_axis[w];
            ijk[a] = if flipped[w] { dims[a] - 1 - o[w] } else { o[w] };
        }
        ijk
    };
    let centre = |g: &Geometry, d: [u32; 3]| {
        g.to_world()
            .transform_point3(DVec3::from_array(d.map(|n| (n as f64 - 1.0) / 2.0)))
    };
    let origin = if angle < 1e-6 {
        let s = source([0, 0, 0]);
        v.geometry
            .to_world()
            .transform_point3(DVec3::from_array(s.map(f64::from)))
    } else {
        // Keep the centre where it was.
        let c = centre(&v.geometry, dims);
        c - DVec3::from_array(spacing) * DVec3::from_array(out_dims.map(|n| (n as f64 - 1.0) / 2.0))
    };
    let geometry = Geometry::axis_aligned(spacing, origin.to_array());
    let (nx, ny) = (dims[0] as usize, dims[1] as usize);
    let index =
        move |ijk: [u32; 3]| ijk[0] as usize + nx * (ijk[1] as usize + ny * ijk[2] as usize);
    let [ox, oy, oz] = out_dims.map(|d| d as usize);
    fn reorder<T: Copy + Send + Sync>(
        values: &[T],
        (ox, oy, oz): (usize, usize, usize),
        at: impl Fn([u32; 3]) -> usize + Sync,
    ) -> Vec<T> {
        let mut out = Vec::with_capacity(ox * oy * oz);
        out.par_extend((0..ox * oy * oz).into_par_iter().map(|n| {
            let o = [
                (n % ox) as u32,
                ((n / ox) % oy) as u32,
                (n / (ox * oy)) as u32,
            ];
            values[at(o)]
        }));
        out
    }
    let at = |o: [u32; 3]| index(source(o));
    let voxels = match &v.voxels {
        Voxels::U8(x) => Voxels::U8(reorder(x, (ox, oy, oz), at)),
        Voxels::I8(x) => Voxels::I8(reorder(x, (ox, oy, oz), at)),
        Voxels::U16(x) => Voxels::U16(reorder(x, (ox, oy, oz), at)),
        Voxels::I16(x) => Voxels::I16(reorder(x, (ox, oy, oz), at)),
        Voxels::F32(x) => Voxels::F32(reorder(x, (ox, oy, oz), at)),
    };
    let mut out = VolumeData::from_voxels(out_dims, geometry, voxels)?;
    out.stored_type = v.stored_type;
    Ok((out, angle))
}

/// The multiscale metadata of `levels` (finest first), axes z, y, x in millimetres.
fn multiscales(name: &str, levels: &[VolumeData]) -> Value {
    let datasets: Vec<Value> = levels
        .iter()
        .enumerate()
        .map(|(k, l)| {
            let s = l.geometry.spacing;
            let o = l.geometry.origin;
            json!({
                "path": k.to_string(),
                "coordinateTransformations": [
                    {"type": "scale", "scale": [s.z, s.y, s.x]},
                    {"type": "translation", "translation": [o.z, o.y, o.x]},
                ],
            })
        })
        .collect();
    let axes: Vec<Value> = ["z", "y", "x"]
        .iter()
        .map(|a| json!({"name": a, "type": "space", "unit": "millimeter"}))
        .collect();
    json!([{ "name": name, "axes": axes, "datasets": datasets }])
}

fn zarr_error(path: &Path, e: impl std::fmt::Display) -> DataError {
    DataError::format(path, format!("writing OME-Zarr: {e}"))
}

/// Writes the arrays `0`, `1`, ... of `levels` into the group at `group` of `store`.
fn write_levels(
    store: &Arc<FilesystemStore>,
    out: &Path,
    group: &str,
    levels: &[VolumeData],
    chunk: u32,
) -> Result<(), DataError> {
    for (k, l) in levels.iter().enumerate() {
        let shape: Vec<u64> = [2, 1, 0].iter().map(|&a| l.dims[a] as u64).collect();
        let chunks: Vec<u64> = shape.iter().map(|&n| n.min(chunk as u64)).collect();
        let (dt, fill): (_, zarrs::array::FillValue) = match &l.voxels {
            Voxels::U8(_) => (data_type::uint8(), 0u8.into()),
            Voxels::I8(_) => (data_type::int8(), 0i8.into()),
            Voxels::U16(_) => (data_type::uint16(), 0u16.into()),
            Voxels::I16(_) => (data_type::int16(), 0i16.into()),
            Voxels::F32(_) => (data_type::float32(), f32::NAN.into()),
        };
        let array = ArrayBuilder::new(shape, chunks, dt, fill)
            .bytes_to_bytes_codecs(vec![Arc::new(ZstdCodec::new(3, false))])
            .dimension_names(["z", "y", "x"].into())
            .build(store.clone(), &format!("{group}/{k}"))
            .map_err(|e| zarr_error(out, e))?;
        array.store_metadata().map_err(|e| zarr_error(out, e))?;
        let all = array.subset_all();
        let stored =
            crate::with_voxels!(&l.voxels, v => array.store_array_subset(&all, v.as_slice()));
        stored.map_err(|e| zarr_error(out, e))?;
    }
    Ok(())
}

fn pyramid_of(
    top: VolumeData,
    options: &ConvertOptions,
    coarser: fn(&VolumeData) -> Result<VolumeData, DataError>,
) -> Result<Vec<VolumeData>, DataError> {
    let mut levels = vec![top];
    loop {
        let last = levels.last().expect("a level");
        let wanted = match options.levels {
            Some(n) => levels.len() <= n as usize,
            None => last.dims.iter().any(|&d| d > options.chunk),
        };
        if !wanted || !pyramid::has_coarser(last.dims) {
            return Ok(levels);
        }
        let next = coarser(last)?;
        levels.push(next);
    }
}

/// Writes `volume` to `out` (a new folder, replaced if it is an OME-Zarr hatchery can open) as an
/// OME-Zarr 0.5 multiscale image: level 0 the voxels as they are (reordered along the world
/// axes, see the module docs), each further level the 2×2×2 mean (pyramid.rs) until every axis
/// fits one chunk. `labels` (name, label map on the volume's grid) become `labels/<name>`, their
/// levels by majority, with the object names as `image-label` properties. Returns the warnings
/// (a rotation dropped). Errors: labels on another grid, `out` exists and is not a Zarr group, a
/// write failure (naming `out`).
pub fn write_ome_zarr(
    volume: &VolumeData,
    labels: Option<(&str, &LabelData)>,
    out: &Path,
    options: &ConvertOptions,
) -> Result<Vec<String>, DataError> {
    if options.chunk < 2 {
        return Err(DataError::Invalid(format!(
            "chunk side {} (at least 2)",
            options.chunk
        )));
    }
    let mut warnings = Vec::new();
    if let Some((label_name, l)) = labels {
        if label_name.is_empty() || label_name.contains(['/', '\\']) || label_name.starts_with('.')
        {
            return Err(DataError::Invalid(format!(
                "label image name {label_name:?}: a non-empty folder name without slashes"
            )));
        }
        let same_grid = l.dims == volume.dims
            && (l.geometry.origin - volume.geometry.origin).length() < 1e-4
            && (l.geometry.spacing - volume.geometry.spacing).length() < 1e-6
            && l.geometry
                .direction
                .abs_diff_eq(volume.geometry.direction, 1e-6);
        if !same_grid {
            return Err(DataError::Invalid(format!(
                "the label map ({:?} voxels, {}) is not on the volume's grid ({:?} voxels, {}): \
                 OME-Zarr label images share their image's grid",
                l.dims,
                l.geometry.describe(),
                volume.dims,
                volume.geometry.describe()
            )));
        }
    }
    if out.exists() {
        if !super::is_zarr(out) {
            return Err(DataError::format(
                out,
                "exists and is not a Zarr group: not replaced (remove it or choose another name)",
            ));
        }
        std::fs::remove_dir_all(out).map_err(|e| DataError::io(out, e))?;
    }
    let (top, angle) = along_world_axes(volume)?;
    if angle > 1e-6 {
        warnings.push(format!(
            "the grid is rotated {angle:.2}° from the world axes: written along its nearest axes, \
             centred where it was (OME-Zarr 0.5 places voxels by scale and translation only)"
        ));
    }
    let name = if options.name.is_empty() {
        out.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    } else {
        options.name.clone()
    };
    let levels = pyramid_of(top, options, pyramid::coarser_volume)?;
    let store = Arc::new(FilesystemStore::new(out).map_err(|e| zarr_error(out, e))?);
    let mut root = GroupBuilder::new()
        .build(store.clone(), "/")
        .map_err(|e| zarr_error(out, e))?;
    root.attributes_mut().insert(
        "ome".into(),
        json!({"version": "0.5", "multiscales": multiscales(&name, &levels)}),
    );
    root.store_metadata().map_err(|e| zarr_error(out, e))?;
    write_levels(&store, out, "", &levels, options.chunk)?;

    if let Some((label_name, l)) = labels {
        let as_volume = VolumeData::from_voxels(l.dims, l.geometry, Voxels::U16(l.ids.clone()))?;
        let (top, _) = along_world_axes(&as_volume)?;
        let levels = pyramid_of(top, options, pyramid::coarser_label_volume)?;
        let mut group = GroupBuilder::new()
            .build(store.clone(), "/labels")
            .map_err(|e| zarr_error(out, e))?;
        group.attributes_mut().insert(
            "ome".into(),
            json!({"version": "0.5", "labels": [label_name]}),
        );
        group.store_metadata().map_err(|e| zarr_error(out, e))?;
        let properties: Vec<Value> = l
            .objects
            .iter()
            // The stand-in names of unnamed objects are not written as names.
            .filter(|(id, name)| **name != format!("object {id}"))
            .map(|(id, name)| json!({"label-value": id, "name": name}))
            .collect();
        let path = format!("/labels/{label_name}");
        let mut group = GroupBuilder::new()
            .build(store.clone(), &path)
            .map_err(|e| zarr_error(out, e))?;
        group.attributes_mut().insert(
            "ome".into(),
            json!({
                "version": "0.5",
                "multiscales": multiscales(label_name, &levels),
                "image-label": {"version": "0.5", "properties": properties},
            }),
        );
        group.store_metadata().map_err(|e| zarr_error(out, e))?;
        write_levels(&store, out, &path, &levels, options.chunk)?;
    }
    Ok(warnings)
}
