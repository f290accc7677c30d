//! VTK XML ImageData volumes (`.vti`).
//!
//! Parsed by hand (quick-xml for the markup, our own base64; flate2, lz4_flex and lzma-rust2
//! for compressed blocks) rather than with the vtkio crate: its 0.7 line is only a release
//! candidate, panics on truncated data arrays, silently drops arrays whose last compressed
//! block is full, and decodes every array before the grid size could be checked.
//!
//! `markup` reads the XML up to the appended data, `decode` one array's values; this module
//! picks the array, assembles the pieces and places the grid in the world.

mod decode;
mod markup;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_grid;

use std::path::Path;

use glam::{DMat3, DVec3};

use crate::geometry::Geometry;
use crate::voxels::MAX_VOXELS;
use crate::voxels::Voxels;
use crate::{DataError, VolumeData};
use decode::{Loss, read_array};
use markup::{ArrayInfo, DataSet, Markup, Piece, parse_markup};

/// The grid the pieces span may be this many times the voxels they hold (pieces missing from a
/// tiling leave NaN gaps) ...
const MAX_SPARSITY: u64 = 16;
/// ... or this many voxels larger, whatever the factor (small grids cost little).
const SPARSE_VOXELS: u64 = 1 << 24;

/// Loads one data array of a VTK XML ImageData file as a volume, as VTK's
/// `vtkXMLImageDataReader` reads it.
///
/// * The array: `array` names any point or cell data array (point data first, if both have
///   one of that name); an unknown name is an error that lists the file's arrays. Without a
///   name: the active scalars of the point data (`<PointData Scalars="name">`), else its first
///   array that can be read (one component, a numeric type), else the same for the cell data.
/// * Placement, as `vtkImageData::TransformContinuousIndexToPhysicalPoint`: point (i, j, k) of
///   the extent (indices counted as in the file, so an extent starting at 2 starts at
///   `Origin + Direction · (Spacing ⊙ (2, …))`) is at `Origin + Direction · (Spacing ⊙ (i, j,
///   k))`, with `Direction` row-major as VTK writes it (identity when absent). Cell data: one
///   voxel per cell, at the cell centre (i + ½, j + ½, k + ½). A negative spacing is folded into
///   the direction (the spacing kept positive) and non-unit direction columns into the
///   spacing, so the transform is unchanged. A zero spacing is taken as 1 and noted in
///   `placement`. VTK files carry no anatomical frame: the world is taken as given (no LPS
///   flip).
/// * Values: UInt8, Int8, UInt16, Int16 and Float32 arrays keep their type; Float64 and the
///   32- and 64-bit integers become float32 (`stored_type` names the file's type, and
///   `placement` counts integers that float32 rounds and Float64 values beyond its range).
///   Non-finite values are kept ("no data"). Only single-component arrays are read.
/// * Data arrays may be ASCII, inline binary (base64) or appended (raw or base64),
///   uncompressed or compressed by `vtkZLibDataCompressor`, `vtkLZ4DataCompressor` or
///   `vtkLZMADataCompressor`, with UInt32 or UInt64 headers, either byte order.
/// * Pieces: the volume covers the bounding box of the pieces' extents, each piece's values in
///   their place; voxels no piece covers are NaN (noted in `placement`). A grid more than 16
///   times (and 2^24 voxels) larger than the voxels its pieces hold is refused.
pub fn load_vti(path: &Path, array: Option<&str>) -> Result<VolumeData, DataError> {
    let bytes = crate::files::read(path).map_err(|e| DataError::io(path, e))?;
    let file = parse_markup(path, &bytes)?;
    // Numbered as in the file, for errors.
    let pieces: Vec<(usize, &Piece)> = file
        .pieces
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let Some(&(_, first)) = pieces.first() else {
        return Err(DataError::format(
            path,
            "the ImageData has no piece with a non-empty extent",
        ));
    };
    let (cells, chosen) = choose_array(path, first, array)?;
    let name = chosen.name.clone();
    let array_error =
        |message: String| DataError::format(path, format!("data array `{name}`: {message}"));
    let scalar = chosen.scalar().map_err(array_error)?;
    let components = chosen.components().map_err(array_error)?;
    if components != 1 {
        return Err(DataError::unsupported(
            path,
            format!(
                "data array `{name}` has {components} components, only single-component \
                 (scalar) arrays are supported; {}",
                list_arrays(first)
            ),
        ));
    }

    // Everything about the grid is checked before any voxel memory is allocated. Extents
    // here are of the data: points, or cells (one fewer along each axis).
    let data_extent = |e: &[i64; 6]| -> [i64; 6] {
        std::array::from_fn(|i| if cells && i % 2 == 1 { e[i] - 1 } else { e[i] })
    };
    let mut bounds = first.extent;
    for (_, piece) in &pieces {
        for a in 0..3 {
            bounds[2 * a] = bounds[2 * a].min(piece.extent[2 * a]);
            bounds[2 * a + 1] = bounds[2 * a + 1].max(piece.extent[2 * a + 1]);
        }
    }
    let whole = data_extent(&bounds);
    let dims_u64 = extent_dims(&whole);
    if dims_u64.iter().any(|&d| d < 2) {
        return Err(DataError::unsupported(
            path,
            format!(
                "only 3-D volumes with at least 2 voxels per axis are supported, {} data dims \
                 are {dims_u64:?}",
                if cells { "cell" } else { "point" }
            ),
        ));
    }
    let voxel_count = dims_u64
        .iter()
        .try_fold(1u64, |acc, &d| acc.checked_mul(d))
        .unwrap_or(u64::MAX);
    if voxel_count > MAX_VOXELS {
        return Err(DataError::TooLarge {
            path: path.to_path_buf(),
            voxels: voxel_count,
            limit: MAX_VOXELS,
        });
    }
    // Voxels no piece covers become NaN, memory the file does not pay for: a few small pieces
    // far apart would span a huge grid of nothing. Allow the gaps of a tiling with pieces
    // missing, not more.
    let held = pieces
        .iter()
        .map(|(_, p)| extent_dims(&data_extent(&p.extent)).iter().product::<u64>())
        .fold(0u64, u64::saturating_add);
    if voxel_count > (held.saturating_mul(MAX_SPARSITY)).max(held.saturating_add(SPARSE_VOXELS)) {
        return Err(DataError::unsupported(
            path,
            format!(
                "the pieces hold {held} voxels but span a grid of {voxel_count}; grids more \
                 than {MAX_SPARSITY} times larger than their pieces are not read"
            ),
        ));
    }
    // Each dim is at most MAX_VOXELS / 4 here, so it fits u32.
    let dims = dims_u64.map(|d| d as u32);

    let mut loss = Loss::default();
    let mut parts = Vec::with_capacity(pieces.len());
    for &(index, piece) in &pieces {
        let extent = data_extent(&piece.extent);
        let piece_dims = extent_dims(&extent);
        if piece_dims.contains(&0) {
            continue; // A piece one point thick has no cells.
        }
        let data = if cells { &piece.cell } else { &piece.point };
        let array = data.arrays.iter().find(|a| a.name == name).ok_or_else(|| {
            DataError::format(
                path,
                format!("piece {index} has no {} array `{name}`", set_name(cells)),
            )
        })?;
        let scalar = array.scalar().map_err(array_error)?;
        if array.components().map_err(array_error)? != 1 {
            return Err(array_error(format!(
                "has several components in piece {index}"
            )));
        }
        let count = piece_dims.iter().product::<u64>() as usize;
        let (voxels, piece_loss) =
            read_array(array, scalar, count, &file.encoding, file.appended.as_ref())
                .map_err(array_error)?;
        loss.add(piece_loss);
        let offset: [usize; 3] = std::array::from_fn(|a| (extent[2 * a] - whole[2 * a]) as usize);
        parts.push((voxels, piece_dims.map(|d| d as usize), offset));
    }
    let (voxels, uncovered) = assemble(parts, dims.map(|d| d as usize));

    let lower = [whole[0], whole[2], whole[4]];
    let (geometry, mut notes) = geometry(path, &file, lower, cells)?;
    if uncovered > 0 {
        notes.push(format!("{uncovered} voxels in no piece are NaN"));
    }
    if loss.rounded > 0 {
        notes.push(format!(
            "{} {} values rounded to float32",
            loss.rounded,
            scalar.type_name()
        ));
    }
    if loss.overflowed > 0 {
        notes.push(format!(
            "{} float64 values beyond the float32 range became ±inf (no data)",
            loss.overflowed
        ));
    }
    let mut volume =
        VolumeData::from_voxels(dims, geometry, voxels).map_err(|e| e.in_file(path))?;
    volume.stored_type = scalar.type_name();
    let b = bounds;
    volume.placement = format!(
        "VTK Origin/Spacing/Direction, extent {}..{} {}..{} {}..{}, {} `{name}`{}",
        b[0],
        b[1],
        b[2],
        b[3],
        b[4],
        b[5],
        if cells {
            "cell data (cell centres)"
        } else {
            "point data"
        },
        notes.iter().map(|n| format!("; {n}")).collect::<String>()
    );
    Ok(volume)
}

