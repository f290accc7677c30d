//! OME-Zarr images (OME-NGFF 0.4 on Zarr v2, 0.5 on Zarr v3; the axis-less 0.1–0.3 read as
//! `t, c, z, y, x`): a multiscale pyramid of arrays, each level placed by its
//! `coordinateTransformations` (scale, then translation, then the multiscale's own), and label
//! images under `labels/` whose `image-label` properties may name the objects.
//!
//! hatchery's convention, since the format names axes but no anatomy: the space axes `x`, `y`,
//! `z` are world R, A, S (RAS+, see [`crate::geometry`]); a voxel's centre lies at
//! `scale · index + translation` in the axis unit, converted to millimetres. Voxel axis i is the
//! array's last (fastest) space axis, so the voxels are used in the array's own order without a
//! transpose. Non-space axes (time, channel) are read at index 0, with a warning when they hold
//! more.
//!
//! A path names an image group (`specimen.zarr`) or a label image (`specimen.zarr/labels/nuclei`);
//! [`crate::volume_file::LoadOptions::array`] may name a label image of the group instead.

mod metadata;
mod write;

use metadata::{compose, dataset_path, ome_attributes, parse_axes, unit_mm};

pub use write::{ConvertOptions, write_ome_zarr};

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat3, DVec3};
use serde_json::{Map, Value};
use zarrs::array::{Array, ArraySubset, data_type};
use zarrs::filesystem::FilesystemStore;

use crate::DataError;
use crate::geometry::Geometry;
use crate::volume::VolumeData;
use crate::voxels::{MAX_VOXELS, Voxels};

/// Whether `path` is a Zarr group (v2 `.zgroup`/`.zattrs` or v3 `zarr.json`).
pub fn is_zarr(path: &Path) -> bool {
    path.is_dir()
        && ["zarr.json", ".zattrs", ".zgroup"]
            .iter()
            .any(|f| path.join(f).is_file())
}

/// The Zarr group a path means: the folder itself, or the folder of a group metadata file
/// (`zarr.json`, `.zattrs`, `.zgroup`) — what a file dialog, which picks files, can choose.
pub fn group_of(path: &Path) -> &Path {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase());
    match (name.as_deref(), path.parent()) {
        (Some("zarr.json" | ".zattrs" | ".zgroup"), Some(parent)) if is_zarr(parent) => parent,
        _ => path,
    }
}

/// An axis of an image's arrays.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    pub name: String,
    /// `space`, `time`, `channel`, or empty where the file does not say.
    pub kind: String,
    /// The unit as written (`micrometer`), if any.
    pub unit: Option<String>,
}

/// One level of a multiscale pyramid.
#[derive(Clone, Debug)]
pub struct Level {
    /// The array's path within the image group (`0`, `s1`, ...).
    pub path: String,
    /// The array's shape, in the array's axis order.
    pub shape: Vec<u64>,
    /// Voxels along i, j, k (i: the fastest space axis).
    pub dims: [u32; 3],
    /// Voxel → world (RAS+ mm).
    pub geometry: Geometry,
}

/// An opened OME-Zarr multiscale image (or label image).
pub struct Multiscale {
    pub path: PathBuf,
    /// The OME-NGFF version the metadata states (`0.4`, `0.5`, ...).
    pub version: String,
    pub name: String,
    pub axes: Vec<Axis>,
    /// Finest first, as the file lists them.
    pub levels: Vec<Level>,
    /// How the voxels were placed, for `hatchery info`.
    pub placement: String,
    /// What reading had to assume (no unit, extra channels), one line each.
    pub warnings: Vec<String>,
    /// The `image-label` metadata where this is a label image.
    image_label: Option<Value>,
    /// Each level's array (opened once: bricks read boxes of them).
    arrays: Vec<Array<FilesystemStore>>,
    grids: Vec<crate::brick_source::LevelGrid>,
}

fn group_attributes(
    store: &Arc<FilesystemStore>,
    path: &Path,
) -> Result<Map<String, Value>, DataError> {
    let group = zarrs::group::Group::open(store.clone(), "/")
        .map_err(|e| DataError::format(path, format!("not a readable Zarr group: {e}")))?;
    Ok(group.attributes().clone())
}

