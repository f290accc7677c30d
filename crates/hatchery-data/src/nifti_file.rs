//! NIfTI-1 and NIfTI-2 volumes (`.nii`, `.nii.gz`).

use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;

use nifti::NiftiType;

use crate::geometry::Geometry;
use crate::nifti_header::{self, Header, HeaderError};
use crate::raw_voxels;
use crate::voxels::Voxels;
use crate::{DataError, VolumeData};

pub use crate::voxels::MAX_VOXELS;

/// Loads a single-file NIfTI-1 or NIfTI-2 volume, gzip-compressed or not (both detected from
/// the content; NIfTI-2 has 64-bit dims and double-precision transforms, the rules are the same).
///
/// * Every integer and float datatype is read (u/i 8, 16, 32, 64, f32, f64). u8, i8, u16, i16
///   and f32 stay in their type (one byte per voxel for uint8); the wider types become f32.
///   `scl_slope`/`scl_inter` are applied (slope 0 means no scaling, per the standard), which
///   gives f32 unless they are the identity.
/// * The voxel → world transform follows the standard (and nibabel): the sform when
///   `sform_code > 0`, else the qform quaternion with `qfac = pixdim[0]` when `qform_code > 0`,
///   else `pixdim` scaling with the origin at 0 ("method 1"). NIfTI's world is RAS+, which is
///   hatchery's (see [`crate::geometry`]). A degenerate sform falls back to the qform.
/// * Of 4-D files (time series) only the first 3-D volume is read, and `placement` says so;
///   files with several values per voxel (`dim[5] > 1`: vectors, tensors) are refused.
/// * A negative `pixdim[1..3]` is taken as its magnitude and noted (nifti1_io uses 1, nibabel
///   refuses the qform); only `qfac` (or the sform) mirrors an axis.
/// * Non-finite voxel values (NaN is common in float maps) are kept: they mean "no data".
pub fn load_nifti(path: &Path) -> Result<VolumeData, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let file_len = crate::files::len_of(&file).map_err(|e| DataError::io(path, e))?;
    let mut buffered = BufReader::new(file);
    let head = buffered.fill_buf().map_err(|e| DataError::io(path, e))?;
    let gzip = head.starts_with(&[0x1f, 0x8b]);
    let mut source: Box<dyn Read> = if gzip {
        Box::new(flate2::bufread::MultiGzDecoder::new(buffered))
    } else {
        Box::new(buffered)
    };
    let read_error = |e: io::Error| stream_error(path, gzip, e);

    // Header first: everything is validated before any voxel memory is allocated.
    let header = nifti_header::read(&mut source).map_err(|e| match e {
        HeaderError::Io(e) => read_error(e),
        HeaderError::NotNifti => DataError::format(
            path,
            "not a NIfTI file (the header size is neither 348, NIfTI-1, nor 540, NIfTI-2, or \
             the magic is wrong)",
        ),
        HeaderError::Other(message) => {
            DataError::format(path, format!("bad NIfTI header: {message}"))
        }
    })?;
    let layout = check_header(path, &header, MAX_VOXELS)?;

    // Skip the extensions between the header and the voxel data.
    let skip = layout.data_offset - header.size;
    let skipped = io::copy(&mut (&mut source).take(skip), &mut io::sink()).map_err(read_error)?;
    if skipped < skip {
        return Err(truncated(path, gzip));
    }

    let byte_count = layout.voxels as usize * layout.datatype.size_of();
    // Reserve no more than the file can hold (a gzip stream at deflate's best ratio): a header
    // may promise gigabytes that are not there.
    let available = if gzip {
        raw_voxels::decoded_bound(file_len, true)
    } else {
        file_len.saturating_sub(layout.data_offset)
    };
    let room = usize::try_from(available).map_or(byte_count, |a| a.min(byte_count));
    let mut raw = Vec::new();
    raw.try_reserve_exact(room).map_err(|_| {
        DataError::format(
            path,
            format!("cannot allocate {room} bytes for the voxel data"),
        )
    })?;
    (&mut source)
        .take(byte_count as u64)
        .read_to_end(&mut raw)
        .map_err(read_error)?;
    if raw.len() < byte_count {
        return Err(DataError::format(
            path,
            format!(
                "{}: voxel data has {} of the {byte_count} bytes the header promises",
                if gzip {
                    "truncated gzip stream"
                } else {
                    "truncated file"
                },
                raw.len()
            ),
        ));
    }

    let voxels = decode_voxels(
        layout.datatype,
        raw,
        header.big_endian,
        layout.slope,
        layout.intercept,
    );
    let mut volume = VolumeData::from_voxels(layout.dims, layout.geometry, voxels)
        .map_err(|e| e.in_file(path))?;
    volume.stored_type = stored_type_name(layout.datatype);
    volume.placement = if header.version == 2 {
        format!("NIfTI-2 {}", layout.placement)
    } else {
        layout.placement
    };
    Ok(volume)
}