/// Picks the array to read from the first piece: `(cell data?, array)`.
fn choose_array<'p, 'a>(
    path: &Path,
    piece: &'p Piece<'a>,
    wanted: Option<&str>,
) -> Result<(bool, &'p ArrayInfo<'a>), DataError> {
    let sets = [(false, &piece.point), (true, &piece.cell)];
    if let Some(wanted) = wanted {
        return sets
            .iter()
            .find_map(|&(cells, set)| {
                let array = set.arrays.iter().find(|a| a.name == wanted)?;
                Some((cells, array))
            })
            .ok_or_else(|| {
                DataError::format(
                    path,
                    format!("has no data array `{wanted}`; {}", list_arrays(piece)),
                )
            });
    }
    for (cells, set) in sets {
        let active = set
            .active
            .as_deref()
            .and_then(|name| set.arrays.iter().find(|a| a.name == name));
        // The file's own choice, even if it cannot be read (the error lists the others).
        if let Some(array) = active {
            return Ok((cells, array));
        }
        if let Some(array) = set.arrays.iter().find(|a| a.is_scalar()) {
            return Ok((cells, array));
        }
    }
    // Nothing readable: the first array, to say why it cannot be read.
    sets.iter()
        .find_map(|&(cells, set)| Some((cells, set.arrays.first()?)))
        .ok_or_else(|| {
            DataError::format(path, "the ImageData piece has no point or cell data array")
        })
}