fn open_store(path: &Path) -> Result<Arc<FilesystemStore>, DataError> {
    FilesystemStore::new(path)
        .map(Arc::new)
        .map_err(|e| DataError::format(path, format!("cannot open as a Zarr store: {e}")))
}

impl Multiscale {
    /// Opens the image group at `path` (the first of its `multiscales`) and every level's array
    /// metadata. Errors: not a Zarr group, no `multiscales`, not three space axes (the last
    /// three, as the spec requires), a transformation other than scale/translation, a zero scale.
    pub fn open(path: &Path) -> Result<Self, DataError> {
        let v3_array = std::fs::read_to_string(path.join("zarr.json"))
            .ok()
            .and_then(|t| serde_json::from_str::<Value>(&t).ok())
            .is_some_and(|m| m.get("node_type").and_then(Value::as_str) == Some("array"));
        if path.join(".zarray").is_file() || v3_array {
            return Err(DataError::format(
                path,
                "a Zarr array, not an OME-Zarr image: name the image group (the folder with the \
                 `multiscales` metadata, usually the one above)",
            ));
        }
        let store = open_store(path)?;
        let attributes = group_attributes(&store, path)?;
        let ome = ome_attributes(&attributes);
        let Some(Value::Object(ms)) = ome
            .get("multiscales")
            .and_then(Value::as_array)
            .and_then(|l| l.first())
        else {
            let hint = if ome.contains_key("labels") || ome.contains_key("plate") {
                " (a `labels` or `plate` group: name one image in it)"
            } else {
                ""
            };
            return Err(DataError::format(
                path,
                format!("no OME `multiscales` metadata{hint}"),
            ));
        };
        let version = ms
            .get("version")
            .or_else(|| ome.get("version"))
            .and_then(Value::as_str)
            .unwrap_or("0.4")
            .to_owned();
        let datasets = ms
            .get("datasets")
            .and_then(Value::as_array)
            .filter(|d| !d.is_empty())
            .ok_or_else(|| DataError::format(path, "multiscales without `datasets`"))?;
        let first = dataset_path(path, &datasets[0])?;
        let rank = open_array(&store, path, &first)?.shape().len();
        let axes = parse_axes(path, ms, rank)?;
        if axes.len() != rank {
            return Err(DataError::format(
                path,
                format!("{} axes for {rank}-D arrays", axes.len()),
            ));
        }
        let space: Vec<usize> = (0..rank).filter(|&a| axes[a].kind == "space").collect();
        if space.len() != 3 || space[0] != rank - 3 {
            let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
            return Err(DataError::unsupported(
                path,
                format!(
                    "axes {names:?}: hatchery reads volumes, whose last three axes are space axes \
                     ({} space axes here)",
                    space.len()
                ),
            ));
        }
        let mut warnings = Vec::new();
        // World axis (0 = R/x, 1 = A/y, 2 = S/z) of voxel axes i, j, k.
        let named: Option<Vec<usize>> = (0..3)
            .map(|v| {
                ["x", "y", "z"]
                    .iter()
                    .position(|&n| axes[rank - 1 - v].name == n)
            })
            .collect();
        let world_axis = match named {
            Some(w) if w[0] != w[1] && w[1] != w[2] && w[0] != w[2] => w,
            _ => {
                warnings.push(format!(
                    "space axes are not named x, y, z ({:?}): placed as x, y, z from fastest to slowest",
                    axes[rank - 3..].iter().map(|a| &a.name).collect::<Vec<_>>()
                ));
                vec![0, 1, 2]
            }
        };
        let mut mm = [1.0; 3];
        for v in 0..3 {
            let a = &axes[rank - 1 - v];
            mm[v] = match a.unit.as_deref() {
                Some(u) => unit_mm(u).unwrap_or_else(|| {
                    warnings.push(format!(
                        "axis {}: unknown unit {u:?}, taken as millimetres",
                        a.name
                    ));
                    1.0
                }),
                None => 1.0,
            };
        }
        if axes[rank - 3..].iter().all(|a| a.unit.is_none()) {
            warnings.push("the space axes give no unit: taken as millimetres".into());
        }
        let (mut levels, mut arrays) = (Vec::new(), Vec::new());
        for d in datasets {
            let level_path = dataset_path(path, d)?;
            let array = open_array(&store, path, &level_path)?;
            let shape = array.shape().to_vec();
            if shape.len() != rank {
                return Err(DataError::format(
                    path,
                    format!(
                        "level {level_path} has {} dimensions, level {first} {rank}",
                        shape.len()
                    ),
                ));
            }
            let (mut scale, mut shift) = (vec![1.0; rank], vec![0.0; rank]);
            compose(
                path,
                d.get("coordinateTransformations"),
                &mut scale,
                &mut shift,
            )?;
            compose(
                path,
                ms.get("coordinateTransformations"),
                &mut scale,
                &mut shift,
            )?;
            let mut dims = [0u32; 3];
            let mut spacing = [0.0; 3];
            let mut direction = DMat3::ZERO;
            let mut origin = DVec3::ZERO;
            for v in 0..3 {
                let a = rank - 1 - v;
                dims[v] = u32::try_from(shape[a]).map_err(|_| {
                    DataError::format(
                        path,
                        format!("level {level_path}: {} voxels along an axis", shape[a]),
                    )
                })?;
                if scale[a] == 0.0 {
                    return Err(DataError::format(
                        path,
                        format!("level {level_path}: zero scale"),
                    ));
                }
                spacing[v] = scale[a].abs() * mm[v];
                let mut column = DVec3::ZERO;
                column[world_axis[v]] = scale[a].signum();
                *direction.col_mut(v) = column;
                origin[world_axis[v]] = shift[a] * mm[v];
            }
            let geometry = Geometry {
                spacing: DVec3::from_array(spacing),
                direction,
                origin,
            };
            geometry.check().map_err(|e| e.in_file(path))?;
            levels.push(Level {
                path: level_path,
                shape,
                dims,
                geometry,
            });
            arrays.push(array);
        }
        for (a, axis) in axes[..rank - 3].iter().enumerate() {
            if levels[0].shape[a] > 1 {
                warnings.push(format!(
                    "{} axis {:?} holds {} entries: reading the first",
                    if axis.kind.is_empty() {
                        "non-space"
                    } else {
                        &axis.kind
                    },
                    axis.name,
                    levels[0].shape[a]
                ));
            }
        }
        let name = ms
            .get("name")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_owned();
        let units: Vec<String> = (0..3)
            .map(|v| {
                axes[rank - 1 - v]
                    .unit
                    .clone()
                    .unwrap_or_else(|| "no unit".into())
            })
            .collect();
        let placement = format!(
            "OME-Zarr {version} multiscales{}: {} levels, scale + translation in {}; x, y, z = R, A, S",
            if name.is_empty() {
                String::new()
            } else {
                format!(" {name:?}")
            },
            levels.len(),
            units.join(" / ")
        );
        Ok(Multiscale {
            path: path.to_path_buf(),
            version,
            name,
            axes,
            placement,
            warnings,
            image_label: ome.get("image-label").cloned(),
            grids: levels
                .iter()
                .map(|l| crate::brick_source::LevelGrid {
                    dims: l.dims,
                    geometry: l.geometry,
                })
                .collect(),
            levels,
            arrays,
        })
    }

