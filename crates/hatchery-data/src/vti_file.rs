//! VTK XML ImageData volumes (`.vti`).
//!
//! Parsed by hand (quick-xml for the markup, our own base64, flate2 for zlib) rather than with
//! the vtkio crate: its 0.7 line is only a release candidate, panics on truncated data arrays,
//! silently drops arrays whose last compressed block is full, and decodes every array before
//! the grid size could be checked.

use std::io::Read;
use std::path::Path;

use quick_xml::events::{BytesStart, Event};
use quick_xml::reader::Reader;
use rayon::prelude::*;

use crate::nifti_file::MAX_VOXELS;
use crate::{DataError, VolumeData};

/// Loads the first point-data array of a VTK XML ImageData file (or, if there is no point
/// data, the first cell-data array) as a volume.
///
/// * Data arrays may be ASCII, inline binary (base64) or appended (raw or base64), uncompressed
///   or zlib-compressed (`vtkZLibDataCompressor`), with UInt32 or UInt64 headers, either byte
///   order. Every integer and float type is converted to f32; only single-component arrays
///   are read.
/// * Point data: one voxel per point, `dims = extent + 1`. Cell data: one voxel per cell,
///   placed at the cell centre.
/// * Spacing is `|Spacing|` (0 or non-finite -> 1); `Direction` is not applied, the grid is
///   kept axis-aligned in index order (x fastest, as VTK stores it).
/// * Only single-piece files are read. Non-finite values are kept ("no data").
pub fn load_vti(path: &Path, array: Option<&str>) -> Result<VolumeData, DataError> {
    let _ = array; // TODO(issue 9): pick the named array
    let bytes = std::fs::read(path).map_err(|e| DataError::io(path, e))?;
    let file = parse_markup(path, &bytes)?;

    let (array, cells) = match (file.point_array, file.cell_array) {
        (Some(array), _) => (array, false),
        (None, Some(array)) => (array, true),
        (None, None) => {
            return Err(DataError::format(
                path,
                "the ImageData piece has no point or cell data array",
            ));
        }
    };

    // Everything about the grid is checked before any voxel memory is allocated.
    let extent = file.extent;
    let dims_u64: [u64; 3] = std::array::from_fn(|axis| {
        let points = (extent[2 * axis + 1] - extent[2 * axis]) as u64 + 1;
        if cells { points - 1 } else { points }
    });
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
    let voxels = dims_u64
        .iter()
        .try_fold(1u64, |acc, &d| acc.checked_mul(d))
        .unwrap_or(u64::MAX);
    if voxels > MAX_VOXELS {
        return Err(DataError::TooLarge {
            path: path.to_path_buf(),
            voxels,
            limit: MAX_VOXELS,
        });
    }
    // Each dim is at most MAX_VOXELS / 4 here, so it fits u32.
    let dims = dims_u64.map(|d| d as u32);
    if array.components != 1 {
        return Err(DataError::unsupported(
            path,
            format!(
                "data array `{}` has {} components, only single-component (scalar) arrays are \
                 supported",
                array.name, array.components
            ),
        ));
    }

    let values =
        read_values(&array, voxels as usize, &file.encoding, file.appended).map_err(|message| {
            DataError::format(path, format!("data array `{}`: {message}", array.name))
        })?;

    // VTK places point (i, j, k) at Origin + Spacing * (i, j, k) with indices counted from the
    // extent's lower corner, so our voxel 0 sits at that corner (or at the first cell centre).
    let spacing = file.spacing.map(|s| {
        if s.is_finite() && s != 0.0 {
            s.abs()
        } else {
            1.0
        }
    });
    let origin: [f32; 3] = std::array::from_fn(|axis| {
        let first = extent[2 * axis] as f64 + if cells { 0.5 } else { 0.0 };
        (file.origin[axis] as f64 + spacing[axis] as f64 * first) as f32
    });
    VolumeData::new(dims, spacing, origin, values).map_err(|e| e.in_file(path))
}

