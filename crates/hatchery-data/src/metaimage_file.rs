//! MetaImage volumes as ITK's MetaIO writes them: `.mha` (header and data in one file) and
//! `.mhd` (header naming a data file). The header is `Key = Value` lines ending with
//! `ElementDataFile`; the layout and the geometry rules below were checked against SimpleITK.

use std::io::{BufRead, BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use glam::DMat3;

use crate::geometry::Geometry;
use crate::raw_voxels::{self, Element};
use crate::{DataError, VolumeData};

/// A header longer than this is not a header (binary data without an `ElementDataFile` line).
const MAX_HEADER_BYTES: u64 = 1 << 20;

/// Loads a single-channel 3-D MetaImage (`.mha` or `.mhd`).
///
/// * `ObjectType = Image` (when given), `NDims = 3`, `DimSize`, `ElementNumberOfChannels = 1`.
/// * `ElementType` MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, MET_INT, MET_ULONG,
///   MET_LONG (4 bytes, as in MetaIO), MET_ULONG_LONG, MET_LONG_LONG, MET_FLOAT, MET_DOUBLE;
///   u8, i8, u16, i16 and f32 stay as they are, the wider types are converted to f32 (integers
///   above 2^24 and double values lose precision). `BinaryDataByteOrderMSB` or
///   `ElementByteOrderMSB = True` means big-endian.
/// * Data: `ElementDataFile = LOCAL` (after the header) or a file name relative to the header's
///   folder; `CompressedData = True` is a zlib (or gzip) stream. `HeaderSize = N` puts the data
///   at byte N of the data file (of the `.mha` itself for LOCAL, as MetaIO reads it), `-1` at
///   its end (uncompressed only).
/// * Geometry: ITK's physical space is LPS+, turned into hatchery's RAS+ mm world.
///   `ElementSpacing` (else `ElementSize`, else 1) in mm, `Offset` (or `Origin`, `Position`):
///   the centre of voxel 0. `TransformMatrix` (or `Rotation`, `Orientation`) lists the
///   direction of the i, j and k axes one after the other (the file's row-major 3×3 is the
///   transpose of ITK's direction matrix, checked against SimpleITK). `AnatomicalOrientation`
///   is ignored, as in ITK: the matrix alone places the voxels.
///
/// Errors: [`DataError::Format`] for a malformed header or truncated data,
/// [`DataError::Unsupported`] for valid files we do not read (other dimensions, several
/// channels, ASCII data, file lists, a data file that is not a regular file such as
/// `/dev/zero`), [`DataError::TooLarge`] above
/// [`crate::nifti_file::MAX_VOXELS`] voxels (checked before anything is allocated),
/// [`DataError::Io`] when a file cannot be read.
pub fn load_metaimage(path: &Path) -> Result<VolumeData, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let header = read_header(path, &mut BufReader::new(file))?;
    let layout = check_header(path, &header, crate::voxels::MAX_VOXELS)?;
    let bytes = read_data(path, &layout)?;
    let voxels = raw_voxels::decode(&bytes, layout.element, layout.big_endian);
    let mut volume = VolumeData::from_voxels(layout.dims, layout.geometry, voxels)
        .map_err(|e| e.in_file(path))?;
    volume.stored_type = layout.element.name();
    volume.placement = layout.placement;
    Ok(volume)
}

/// A MetaImage file's voxels read box by box from the memory-mapped data file, without holding
/// them (streaming, [`crate::brick_source`]); any size. Errors: as [`load_metaimage`];
/// compressed data (which cannot be read a box at a time: convert it to OME-Zarr).
pub fn metaimage_source(path: &Path) -> Result<crate::raw_source::RawSource, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let header = read_header(path, &mut BufReader::new(file))?;
    // 2⁴⁸ voxels: far beyond any disk, low enough that byte counts cannot overflow.
    let layout = check_header(path, &header, 1 << 48)?;
    if layout.compressed {
        return Err(DataError::unsupported(
            path,
            "compressed voxel data cannot be read a brick at a time (`hatchery convert` it to OME-Zarr)",
        ));
    }
    crate::raw_source::RawSource::open(
        &layout.data_file,
        layout.offset,
        layout.element,
        layout.big_endian,
        layout.dims,
        layout.geometry,
    )
}

/// The header's `Key = Value` pairs (keys matched without regard to case) and the byte where
/// the header ends.
struct Header {
    fields: Vec<(String, String)>,
    end: u64,
}

impl Header {
    /// The first of several synonyms that is present.
    fn get(&self, names: &[&str]) -> Option<&str> {
        names.iter().find_map(|name| {
            self.fields
                .iter()
                .find(|(k, _)| k.eq_ignore_ascii_case(name))
                .map(|(_, v)| v.as_str())
        })
    }
}