    /// Reads level `level` whole into memory, in its stored type where hatchery keeps it
    /// (u8, i8, u16, i16, f32; other numbers as f32). Errors: more than
    /// [`MAX_VOXELS`] voxels, an unreadable chunk, a data type that is not a number.
    pub fn read_level(&self, level: usize) -> Result<VolumeData, DataError> {
        let path = &self.path;
        let Some(l) = self.levels.get(level) else {
            return Err(DataError::Invalid(format!(
                "{}: no level {level} (it has {})",
                path.display(),
                self.levels.len()
            )));
        };
        let voxels: u64 = l.dims.iter().map(|&d| d as u64).product();
        if voxels > MAX_VOXELS {
            return Err(DataError::TooLarge {
                path: path.clone(),
                voxels,
                limit: MAX_VOXELS,
            });
        }
        let (values, stored) = self.read_subset(level, [0; 3], l.dims)?;
        let mut volume =
            VolumeData::from_voxels(l.dims, l.geometry, values).map_err(|e| e.in_file(path))?;
        volume.stored_type = stored;
        volume.placement = if level == 0 {
            self.placement.clone()
        } else {
            format!("{} (level {level}: {})", self.placement, l.path)
        };
        volume.warnings = self.warnings.clone();
        Ok(volume)
    }