/// How binary data is laid out, from the `VTKFile` element.
struct Encoding {
    big_endian: bool,
    /// Header numbers are UInt64 instead of UInt32.
    wide_header: bool,
    zlib: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &str) -> Option<Self> {
        use Scalar::*;
        // VTK 4-era files use the C type names.
        Some(match name {
            "Int8" | "char" | "signed_char" => I8,
            "UInt8" | "unsigned_char" => U8,
            "Int16" | "short" => I16,
            "UInt16" | "unsigned_short" => U16,
            "Int32" | "int" => I32,
            "UInt32" | "unsigned_int" => U32,
            "Int64" | "long" | "long_long" | "vtkIdType" => I64,
            "UInt64" | "unsigned_long" | "unsigned_long_long" => U64,
            "Float32" | "float" => F32,
            "Float64" | "double" => F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        use Scalar::*;
        match self {
            I8 | U8 => 1,
            I16 | U16 => 2,
            I32 | U32 | F32 => 4,
            I64 | U64 | F64 => 8,
        }
    }

    /// Converts one value of `self.size()` bytes.
    #[inline]
    fn to_f32(self, b: &[u8], big_endian: bool) -> f32 {
        macro_rules! conv {
            ($t:ty, $n:literal) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(b);
                (if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }) as f32
            }};
        }
        use Scalar::*;
        match self {
            I8 => b[0] as i8 as f32,
            U8 => b[0] as f32,
            I16 => conv!(i16, 2),
            U16 => conv!(u16, 2),
            I32 => conv!(i32, 4),
            U32 => conv!(u32, 4),
            I64 => conv!(i64, 8),
            U64 => conv!(u64, 8),
            F32 => conv!(f32, 4),
            F64 => conv!(f64, 8),
        }
    }
}

enum Format {
    Ascii,
    /// Inline base64.
    Binary,
    /// In the `AppendedData` section, at this offset.
    Appended(u64),
}

struct ArrayInfo {
    name: String,
    scalar: Scalar,
    components: u64,
    format: Format,
    /// The element's text, for ASCII and inline binary arrays.
    text: String,
}

/// The `AppendedData` section: the bytes after its `_` marker, and whether they are base64.
struct Appended<'a> {
    data: &'a [u8],
    base64: bool,
}

/// What the markup says, up to the raw bytes of the `AppendedData` section.
struct Markup<'a> {
    encoding: Encoding,
    extent: [i64; 6],
    origin: [f32; 3],
    spacing: [f32; 3],
    point_array: Option<ArrayInfo>,
    cell_array: Option<ArrayInfo>,
    appended: Option<Appended<'a>>,
}