/// An uncompressed `.nii` file's voxels read box by box from the memory-mapped file, without
/// holding them (streaming, [`crate::brick_source`]); any size, scaled by `scl_slope` and
/// `scl_inter` as [`load_nifti`] does. Errors: as [`load_nifti`]; a gzip-compressed file (which
/// cannot be read a box at a time: `gunzip` it, or `hatchery convert` it to OME-Zarr).
pub fn nifti_source(path: &Path) -> Result<crate::raw_source::RawSource, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let mut buffered = BufReader::new(file);
    let head = buffered.fill_buf().map_err(|e| DataError::io(path, e))?;
    if head.starts_with(&[0x1f, 0x8b]) {
        return Err(DataError::unsupported(
            path,
            "gzip-compressed voxels cannot be read a brick at a time (gunzip it, or \
             `hatchery convert` it to OME-Zarr)",
        ));
    }
    let header = nifti_header::read(&mut buffered).map_err(|e| match e {
        HeaderError::Io(e) => DataError::io(path, e),
        HeaderError::NotNifti => DataError::format(path, "not a NIfTI file"),
        HeaderError::Other(message) => {
            DataError::format(path, format!("bad NIfTI header: {message}"))
        }
    })?;
    // 2⁴⁸ voxels: far beyond any disk, low enough that byte counts cannot overflow.
    let layout = check_header(path, &header, 1 << 48)?;
    let (datatype, big_endian) = (layout.datatype, header.big_endian);
    let (slope, intercept) = (layout.slope, layout.intercept);
    let decode: crate::raw_source::Decode =
        Box::new(move |raw| decode_voxels(datatype, raw, big_endian, slope, intercept));
    crate::raw_source::RawSource::open_with(
        path,
        Some(layout.data_offset),
        datatype.size_of(),
        decode,
        layout.dims,
        layout.geometry,
    )
}

/// Voxel bytes as voxels: 8- and 16-bit integers and f32 in their own type, the wider types
/// (32/64-bit integers, f64) as f32; `slope` 0 means no scaling, else `v · slope + intercept`
/// (which makes f32). Shared with the MGH reader.
pub(crate) fn decode_voxels(
    datatype: NiftiType,
    raw: Vec<u8>,
    big: bool,
    slope: f64,
    intercept: f64,
) -> Voxels {
    match native_voxels(datatype, raw, big) {
        Ok(voxels) if slope == 0.0 => voxels,
        Ok(voxels) => voxels.rescaled(slope, intercept),
        Err(raw) => Voxels::F32(wide_voxels(datatype, &raw, big, slope, intercept)),
    }
}