    /// Voxels `lo .. lo + size` (voxel axes i, j, k) of `level`, at index 0 of non-space axes,
    /// with the name of the stored type.
    fn read_subset(
        &self,
        level: usize,
        lo: [u32; 3],
        size: [u32; 3],
    ) -> Result<(Voxels, &'static str), DataError> {
        let path = &self.path;
        let l = &self.levels[level];
        let array = &self.arrays[level];
        let rank = l.shape.len();
        let ranges: Vec<std::ops::Range<u64>> = (0..rank)
            .map(|a| match (rank - 1).checked_sub(a) {
                Some(v) if v < 3 => lo[v] as u64..(lo[v] + size[v]) as u64,
                _ => 0..1,
            })
            .collect();
        let subset = ArraySubset::new_with_ranges(&ranges);
        let fail =
            |e: zarrs::array::ArrayError| DataError::format(path, format!("level {}: {e}", l.path));
        let dt = array.data_type();
        // Types hatchery keeps natively, then those it widens to f32 (through f64, as the other
        // loaders do).
        macro_rules! read {
            ($($t:ty => $f:ident $variant:ident),*; $($w:ty => $wf:ident),*) => {
                $(if *dt == data_type::$f() {
                    let v: Vec<$t> = array.retrieve_array_subset(&subset).map_err(fail)?;
                    return Ok((Voxels::$variant(v), stringify!($f)));
                })*
                $(if *dt == data_type::$wf() {
                    let v: Vec<$w> = array.retrieve_array_subset(&subset).map_err(fail)?;
                    let v = v.into_iter().map(|x| x as f64 as f32).collect();
                    return Ok((Voxels::F32(v), stringify!($wf)));
                })*
            };
        }
        read!(
            u8 => uint8 U8, i8 => int8 I8, u16 => uint16 U16, i16 => int16 I16,
            f32 => float32 F32;
            u32 => uint32, i32 => int32, u64 => uint64, i64 => int64, f64 => float64
        );
        Err(DataError::unsupported(
            path,
            format!(
                "level {}: data type {dt:?} is not a number hatchery reads",
                l.path
            ),
        ))
    }

    /// The finest level one volume in memory may hold ([`MAX_VOXELS`]), with a warning when
    /// that is not level 0 (a pyramid's coarser level stands in for the whole). Errors: as
    /// [`Self::read_level`]; even the coarsest level is too large.
    pub fn read_finest_in_memory(&self) -> Result<VolumeData, DataError> {
        let count = |l: &Level| l.dims.iter().map(|&d| d as u64).product::<u64>();
        let level = (0..self.levels.len())
            .find(|&k| count(&self.levels[k]) <= MAX_VOXELS)
            .unwrap_or(self.levels.len() - 1);
        let mut volume = self.read_level(level)?;
        if level > 0 {
            let [x, y, z] = self.levels[0].dims;
            let [cx, cy, cz] = self.levels[level].dims;
            volume.warnings.push(format!(
                "level 0 ({x}×{y}×{z} voxels) exceeds the {MAX_VOXELS}-voxel limit of a volume in \
                 memory: read level {level} ({cx}×{cy}×{cz}) instead"
            ));
        }
        Ok(volume)
    }

    /// Object names of a label image: `image-label.properties` entries' `name` (or `class`),
    /// by `label-value`. Empty for other images.
    pub fn label_names(&self) -> BTreeMap<u16, String> {
        let mut names = BTreeMap::new();
        let Some(props) = self
            .image_label
            .as_ref()
            .and_then(|l| l.get("properties"))
            .and_then(Value::as_array)
        else {
            return names;
        };
        for p in props {
            let id = p.get("label-value").and_then(Value::as_u64);
            let name = ["name", "class", "label-name"]
                .iter()
                .find_map(|k| p.get(*k).and_then(Value::as_str));
            if let (Some(id), Some(name)) = (id, name)
                && let Ok(id) = u16::try_from(id)
            {
                names.insert(id, name.to_owned());
            }
        }
        names
    }