/// Walks the XML, keeping the first data array of the piece's PointData and CellData. Stops at
/// `AppendedData`, whose raw content is not XML.
fn parse_markup<'a>(path: &Path, bytes: &'a [u8]) -> Result<Markup<'a>, DataError> {
    let xml_error =
        |e: &dyn std::fmt::Display| DataError::format(path, format!("invalid XML: {e}"));
    let mut reader = Reader::from_reader(bytes);
    let mut open: Vec<String> = Vec::new();
    let mut encoding = None;
    let mut whole_extent = None;
    let mut origin = [0.0f32; 3];
    let mut spacing = [1.0f32; 3];
    let mut pieces = 0usize;
    let mut piece_extent = None;
    let mut point_array = None;
    let mut cell_array = None;
    // Which of the two arrays the current text belongs to (cell data or not), and the depth of
    // its element: text of nested elements (VTK's InformationKey) is not data.
    let mut capturing: Option<(bool, usize)> = None;
    let mut appended = None;

    loop {
        let event = reader.read_event().map_err(|e| xml_error(&e))?;
        let (element, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                open.pop();
                if capturing.is_some_and(|(_, depth)| open.len() < depth) {
                    capturing = None;
                }
                continue;
            }
            Event::Text(t) => {
                capture(capturing, open.len(), &mut point_array, &mut cell_array, &t);
                continue;
            }
            Event::CData(t) => {
                capture(capturing, open.len(), &mut point_array, &mut cell_array, &t);
                continue;
            }
            Event::GeneralRef(_) if capturing.is_some_and(|(_, depth)| depth == open.len()) => {
                return Err(DataError::format(
                    path,
                    "entity reference inside a data array",
                ));
            }
            Event::Eof => break,
            _ => continue,
        };
        let name = element.name().as_ref().to_string();
        let parent = open.last().map(String::as_str);
        match (parent, name.as_str()) {
            (None, "VTKFile") => encoding = Some(file_attributes(path, &element)?),
            (None, other) => {
                return Err(DataError::format(
                    path,
                    format!("not a VTK XML file: the root element is <{other}>, not <VTKFile>"),
                ));
            }
            (Some("VTKFile"), "ImageData") => {
                let extent = attribute(path, &element, "WholeExtent")?
                    .ok_or_else(|| DataError::format(path, "<ImageData> has no WholeExtent"))?;
                whole_extent = Some(parse_extent(path, &extent)?);
                if let Some(text) = attribute(path, &element, "Origin")? {
                    origin = parse_vector(path, "Origin", &text)?;
                }
                if let Some(text) = attribute(path, &element, "Spacing")? {
                    spacing = parse_vector(path, "Spacing", &text)?;
                }
            }
            (Some("ImageData"), "Piece") => {
                pieces += 1;
                if pieces > 1 {
                    return Err(DataError::unsupported(
                        path,
                        "the ImageData has several pieces, only single-piece files are supported",
                    ));
                }
                if let Some(extent) = attribute(path, &element, "Extent")? {
                    piece_extent = Some(parse_extent(path, &extent)?);
                }
            }
            (Some(set @ ("PointData" | "CellData")), "DataArray")
                if open.get(open.len().wrapping_sub(2)).map(String::as_str) == Some("Piece") =>
            {
                let cell = set == "CellData";
                let target = if cell {
                    &mut cell_array
                } else {
                    &mut point_array
                };
                if target.is_none() {
                    *target = Some(array_attributes(path, &element)?);
                    capturing = (!empty).then_some((cell, open.len() + 1));
                }
            }
            (Some("VTKFile"), "AppendedData") => {
                let base64 = match attribute(path, &element, "encoding")?.as_deref() {
                    Some("base64") => true,
                    Some("raw") | None => false,
                    Some(other) => {
                        return Err(DataError::unsupported(
                            path,
                            format!("unknown AppendedData encoding `{other}`"),
                        ));
                    }
                };
                let start = (reader.buffer_position() as usize).min(bytes.len());
                let rest = &bytes[start..];
                // The section starts, after optional whitespace, with an `_` marker.
                let marker = rest.iter().position(|b| !b.is_ascii_whitespace());
                let data = match marker {
                    Some(i) if rest[i] == b'_' && !empty => &rest[i + 1..],
                    _ => {
                        return Err(DataError::format(
                            path,
                            "<AppendedData> does not start with the `_` marker",
                        ));
                    }
                };
                appended = Some(Appended { data, base64 });
                // What follows is raw data, not markup; nothing after it concerns us.
                break;
            }
            _ => {}
        }
        if !empty {
            open.push(name);
        }
    }

    // A file cut inside the markup ends with elements still open (appended data is checked
    // when it is decoded).
    if appended.is_none()
        && let Some(inner) = open.last()
    {
        return Err(DataError::format(
            path,
            format!("truncated file: it ends inside <{inner}>"),
        ));
    }
    let encoding = encoding
        .ok_or_else(|| DataError::format(path, "not a VTK XML file: no <VTKFile> element"))?;
    let whole_extent = whole_extent
        .ok_or_else(|| DataError::format(path, "no <ImageData> element in the VTKFile"))?;
    Ok(Markup {
        encoding,
        extent: piece_extent.unwrap_or(whole_extent),
        origin,
        spacing,
        point_array,
        cell_array,
        appended,
    })
}

/// Appends element text to the array being captured, if the text is directly inside it.
fn capture(
    capturing: Option<(bool, usize)>,
    depth: usize,
    point_array: &mut Option<ArrayInfo>,
    cell_array: &mut Option<ArrayInfo>,
    text: &str,
) {
    let Some((cell, array_depth)) = capturing else {
        return;
    };
    let target = if cell { cell_array } else { point_array };
    if depth == array_depth
        && let Some(array) = target
    {
        array.text.push_str(text);
    }
}

fn attribute(path: &Path, element: &BytesStart, name: &str) -> Result<Option<String>, DataError> {
    let attr = element.try_get_attribute(name).map_err(|e| {
        DataError::format(
            path,
            format!(
                "invalid XML attribute in <{}>: {e}",
                element.name().as_ref()
            ),
        )
    })?;
    Ok(attr.map(|a| a.value.trim().to_string()))
}