fn set_name(cells: bool) -> &'static str {
    if cells { "cell data" } else { "point data" }
}

/// `point data: `a` (Float32, active), `b` (UInt8 × 3); cell data: none`, for errors.
fn list_arrays(piece: &Piece) -> String {
    let list = |set: &DataSet| -> String {
        if set.arrays.is_empty() {
            return "none".into();
        }
        let arrays: Vec<String> = set
            .arrays
            .iter()
            .map(|a| {
                let mut about = a.type_name.clone().unwrap_or_else(|| "no type".into());
                if let Some(c) = a.components.as_deref().filter(|&c| c != "1") {
                    about.push_str(&format!(" × {c}"));
                }
                if set.active.as_deref() == Some(a.name.as_str()) {
                    about.push_str(", active");
                }
                format!("`{}` ({about})", a.name)
            })
            .collect();
        arrays.join(", ")
    };
    format!(
        "the file's arrays are: point data {}; cell data {}",
        list(&piece.point),
        list(&piece.cell)
    )
}

/// Counts along each axis of an inclusive extent (0 where it is empty).
fn extent_dims(e: &[i64; 6]) -> [u64; 3] {
    std::array::from_fn(|a| (e[2 * a + 1] - e[2 * a] + 1).max(0) as u64)
}

/// The voxel → world transform of voxel 0 at structured index `lower` (+ ½ for cells).
fn geometry(
    path: &Path,
    file: &Markup,
    lower: [i64; 3],
    cells: bool,
) -> Result<(Geometry, Vec<String>), DataError> {
    let mut notes = Vec::new();
    let d = &file.direction;
    let mut columns = [DVec3::ZERO; 3];
    let mut spacing = [0.0; 3];
    let mut origin = DVec3::from_array(file.origin);
    for a in 0..3 {
        let mut s = file.spacing[a];
        if s == 0.0 {
            notes.push(format!("Spacing 0 along axis {a} taken as 1"));
            s = 1.0;
        }
        // Direction · (Spacing ⊙ ijk): column a of Direction scaled by spacing a.
        let column = DVec3::new(d[a], d[3 + a], d[6 + a]) * s;
        let length = column.length();
        if !length.is_finite() || length == 0.0 {
            return Err(DataError::format(
                path,
                format!("Direction {d:?} has a zero column {a}"),
            ));
        }
        let first = lower[a] as f64 + if cells { 0.5 } else { 0.0 };
        origin += column * first;
        spacing[a] = length;
        columns[a] = column / length;
    }
    let geometry = Geometry {
        spacing: DVec3::from_array(spacing),
        direction: DMat3::from_cols(columns[0], columns[1], columns[2]),
        origin,
    };
    geometry.check().map_err(|e| e.in_file(path))?;
    Ok((geometry, notes))
}