    /// Whether this is a label image (it carries `image-label` metadata).
    pub fn is_label_image(&self) -> bool {
        self.image_label.is_some()
    }
}

/// The label images an image group lists in `labels/` (empty where it has none).
pub fn label_images(image: &Path) -> Vec<String> {
    let dir = image.join("labels");
    if !is_zarr(&dir) {
        return Vec::new();
    }
    let Ok(store) = open_store(&dir) else {
        return Vec::new();
    };
    let Ok(attributes) = group_attributes(&store, &dir) else {
        return Vec::new();
    };
    ome_attributes(&attributes)
        .get("labels")
        .and_then(Value::as_array)
        .map(|l| {
            l.iter()
                .filter_map(|v| v.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default()
}

/// Where to read: the group at `path`, or its label image `array` (`labels/<array>`).
/// Errors: `array` is not one of the group's label images (the error lists them).
pub fn resolve(path: &Path, array: Option<&str>) -> Result<PathBuf, DataError> {
    let Some(name) = array.filter(|a| !a.is_empty()) else {
        return Ok(path.to_path_buf());
    };
    let name = name.strip_prefix("labels/").unwrap_or(name);
    let listed = label_images(path);
    if listed.iter().any(|l| l == name) || is_zarr(&path.join("labels").join(name)) {
        return Ok(path.join("labels").join(name));
    }
    Err(DataError::format(
        path,
        format!(
            "no label image {name:?} in labels/ (it lists {})",
            if listed.is_empty() {
                "none".to_string()
            } else {
                listed.join(", ")
            }
        ),
    ))
}

/// A label map from an OME-Zarr group: the label image `array` (`labels/<array>`) where given;
/// else the group itself where it is a label image or has none; else the first label image it
/// lists (with a warning naming the others). Returns its finest level and the object names of its
/// `image-label` properties.
pub fn load_label_image(
    path: &Path,
    array: Option<&str>,
) -> Result<(VolumeData, BTreeMap<u16, String>), DataError> {
    let path = group_of(path);
    let mut chosen = resolve(path, array)?;
    let mut note = None;
    if array.is_none_or(str::is_empty) {
        let listed = label_images(path);
        let is_label = Multiscale::open(path).is_ok_and(|m| m.is_label_image());
        if !is_label && let Some(first) = listed.first() {
            chosen = path.join("labels").join(first);
            note = Some(format!(
                "reading label image {first:?} of labels/{}",
                if listed.len() > 1 {
                    format!(" (also {}: choose with `array`)", listed[1..].join(", "))
                } else {
                    String::new()
                }
            ));
        }
    }
    let image = Multiscale::open(&chosen)?;
    let mut volume = image.read_finest_in_memory()?;
    volume.warnings.extend(note);
    Ok((volume, image.label_names()))
}

/// Loads the OME-Zarr image at `path` (or its label image `array`): its finest level, or where
/// that holds more than [`MAX_VOXELS`] the finest level within it, with a warning naming it
/// (a pyramid's point is that a coarser level stands in for the whole).
pub fn load_ome_zarr(path: &Path, array: Option<&str>) -> Result<VolumeData, DataError> {
    let path = group_of(path);
    let image = Multiscale::open(&resolve(path, array)?)?;
    image.read_finest_in_memory()
}

fn open_array(
    store: &Arc<FilesystemStore>,
    path: &Path,
    level: &str,
) -> Result<Array<FilesystemStore>, DataError> {
    Array::open(store.clone(), &format!("/{level}"))
        .map_err(|e| DataError::format(path, format!("level {level}: {e}")))
}

/// Bricks of an OME-Zarr pyramid read box by box from its chunks (only the chunks a box touches).
impl crate::brick_source::BrickSource for Multiscale {
    fn levels(&self) -> &[crate::brick_source::LevelGrid] {
        &self.grids
    }

    fn read_box(&self, level: usize, lo: [u32; 3], size: [u32; 3]) -> Result<Voxels, DataError> {
        crate::brick_source::check_box(&self.grids, level, lo, size)
            .map_err(|e| e.in_file(&self.path))?;
        Ok(self.read_subset(level, lo, size)?.0)
    }
}