fn file_attributes(path: &Path, element: &BytesStart) -> Result<Encoding, DataError> {
    match attribute(path, element, "type")?.as_deref() {
        Some("ImageData") => {}
        Some(other) => {
            return Err(DataError::unsupported(
                path,
                format!("VTK XML file of type {other}, only ImageData (.vti) is supported"),
            ));
        }
        None => return Err(DataError::format(path, "<VTKFile> has no type attribute")),
    }
    let big_endian = match attribute(path, element, "byte_order")?.as_deref() {
        Some("BigEndian") => true,
        Some("LittleEndian") | None => false,
        Some(other) => {
            return Err(DataError::format(
                path,
                format!("unknown byte_order `{other}`"),
            ));
        }
    };
    // Files from before header_type existed (version 0.1) use UInt32 headers.
    let wide_header = match attribute(path, element, "header_type")?.as_deref() {
        Some("UInt64") => true,
        Some("UInt32") | None => false,
        Some(other) => {
            return Err(DataError::format(
                path,
                format!("unknown header_type `{other}`"),
            ));
        }
    };
    let zlib = match attribute(path, element, "compressor")?.as_deref() {
        None | Some("") => false,
        Some("vtkZLibDataCompressor") => true,
        Some(other) => {
            return Err(DataError::unsupported(
                path,
                format!("compressor {other} is not supported, only vtkZLibDataCompressor is"),
            ));
        }
    };
    Ok(Encoding {
        big_endian,
        wide_header,
        zlib,
    })
}

fn array_attributes(path: &Path, element: &BytesStart) -> Result<ArrayInfo, DataError> {
    let name = attribute(path, element, "Name")?.unwrap_or_default();
    let type_name = attribute(path, element, "type")?.ok_or_else(|| {
        DataError::format(path, format!("data array `{name}` has no type attribute"))
    })?;
    let scalar = Scalar::from_name(&type_name).ok_or_else(|| {
        DataError::unsupported(
            path,
            format!("data array `{name}` has type {type_name}, only integer and float types are supported"),
        )
    })?;
    let components = match attribute(path, element, "NumberOfComponents")? {
        None => 1,
        Some(text) => text.parse::<u64>().map_err(|_| {
            DataError::format(
                path,
                format!("data array `{name}`: bad NumberOfComponents `{text}`"),
            )
        })?,
    };
    let format = match attribute(path, element, "format")?.as_deref() {
        Some("ascii") => Format::Ascii,
        Some("binary") => Format::Binary,
        Some("appended") => {
            let text = attribute(path, element, "offset")?.unwrap_or_else(|| "0".into());
            let offset = text.parse::<u64>().map_err(|_| {
                DataError::format(path, format!("data array `{name}`: bad offset `{text}`"))
            })?;
            Format::Appended(offset)
        }
        other => {
            return Err(DataError::format(
                path,
                format!(
                    "data array `{name}`: unknown format `{}`",
                    other.unwrap_or("(none)")
                ),
            ));
        }
    };
    Ok(ArrayInfo {
        name,
        scalar,
        components,
        format,
        text: String::new(),
    })
}

/// `x0 x1 y0 y1 z0 z1`, inclusive point indices.
fn parse_extent(path: &Path, text: &str) -> Result<[i64; 6], DataError> {
    let bad = || DataError::format(path, format!("bad extent `{text}`"));
    let numbers = text
        .split_ascii_whitespace()
        .map(|t| t.parse::<i64>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| bad())?;
    let extent: [i64; 6] = numbers.try_into().map_err(|_| bad())?;
    // Bounded so that the counts below cannot overflow.
    const LIMIT: i64 = 1 << 40;
    if extent.iter().any(|e| !(-LIMIT..=LIMIT).contains(e))
        || (0..3).any(|a| extent[2 * a] > extent[2 * a + 1])
    {
        return Err(bad());
    }
    Ok(extent)
}

fn parse_vector(path: &Path, what: &str, text: &str) -> Result<[f32; 3], DataError> {
    let bad = || DataError::format(path, format!("bad {what} `{text}`"));
    let numbers = text
        .split_ascii_whitespace()
        .map(|t| t.parse::<f64>().map(|v| v as f32))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| bad())?;
    let v: [f32; 3] = numbers.try_into().map_err(|_| bad())?;
    if v.iter().any(|x| !x.is_finite()) {
        return Err(bad());
    }
    Ok(v)
}