/// The voxel bytes of the 8- and 16-bit integer and f32 types in their own type (the u8 buffer
/// is kept as is); other types are handed back.
fn native_voxels(datatype: NiftiType, raw: Vec<u8>, big: bool) -> Result<Voxels, Vec<u8>> {
    let two = |b: &[u8]| if big { [b[1], b[0]] } else { [b[0], b[1]] };
    let four = |b: &[u8]| {
        if big {
            [b[3], b[2], b[1], b[0]]
        } else {
            [b[0], b[1], b[2], b[3]]
        }
    };
    Ok(match datatype {
        NiftiType::Uint8 => Voxels::U8(raw),
        NiftiType::Int8 => Voxels::I8(raw.into_iter().map(|b| b as i8).collect()),
        NiftiType::Uint16 => Voxels::U16(
            raw.chunks_exact(2)
                .map(|b| u16::from_le_bytes(two(b)))
                .collect(),
        ),
        NiftiType::Int16 => Voxels::I16(
            raw.chunks_exact(2)
                .map(|b| i16::from_le_bytes(two(b)))
                .collect(),
        ),
        NiftiType::Float32 => Voxels::F32(
            raw.chunks_exact(4)
                .map(|b| f32::from_le_bytes(four(b)))
                .collect(),
        ),
        _ => return Err(raw),
    })
}

/// Decodes the wider types (32/64-bit integers, f64) to f32, scaling in f64 first.
fn wide_voxels(datatype: NiftiType, raw: &[u8], big: bool, slope: f64, intercept: f64) -> Vec<f32> {
    fn word<const N: usize>(b: &[u8], big: bool) -> [u8; N] {
        let mut w: [u8; N] = b.try_into().expect("chunk of N bytes");
        if big {
            w.reverse();
        }
        w
    }
    let (slope, intercept) = if slope == 0.0 {
        (1.0, 0.0)
    } else {
        (slope, intercept)
    };
    let scaled = |v: f64| (v * slope + intercept) as f32;
    match datatype {
        NiftiType::Uint32 => raw
            .chunks_exact(4)
            .map(|b| scaled(f64::from(u32::from_le_bytes(word(b, big)))))
            .collect(),
        NiftiType::Int32 => raw
            .chunks_exact(4)
            .map(|b| scaled(f64::from(i32::from_le_bytes(word(b, big)))))
            .collect(),
        NiftiType::Uint64 => raw
            .chunks_exact(8)
            .map(|b| scaled(u64::from_le_bytes(word(b, big)) as f64))
            .collect(),
        NiftiType::Int64 => raw
            .chunks_exact(8)
            .map(|b| scaled(i64::from_le_bytes(word(b, big)) as f64))
            .collect(),
        _ => raw
            .chunks_exact(8)
            .map(|b| scaled(f64::from_le_bytes(word(b, big))))
            .collect(),
    }
}

pub(crate) fn stored_type_name(t: NiftiType) -> &'static str {
    use NiftiType::*;
    match t {
        Uint8 => "uint8",
        Int8 => "int8",
        Uint16 => "uint16",
        Int16 => "int16",
        Uint32 => "uint32",
        Int32 => "int32",
        Uint64 => "uint64",
        Int64 => "int64",
        Float64 => "float64",
        _ => "float32",
    }
}

/// What the header tells us, validated.
struct Layout {
    dims: [u32; 3],
    voxels: u64,
    datatype: NiftiType,
    slope: f64,
    intercept: f64,
    geometry: Geometry,
    /// Which header rule placed the voxels.
    placement: String,
    data_offset: u64,
}