/// Puts the pieces' values (`(values, dims, offset)`) in place in a grid of `dims`; later
/// pieces win where pieces overlap (they share their boundary points). Returns the voxels
/// and how many no piece covered (NaN, which needs float32).
fn assemble(mut parts: Vec<(Voxels, [usize; 3], [usize; 3])>, dims: [usize; 3]) -> (Voxels, u64) {
    if parts.len() == 1 && parts[0].1 == dims {
        let (voxels, _, _) = parts.remove(0);
        return (voxels, 0);
    }
    let count = dims.iter().product::<usize>();
    let mut covered = vec![false; count];
    for (_, part_dims, offset) in &parts {
        copy_rows(
            &mut covered,
            dims,
            &vec![true; part_dims.iter().product()],
            *part_dims,
            *offset,
        );
    }
    let uncovered = covered.iter().filter(|&&c| !c).count();
    let same_type = parts
        .windows(2)
        .all(|w| std::mem::discriminant(&w[0].0) == std::mem::discriminant(&w[1].0));
    macro_rules! merge {
        ($variant:ident, $zero:expr) => {{
            let mut out = vec![$zero; count];
            for (voxels, part_dims, offset) in &parts {
                if let Voxels::$variant(values) = voxels {
                    copy_rows(&mut out, dims, values, *part_dims, *offset);
                }
            }
            Voxels::$variant(out)
        }};
    }
    let merged = match parts.first().map(|p| &p.0) {
        Some(_) if !same_type || uncovered > 0 => {
            for part in &mut parts {
                let values = std::mem::replace(&mut part.0, Voxels::F32(Vec::new())).into_f32();
                part.0 = Voxels::F32(values);
            }
            // NaN where no piece put a value.
            merge!(F32, f32::NAN)
        }
        Some(Voxels::U8(_)) => merge!(U8, 0u8),
        Some(Voxels::I8(_)) => merge!(I8, 0i8),
        Some(Voxels::U16(_)) => merge!(U16, 0u16),
        Some(Voxels::I16(_)) => merge!(I16, 0i16),
        Some(Voxels::F32(_)) | None => merge!(F32, f32::NAN),
    };
    (merged, uncovered as u64)
}

/// Copies a `src_dims` block (x fastest) into `dest` of `dims` at `offset`.
fn copy_rows<T: Copy>(
    dest: &mut [T],
    dims: [usize; 3],
    src: &[T],
    src_dims: [usize; 3],
    offset: [usize; 3],
) {
    let row = src_dims[0];
    for k in 0..src_dims[2] {
        for j in 0..src_dims[1] {
            let from = row * (j + src_dims[1] * k);
            let to = offset[0] + dims[0] * (offset[1] + j + dims[1] * (offset[2] + k));
            dest[to..to + row].copy_from_slice(&src[from..from + row]);
        }
    }
}