/// Decodes `count` values of a single-component array; errors are messages about the array.
fn read_values(
    array: &ArrayInfo,
    count: usize,
    encoding: &Encoding,
    appended: Option<Appended>,
) -> Result<Vec<f32>, String> {
    let mut source = match array.format {
        Format::Ascii => return read_ascii(&array.text, count),
        Format::Binary => ByteSource::Base64(Base64::new(array.text.as_bytes())),
        Format::Appended(offset) => {
            let appended = appended.ok_or("format is appended but there is no <AppendedData>")?;
            let data = usize::try_from(offset)
                .ok()
                .and_then(|o| appended.data.get(o..))
                .ok_or_else(|| format!("offset {offset} is past the end of the appended data"))?;
            if appended.base64 {
                ByteSource::Base64(Base64::new(data))
            } else {
                ByteSource::Raw(data)
            }
        }
    };
    let size = array.scalar.size();
    let byte_count = count * size;
    let bytes = if encoding.zlib {
        read_compressed(&mut source, encoding, byte_count)?
    } else {
        let stored = source.header_number(encoding)?;
        if stored != byte_count as u64 {
            return Err(format!(
                "holds {stored} bytes, the extent needs {byte_count}"
            ));
        }
        source.take(byte_count)?
    };
    let (scalar, big_endian) = (array.scalar, encoding.big_endian);
    Ok(bytes
        .par_chunks_exact(size)
        .map(|b| scalar.to_f32(b, big_endian))
        .collect())
}

/// Compressed layout: `[nb][nu][np][nc_1 .. nc_nb]` header numbers, then `nb` independently
/// zlib-compressed blocks of `nu` bytes each before compression, the last one `np` bytes (or
/// `nu` when `np` is 0, i.e. the last block is full).
fn read_compressed(
    source: &mut ByteSource,
    encoding: &Encoding,
    byte_count: usize,
) -> Result<Vec<u8>, String> {
    let blocks = source.header_number(encoding)?;
    let block_size = source.header_number(encoding)?;
    let last_size = source.header_number(encoding)?;
    let total = match blocks {
        0 => Some(0),
        n if block_size > 0 && last_size <= block_size => {
            let last = if last_size == 0 {
                block_size
            } else {
                last_size
            };
            (n - 1)
                .checked_mul(block_size)
                .and_then(|t| t.checked_add(last))
        }
        _ => None,
    };
    if total != Some(byte_count as u64) {
        return Err(format!(
            "compression header ({blocks} blocks of {block_size} bytes, last {last_size}) does \
             not match the {byte_count} bytes the extent needs"
        ));
    }
    // blocks <= byte_count here, but the header of their sizes must still be in the file.
    let header_bytes = header_size(encoding) * blocks as usize;
    if header_bytes > source.max_remaining() {
        return Err("truncated compression header".into());
    }
    let mut offsets = Vec::with_capacity(blocks as usize + 1);
    offsets.push(0usize);
    for _ in 0..blocks {
        let size = source.header_number(encoding)?;
        let end = usize::try_from(size)
            .ok()
            .and_then(|s| offsets.last().unwrap_or(&0).checked_add(s))
            .filter(|&end| end <= source.max_remaining())
            .ok_or("compressed blocks are larger than the rest of the file")?;
        offsets.push(end);
    }
    let compressed = source.take(*offsets.last().unwrap_or(&0))?;

    let mut out = Vec::new();
    out.try_reserve_exact(byte_count)
        .map_err(|_| format!("cannot allocate {byte_count} bytes"))?;
    out.resize(byte_count, 0u8);
    // Blocks are independent, so they decompress in parallel straight into place.
    out.par_chunks_mut(block_size.max(1) as usize)
        .zip(offsets.par_windows(2))
        .enumerate()
        .try_for_each(|(i, (out, range))| {
            let block = &compressed[range[0]..range[1]];
            let mut decoder = flate2::bufread::ZlibDecoder::new(block);
            decoder
                .read_exact(out)
                .map_err(|e| format!("corrupt zlib block {i}: {e}"))
        })?;
    Ok(out)
}

fn header_size(encoding: &Encoding) -> usize {
    if encoding.wide_header { 8 } else { 4 }
}

fn read_ascii(text: &str, count: usize) -> Result<Vec<f32>, String> {
    let mut values = Vec::new();
    values
        .try_reserve_exact(count)
        .map_err(|_| format!("cannot allocate {count} values"))?;
    for token in text.split_ascii_whitespace() {
        if values.len() == count {
            return Err(format!("has more than the {count} values the extent needs"));
        }
        let v = token
            .parse::<f64>()
            .map_err(|_| format!("`{token}` is not a number"))?;
        values.push(v as f32);
    }
    if values.len() < count {
        return Err(format!(
            "has {} values, the extent needs {count}",
            values.len()
        ));
    }
    Ok(values)
}