/// The header's layout, refused above `limit` voxels.
fn check_header(path: &Path, h: &Header, limit: u64) -> Result<Layout, DataError> {
    if h.pair {
        return Err(DataError::unsupported(
            path,
            "separate .hdr/.img NIfTI pairs are not supported, use a single .nii or .nii.gz file",
        ));
    }
    let rank = h.dim[0];
    if !(1..=7).contains(&rank) {
        return Err(DataError::format(
            path,
            format!("invalid dimension count dim[0] = {rank}"),
        ));
    }
    let dims_signed: [i64; 3] =
        std::array::from_fn(|i| if i < rank as usize { h.dim[i + 1] } else { 1 });
    if let Some(d) = dims_signed.iter().find(|&&d| d < 0) {
        return Err(DataError::format(
            path,
            format!("negative dimension {d} in header"),
        ));
    }
    if let Some(d) = dims_signed.iter().find(|&&d| d > i64::from(u32::MAX)) {
        return Err(DataError::TooLarge {
            path: path.to_path_buf(),
            voxels: *d as u64,
            limit: MAX_VOXELS,
        });
    }
    let dims = dims_signed.map(|d| d as u32);
    if dims.iter().any(|&d| d < 2) {
        return Err(DataError::unsupported(
            path,
            format!(
                "only 3-D volumes with at least 2 voxels per axis are supported, dims are {dims:?}"
            ),
        ));
    }
    // dim[4] counts volumes (time points), dim[5] values per voxel (intent vectors), dim[6..7]
    // further volume axes.
    let extra = |i: usize| if i <= rank as usize { h.dim[i] } else { 1 };
    if (4..=7).any(|i| extra(i) < 1) {
        return Err(DataError::format(
            path,
            format!(
                "dim[4..7] must be at least 1, the header has {:?}",
                &h.dim[4..]
            ),
        ));
    }
    if extra(5) > 1 {
        return Err(DataError::unsupported(
            path,
            format!(
                "{} values per voxel (dim[5], intent code {}): only scalar volumes are \
                 supported",
                extra(5),
                h.intent_code
            ),
        ));
    }
    let volumes = [4, 6, 7]
        .iter()
        .map(|&i| extra(i) as u64)
        .fold(1u64, u64::saturating_mul);
    let voxels = voxel_count_within(path, dims, limit)?;

    let datatype = nifti_header::datatype(h.datatype).ok_or_else(|| {
        DataError::unsupported(
            path,
            format!(
                "datatype code {} is not supported, only integer and float scalars are",
                h.datatype
            ),
        )
    })?;

    // Per the standard a zero slope means "no scaling"; we treat a non-finite one the same way.
    let (slope, intercept) = if h.scl_slope.is_finite() && h.scl_slope != 0.0 {
        (
            h.scl_slope,
            if h.scl_inter.is_finite() {
                h.scl_inter
            } else {
                0.0
            },
        )
    } else {
        (0.0, 0.0)
    };

    let (geometry, mut placement) = nifti_geometry(path, h)?;
    if volumes > 1 {
        placement += &format!(
            "; the first of {volumes} volumes (dim[4], dim[6], dim[7] = {}, {}, {})",
            extra(4),
            extra(6),
            extra(7)
        );
    }

    // vox_offset is a float in the format; it must leave room for the 4-byte extender. Some
    // writers leave it 0 for single files, meaning "right after the extender".
    let offset = h.vox_offset;
    if !offset.is_finite() || offset < 0.0 || offset > (1u64 << 31) as f64 {
        return Err(DataError::format(
            path,
            format!("invalid vox_offset {offset}"),
        ));
    }
    let data_offset = (offset as u64).max(h.size + 4);

    Ok(Layout {
        dims,
        voxels,
        datatype,
        slope,
        intercept,
        geometry,
        placement,
        data_offset,
    })
}