fn read_header(path: &Path, reader: &mut dyn BufRead) -> Result<Header, DataError> {
    let mut header = Header {
        fields: Vec::new(),
        end: 0,
    };
    let mut raw = Vec::new();
    loop {
        raw.clear();
        let n = reader
            .take(MAX_HEADER_BYTES)
            .read_until(b'\n', &mut raw)
            .map_err(|e| DataError::io(path, e))?;
        header.end += n as u64;
        if n == 0 || header.end > MAX_HEADER_BYTES {
            let what = if header.fields.is_empty() {
                "not a MetaImage file (no `Key = Value` header)"
            } else {
                "header has no `ElementDataFile` line"
            };
            return Err(DataError::format(path, what));
        }
        let line = String::from_utf8_lossy(&raw);
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let Some((key, value)) = line.split_once('=') else {
            if header.fields.is_empty() {
                return Err(DataError::format(
                    path,
                    "not a MetaImage file (no `Key = Value` header)",
                ));
            }
            return Err(DataError::format(path, format!("bad header line `{line}`")));
        };
        let (key, value) = (key.trim().to_string(), value.trim().to_string());
        // MetaIO's rule: the data file field ends the header.
        let last = key.eq_ignore_ascii_case("ElementDataFile");
        header.fields.push((key, value));
        if last {
            return Ok(header);
        }
    }
}

/// What the header says about the data, validated.
struct Layout {
    dims: [u32; 3],
    element: Element,
    big_endian: bool,
    compressed: bool,
    data_file: PathBuf,
    /// Where the data starts in `data_file`; `None`: at its end (`HeaderSize = -1`).
    offset: Option<u64>,
    byte_count: usize,
    geometry: Geometry,
    placement: String,
}

/// The header's layout, refused above `limit` voxels.
fn check_header(path: &Path, h: &Header, limit: u64) -> Result<Layout, DataError> {
    let require = |name: &str| {
        h.get(&[name])
            .ok_or_else(|| DataError::format(path, format!("header has no `{name}`")))
    };
    if let Some(kind) = h
        .get(&["ObjectType"])
        .filter(|t| !t.eq_ignore_ascii_case("Image"))
    {
        return Err(DataError::unsupported(
            path,
            format!("ObjectType `{kind}` is not an image"),
        ));
    }
    let ndims: u32 = parse(path, "NDims", require("NDims")?)?;
    if ndims != 3 {
        return Err(DataError::unsupported(
            path,
            format!("NDims = {ndims}: only 3-D images are supported"),
        ));
    }
    let sizes: [u64; 3] = numbers(path, "DimSize", require("DimSize")?)?;
    if sizes.contains(&0) {
        return Err(DataError::format(path, format!("bad DimSize {sizes:?}")));
    }
    let count = raw_voxels::checked_count_within(path, &sizes, limit)? as usize;
    let dims = sizes.map(|d| d as u32);
    let channels: u32 = h
        .get(&["ElementNumberOfChannels"])
        .map_or(Ok(1), |v| parse(path, "ElementNumberOfChannels", v))?;
    if channels != 1 {
        return Err(DataError::unsupported(
            path,
            format!("{channels} channels per voxel; only single-channel (scalar) images are read"),
        ));
    }
    let element = element_type(path, require("ElementType")?)?;
    if !flag(path, h, &["BinaryData"], true)? {
        return Err(DataError::unsupported(
            path,
            "BinaryData = False (ASCII voxel data) is not supported",
        ));
    }
    let big_endian = flag(
        path,
        h,
        &["BinaryDataByteOrderMSB", "ElementByteOrderMSB"],
        false,
    )?;
    let compressed = flag(path, h, &["CompressedData"], false)?;

    let data_name = require("ElementDataFile")?;
    let first_word = data_name.split_whitespace().next().unwrap_or("");
    if first_word == "LIST" || data_name.contains('%') {
        return Err(DataError::unsupported(
            path,
            format!("ElementDataFile `{data_name}`: file lists and patterns are not supported"),
        ));
    }
    let local = data_name.eq_ignore_ascii_case("LOCAL");
    let data_file = if local {
        path.to_path_buf()
    } else {
        path.parent().unwrap_or(Path::new("")).join(data_name)
    };
    let offset = match h
        .get(&["HeaderSize"])
        .map(|v| parse::<i64>(path, "HeaderSize", v))
    {
        None | Some(Ok(0)) => Some(if local { h.end } else { 0 }),
        Some(Ok(-1)) if compressed => {
            return Err(DataError::format(
                path,
                "HeaderSize = -1 needs uncompressed data",
            ));
        }
        Some(Ok(-1)) => None,
        Some(Ok(n)) if n > 0 => Some(n as u64),
        Some(Ok(n)) => return Err(DataError::format(path, format!("bad HeaderSize {n}"))),
        Some(Err(e)) => return Err(e),
    };

    let (geometry, placement) = geometry(path, h)?;
    Ok(Layout {
        dims,
        element,
        big_endian,
        compressed,
        data_file,
        offset,
        byte_count: count * element.size(),
        geometry,
        placement,
    })
}