/// Where binary array bytes come from: raw appended bytes or base64 text.
enum ByteSource<'a> {
    Raw(&'a [u8]),
    Base64(Base64<'a>),
}

impl ByteSource<'_> {
    fn take(&mut self, n: usize) -> Result<Vec<u8>, String> {
        match self {
            ByteSource::Raw(data) => {
                if data.len() < n {
                    return Err(format!(
                        "truncated: needs {n} more bytes, the file has {}",
                        data.len()
                    ));
                }
                let (head, rest) = data.split_at(n);
                *data = rest;
                Ok(head.to_vec())
            }
            ByteSource::Base64(b) => b.take(n),
        }
    }

    /// An upper bound of the bytes left, to refuse absurd sizes before allocating.
    fn max_remaining(&self) -> usize {
        match self {
            ByteSource::Raw(data) => data.len(),
            ByteSource::Base64(b) => (b.text.len() - b.pos) / 4 * 3 + 3,
        }
    }

    /// One number of a binary array's header (sizes and block counts), decoded exactly.
    fn header_number(&mut self, encoding: &Encoding) -> Result<u64, String> {
        let b = self.take(header_size(encoding))?;
        let mut a = [0u8; 8];
        if encoding.big_endian {
            a[8 - b.len()..].copy_from_slice(&b);
            Ok(u64::from_be_bytes(a))
        } else {
            a[..b.len()].copy_from_slice(&b);
            Ok(u64::from_le_bytes(a))
        }
    }
}

/// Incremental base64 decoding that skips whitespace and accepts padding in the middle:
/// VTK writes the header and the data of compressed arrays as separately padded base64
/// strings, and some writers do the same for uncompressed ones. Decoding through the padding
/// yields the concatenated bytes either way.
struct Base64<'a> {
    text: &'a [u8],
    pos: usize,
    bits: u32,
    bit_count: u32,
}

impl<'a> Base64<'a> {
    fn new(text: &'a [u8]) -> Self {
        Self {
            text,
            pos: 0,
            bits: 0,
            bit_count: 0,
        }
    }

    fn take(&mut self, n: usize) -> Result<Vec<u8>, String> {
        let mut out = Vec::new();
        out.try_reserve_exact(n)
            .map_err(|_| format!("cannot allocate {n} bytes"))?;
        while out.len() < n {
            let Some(&c) = self.text.get(self.pos) else {
                return Err(format!(
                    "truncated base64 data: needs {} more bytes",
                    n - out.len()
                ));
            };
            self.pos += 1;
            let v = match c {
                b'A'..=b'Z' => c - b'A',
                b'a'..=b'z' => c - b'a' + 26,
                b'0'..=b'9' => c - b'0' + 52,
                b'+' => 62,
                b'/' => 63,
                // Padding ends a quantum; its leftover bits are zero fill.
                b'=' => {
                    self.bits = 0;
                    self.bit_count = 0;
                    continue;
                }
                c if c.is_ascii_whitespace() => continue,
                c => {
                    return Err(format!(
                        "invalid base64 character {:?} at offset {}",
                        c as char,
                        self.pos - 1
                    ));
                }
            };
            self.bits = (self.bits << 6) | v as u32;
            self.bit_count += 6;
            if self.bit_count >= 8 {
                self.bit_count -= 8;
                out.push((self.bits >> self.bit_count) as u8);
                self.bits &= (1 << self.bit_count) - 1;
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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

    fn write(dir: &tempfile::TempDir, name: &str, content: &[u8]) -> std::path::PathBuf {
        let path = dir.path().join(name);
        std::fs::write(&path, content).unwrap();
        path
    }

    /// 4 x 3 x 2 values x + 10 y + 100 z, x fastest.
    fn small_values() -> Vec<f32> {
        (0..2)
            .flat_map(|z| {
                (0..3).flat_map(move |y| (0..4).map(move |x| (x + 10 * y + 100 * z) as f32))
            })
            .collect()
    }

    fn check_small(v: &VolumeData) {
        assert_eq!(v.dims, [4, 3, 2]);
        assert_eq!(v.spacing(), [0.5, 2.0, 1.5]);
        // Extent starts at (2, 0, 1): origin = Origin + Spacing * lower corner.
        assert_eq!(v.origin(), [2.0, 2.0, 4.5]);
        assert_eq!(v.values, small_values());
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
        assert!(v.values.iter().all(|x| x.fract() == 0.0));
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
<ImageData WholeExtent="{SMALL_EXTENT}" Origin="1 2 3" Spacing="0.5 2 1.5">
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
        // First cell centre: Origin + Spacing * (0.5, -0.5, 0.5).
        assert_eq!(v.origin(), [1.25, 1.0, 3.75]);
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
        assert!(matches!(load_vti(&missing, None), Err(DataError::Io { .. })));
    }
}