/// The voxel → world transform by the standard's rules (nifti1.h, "3 different methods"), as
/// nibabel's `get_best_affine` applies them, and a note of which rule was used.
fn nifti_geometry(path: &Path, h: &Header) -> Result<(Geometry, String), DataError> {
    // Voxel sizes are magnitudes: the sign of pixdim[1..3] never mirrors (see load_nifti).
    let pixdim = |i: usize| {
        let s = h.pixdim[i];
        if s.is_finite() && s != 0.0 {
            s.abs()
        } else {
            1.0
        }
    };
    let negative: Vec<String> = (1..=3)
        .filter(|&i| h.pixdim[i] < 0.0)
        .map(|i| format!("pixdim[{i}] = {}", h.pixdim[i]))
        .collect();
    let note = if negative.is_empty() {
        String::new()
    } else {
        format!("; negative {} taken as the magnitude", negative.join(", "))
    };
    if h.sform_code > 0 {
        match Geometry::from_affine(h.srow) {
            Ok(g) => return Ok((g, format!("sform (sform_code {})", h.sform_code))),
            Err(e) if h.qform_code <= 0 => {
                return Err(DataError::format(path, format!("bad sform: {e}")));
            }
            Err(_) => {}
        }
    }
    if h.qform_code > 0 {
        // Quaternion (b, c, d) with a = sqrt(1 - b² - c² - d²); a sum above 1 (rounding in
        // writers) is renormalised with a = 0, as nifti1_io does.
        let [mut b, mut c, mut d] = h.quatern;
        let sum = b * b + c * c + d * d;
        let a = if sum > 1.0 {
            let n = sum.sqrt();
            (b, c, d) = (b / n, c / n, d / n);
            0.0
        } else {
            (1.0 - sum).sqrt()
        };
        let r = [
            [
                a * a + b * b - c * c - d * d,
                2.0 * (b * c - a * d),
                2.0 * (b * d + a * c),
            ],
            [
                2.0 * (b * c + a * d),
                a * a + c * c - b * b - d * d,
                2.0 * (c * d - a * b),
            ],
            [
                2.0 * (b * d - a * c),
                2.0 * (c * d + a * b),
                a * a + d * d - c * c - b * b,
            ],
        ];
        let qfac = if h.pixdim[0] < 0.0 { -1.0 } else { 1.0 };
        let zoom = [pixdim(1), pixdim(2), qfac * pixdim(3)];
        let offset = h.qoffset;
        let rows: [[f64; 4]; 3] = std::array::from_fn(|row| {
            [
                r[row][0] * zoom[0],
                r[row][1] * zoom[1],
                r[row][2] * zoom[2],
                offset[row],
            ]
        });
        let g = Geometry::from_affine(rows)
            .map_err(|e| DataError::format(path, format!("bad qform: {e}")))?;
        return Ok((
            g,
            format!("qform (qform_code {}, qfac {qfac}){note}", h.qform_code),
        ));
    }
    let g = Geometry::axis_aligned([pixdim(1), pixdim(2), pixdim(3)], [0.0; 3]);
    Ok((
        g,
        format!("pixdim scaling (sform_code and qform_code are 0){note}"),
    ))
}

/// The voxel count of `dims`; TooLarge above [`MAX_VOXELS`] (refused before any allocation).
pub(crate) fn voxel_count(path: &Path, dims: [u32; 3]) -> Result<u64, DataError> {
    voxel_count_within(path, dims, MAX_VOXELS)
}

/// The voxel count of `dims`; TooLarge above `limit`.
fn voxel_count_within(path: &Path, dims: [u32; 3], limit: u64) -> Result<u64, DataError> {
    // Three 32-bit dims can overflow 64 bits: saturate (a fuzzed header found it).
    let voxels = dims
        .iter()
        .fold(1u64, |n, &d| n.saturating_mul(u64::from(d)));
    if voxels > limit {
        return Err(DataError::TooLarge {
            path: path.to_path_buf(),
            voxels,
            limit,
        });
    }
    Ok(voxels)
}

pub(crate) fn truncated(path: &Path, gzip: bool) -> DataError {
    DataError::format(
        path,
        if gzip {
            "truncated gzip stream"
        } else {
            "truncated file"
        },
    )
}

/// Reading errors from a (possibly gzip) stream: end-of-file and decoder errors are format
/// problems of the file, the rest are I/O errors.
pub(crate) fn stream_error(path: &Path, gzip: bool, e: io::Error) -> DataError {
    match e.kind() {
        io::ErrorKind::UnexpectedEof => truncated(path, gzip),
        io::ErrorKind::InvalidInput | io::ErrorKind::InvalidData if gzip => {
            DataError::format(path, format!("corrupt gzip stream: {e}"))
        }
        _ => DataError::io(path, e),
    }
}