fn element_type(path: &Path, name: &str) -> Result<Element, DataError> {
    Ok(match name {
        "MET_UCHAR" => Element::U8,
        "MET_CHAR" => Element::I8,
        "MET_USHORT" => Element::U16,
        "MET_SHORT" => Element::I16,
        "MET_UINT" | "MET_ULONG" => Element::U32,
        "MET_INT" | "MET_LONG" => Element::I32,
        "MET_ULONG_LONG" => Element::U64,
        "MET_LONG_LONG" => Element::I64,
        "MET_FLOAT" => Element::F32,
        "MET_DOUBLE" => Element::F64,
        other if other.ends_with("_ARRAY") => {
            return Err(DataError::unsupported(
                path,
                format!("ElementType `{other}`: only scalar element types are read"),
            ));
        }
        other => {
            return Err(DataError::format(
                path,
                format!("unknown ElementType `{other}`"),
            ));
        }
    })
}

/// The voxel → world transform: ITK's LPS geometry, in RAS+.
fn geometry(path: &Path, h: &Header) -> Result<(Geometry, String), DataError> {
    let spacing: [f64; 3] = match h.get(&["ElementSpacing", "ElementSize"]) {
        Some(v) => numbers(path, "ElementSpacing", v)?,
        None => [1.0; 3],
    };
    let origin: [f64; 3] = match h.get(&["Offset", "Origin", "Position"]) {
        Some(v) => numbers(path, "Offset", v)?,
        None => [0.0; 3],
    };
    let direction = match h.get(&["TransformMatrix", "Rotation", "Orientation"]) {
        // Consecutive triples are the i, j, k axis directions: columns of ITK's direction.
        Some(v) => DMat3::from_cols_array(&numbers::<f64, 9>(path, "TransformMatrix", v)?),
        None => DMat3::IDENTITY,
    };
    let g = Geometry::from_lps(spacing, direction, origin);
    g.check().map_err(|e| e.in_file(path))?;
    Ok((
        g,
        "MetaImage ElementSpacing/Offset/TransformMatrix (ITK LPS)".into(),
    ))
}

fn read_data(path: &Path, layout: &Layout) -> Result<Vec<u8>, DataError> {
    let data_path = layout.data_file.as_path();
    // Errors name the data file when it is not the header itself.
    let what = if data_path == path {
        "the local data"
    } else {
        "the data file"
    };
    let io = |e| DataError::io(data_path, e);
    let (mut file, len) = raw_voxels::open_data_file(data_path, what)?;
    let start = match layout.offset {
        Some(offset) => offset,
        None => len.checked_sub(layout.byte_count as u64).ok_or_else(|| {
            DataError::format(
                data_path,
                format!(
                    "truncated data: {what} is shorter than {} bytes",
                    layout.byte_count
                ),
            )
        })?,
    };
    file.seek(SeekFrom::Start(start)).map_err(io)?;
    let mut source: Box<dyn Read> = if layout.compressed {
        raw_voxels::inflate(Box::new(BufReader::new(file))).map_err(io)?
    } else {
        Box::new(file)
    };
    let available = raw_voxels::decoded_bound(len.saturating_sub(start), layout.compressed);
    raw_voxels::read_bytes(data_path, &mut source, layout.byte_count, what, available)
}

/// A `True`/`False` field (MetaIO writes these; `1`/`0` are accepted too).
fn flag(path: &Path, h: &Header, names: &[&str], default: bool) -> Result<bool, DataError> {
    match h.get(names) {
        None => Ok(default),
        Some(v) if v.eq_ignore_ascii_case("true") || v == "1" => Ok(true),
        Some(v) if v.eq_ignore_ascii_case("false") || v == "0" => Ok(false),
        Some(v) => Err(DataError::format(
            path,
            format!("{} must be True or False, got `{v}`", names[0]),
        )),
    }
}

fn parse<T: std::str::FromStr>(path: &Path, field: &str, value: &str) -> Result<T, DataError> {
    value
        .trim()
        .parse()
        .map_err(|_| DataError::format(path, format!("bad {field} `{value}`")))
}

/// Exactly `N` whitespace-separated numbers.
fn numbers<T: std::str::FromStr + Copy + Default, const N: usize>(
    path: &Path,
    field: &str,
    value: &str,
) -> Result<[T; N], DataError> {
    let values: Vec<T> = value
        .split_whitespace()
        .map(|v| parse(path, field, v))
        .collect::<Result<_, _>>()?;
    values.try_into().map_err(|v: Vec<T>| {
        DataError::format(
            path,
            format!("{field} needs {N} numbers, got {} in `{value}`", v.len()),
        )
    })
}
