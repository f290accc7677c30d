//! The XML part of a `.vti` file: the grid, its pieces and their data arrays, up to the raw
//! bytes of the `AppendedData` section.

use std::borrow::Cow;
use std::path::Path;

use quick_xml::events::{BytesStart, Event};
use quick_xml::reader::Reader;

use crate::DataError;

/// How binary data is laid out, from the `VTKFile` element.
pub(super) struct Encoding {
    pub big_endian: bool,
    /// Header numbers are UInt64 instead of UInt32.
    pub wide_header: bool,
    pub compressor: Compressor,
}

/// The `compressor` of the `VTKFile` element. Every compressor uses the same block layout (see
/// `decode::read_compressed`); they differ in how one block is compressed.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Compressor {
    None,
    /// `vtkZLibDataCompressor`: one zlib stream per block.
    Zlib,
    /// `vtkLZ4DataCompressor`: one raw LZ4 block per block (`LZ4_compress_fast`, no frame).
    Lz4,
    /// `vtkLZMADataCompressor`: one `.xz` stream (the xz container) per block.
    Lzma,
    /// Named in the file but not known here; an error only if binary data must be read.
    Unknown(String),
}

/// A scalar type of VTK's XML format.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Scalar {
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
    pub fn from_name(name: &str) -> Option<Self> {
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

    pub fn size(self) -> usize {
        use Scalar::*;
        match self {
            I8 | U8 => 1,
            I16 | U16 => 2,
            I32 | U32 | F32 => 4,
            I64 | U64 | F64 => 8,
        }
    }

    /// The name `hatchery info` prints for the file's type (`VolumeData::stored_type`).
    pub fn type_name(self) -> &'static str {
        use Scalar::*;
        match self {
            I8 => "int8",
            U8 => "uint8",
            I16 => "int16",
            U16 => "uint16",
            I32 => "int32",
            U32 => "uint32",
            I64 => "int64",
            U64 => "uint64",
            F32 => "float32",
            F64 => "float64",
        }
    }
}

/// Where a data array's values are.
pub(super) enum Format {
    Ascii,
    /// Inline base64.
    Binary,
    /// In the `AppendedData` section, at this offset.
    Appended(u64),
}

/// One `DataArray` of a piece's point or cell data. Its attributes are kept as written and
/// checked only if the array is read, so an odd array the user does not ask for is no error.
pub(super) struct ArrayInfo<'a> {
    /// `Name` (empty if none).
    pub name: String,
    /// `type`, as written.
    pub type_name: Option<String>,
    pub components: Option<String>,
    pub format: Option<String>,
    pub offset: Option<String>,
    /// The element's text (ASCII and inline binary arrays), as the parser found it in pieces.
    pub text: Vec<Cow<'a, str>>,
}

impl ArrayInfo<'_> {
    pub(super) fn scalar(&self) -> Result<Scalar, String> {
        let Some(type_name) = &self.type_name else {
            return Err("has no type attribute".into());
        };
        Scalar::from_name(type_name).ok_or_else(|| {
            format!("has type {type_name}, only integer and float types are supported")
        })
    }

    pub(super) fn components(&self) -> Result<u64, String> {
        match &self.components {
            None => Ok(1),
            Some(text) => text
                .parse::<u64>()
                .map_err(|_| format!("bad NumberOfComponents `{text}`")),
        }
    }

    /// Whether the array can be read as a scalar volume (a numeric type, one component).
    pub fn is_scalar(&self) -> bool {
        self.scalar().is_ok() && self.components() == Ok(1)
    }

    pub(super) fn format(&self) -> Result<Format, String> {
        match self.format.as_deref() {
            Some("ascii") => Ok(Format::Ascii),
            Some("binary") => Ok(Format::Binary),
            Some("appended") => {
                let text = self.offset.as_deref().unwrap_or("0");
                let offset = text
                    .parse::<u64>()
                    .map_err(|_| format!("bad offset `{text}`"))?;
                Ok(Format::Appended(offset))
            }
            other => Err(format!("unknown format `{}`", other.unwrap_or("(none)"))),
        }
    }

    /// The text content, joined if the parser split it.
    pub fn text(&self) -> Cow<'_, str> {
        match self.text.as_slice() {
            [] => Cow::Borrowed(""),
            [one] => Cow::Borrowed(one),
            many => Cow::Owned(many.concat()),
        }
    }
}

/// A piece's `PointData` or `CellData`.
#[derive(Default)]
pub(super) struct DataSet<'a> {
    /// The `Scalars` attribute: the name of the active scalars.
    pub active: Option<String>,
    pub arrays: Vec<ArrayInfo<'a>>,
}

pub(super) struct Piece<'a> {
    /// Inclusive point indices `x0 x1 y0 y1 z0 z1`; some axis has `x1 < x0` when empty.
    pub extent: [i64; 6],
    pub point: DataSet<'a>,
    pub cell: DataSet<'a>,
}

impl Piece<'_> {
    pub fn is_empty(&self) -> bool {
        (0..3).any(|a| self.extent[2 * a] > self.extent[2 * a + 1])
    }
}

/// The `AppendedData` section: the bytes after its `_` marker, and whether they are base64.
pub(super) struct Appended<'a> {
    pub data: &'a [u8],
    pub base64: bool,
}

/// What the markup says, up to the raw bytes of the `AppendedData` section.
pub(super) struct Markup<'a> {
    pub encoding: Encoding,
    pub origin: [f64; 3],
    pub spacing: [f64; 3],
    /// Row-major, as VTK writes `vtkImageData::GetDirectionMatrix`.
    pub direction: [f64; 9],
    pub pieces: Vec<Piece<'a>>,
    pub appended: Option<Appended<'a>>,
}

/// What the parser is inside of: a piece's point or cell data array, whose text is data (text
/// of elements nested deeper, like VTK's InformationKey, is not).
#[derive(Clone, Copy)]
struct Capture {
    cell: bool,
    depth: usize,
}

/// Walks the XML, keeping every piece's point and cell data arrays. Stops at `AppendedData`,
/// whose raw content is not XML.
pub(super) fn parse_markup<'a>(path: &Path, bytes: &'a [u8]) -> Result<Markup<'a>, DataError> {
    let xml_error =
        |e: &dyn std::fmt::Display| DataError::format(path, format!("invalid XML: {e}"));
    let mut reader = Reader::from_reader(bytes);
    let mut open: Vec<String> = Vec::new();
    let mut encoding = None;
    let mut whole_extent = None;
    let mut origin = [0.0; 3];
    let mut spacing = [1.0; 3];
    let mut direction = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let mut pieces: Vec<Piece> = Vec::new();
    let mut capturing: Option<Capture> = None;
    let mut appended = None;

    loop {
        let event = reader.read_event().map_err(|e| xml_error(&e))?;
        let (element, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                open.pop();
                if capturing.is_some_and(|c| open.len() < c.depth) {
                    capturing = None;
                }
                continue;
            }
            Event::Text(t) => {
                capture(capturing, open.len(), &mut pieces, t.into_inner());
                continue;
            }
            Event::CData(t) => {
                capture(capturing, open.len(), &mut pieces, t.into_inner());
                continue;
            }
            Event::GeneralRef(_) if capturing.is_some_and(|c| c.depth == open.len()) => {
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
        let grandparent = open.len().checked_sub(2).map(|i| open[i].as_str());
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
                    origin = parse_numbers(path, "Origin", &text)?;
                }
                if let Some(text) = attribute(path, &element, "Spacing")? {
                    spacing = parse_numbers(path, "Spacing", &text)?;
                }
                if let Some(text) = attribute(path, &element, "Direction")? {
                    direction = parse_numbers(path, "Direction", &text)?;
                }
            }
            (Some("ImageData"), "Piece") => {
                let extent = match attribute(path, &element, "Extent")? {
                    Some(text) => parse_extent(path, &text)?,
                    None => whole_extent
                        .ok_or_else(|| DataError::format(path, "<Piece> has no Extent"))?,
                };
                pieces.push(Piece {
                    extent,
                    point: DataSet::default(),
                    cell: DataSet::default(),
                });
            }
            (Some("Piece"), set @ ("PointData" | "CellData")) => {
                if let Some(piece) = pieces.last_mut() {
                    let data = if set == "CellData" {
                        &mut piece.cell
                    } else {
                        &mut piece.point
                    };
                    data.active = attribute(path, &element, "Scalars")?;
                }
            }
            (Some(set @ ("PointData" | "CellData")), "DataArray")
                if grandparent == Some("Piece") =>
            {
                let cell = set == "CellData";
                if let Some(piece) = pieces.last_mut() {
                    let data = if cell {
                        &mut piece.cell
                    } else {
                        &mut piece.point
                    };
                    data.arrays.push(array_attributes(path, &element)?);
                    capturing = (!empty).then_some(Capture {
                        cell,
                        depth: open.len() + 1,
                    });
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
    if whole_extent.is_none() {
        return Err(DataError::format(
            path,
            "no <ImageData> element in the VTKFile",
        ));
    }
    Ok(Markup {
        encoding,
        origin,
        spacing,
        direction,
        pieces,
        appended,
    })
}

/// Appends element text to the array being captured, if the text is directly inside it.
fn capture<'a>(
    capturing: Option<Capture>,
    depth: usize,
    pieces: &mut [Piece<'a>],
    text: Cow<'a, str>,
) {
    let Some(c) = capturing else {
        return;
    };
    if depth != c.depth {
        return;
    }
    let data = pieces
        .last_mut()
        .map(|p| if c.cell { &mut p.cell } else { &mut p.point });
    if let Some(array) = data.and_then(|d| d.arrays.last_mut()) {
        array.text.push(text);
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
    let compressor = match attribute(path, element, "compressor")?.as_deref() {
        None | Some("") => Compressor::None,
        Some("vtkZLibDataCompressor") => Compressor::Zlib,
        Some("vtkLZ4DataCompressor") => Compressor::Lz4,
        Some("vtkLZMADataCompressor") => Compressor::Lzma,
        Some(other) => Compressor::Unknown(other.to_string()),
    };
    Ok(Encoding {
        big_endian,
        wide_header,
        compressor,
    })
}

fn array_attributes<'a>(path: &Path, element: &BytesStart) -> Result<ArrayInfo<'a>, DataError> {
    Ok(ArrayInfo {
        name: attribute(path, element, "Name")?.unwrap_or_default(),
        type_name: attribute(path, element, "type")?,
        components: attribute(path, element, "NumberOfComponents")?,
        format: attribute(path, element, "format")?,
        offset: attribute(path, element, "offset")?,
        text: Vec::new(),
    })
}

/// `x0 x1 y0 y1 z0 z1`, inclusive point indices; `x1 = x0 - 1` (or less) makes an empty piece,
/// as VTK writes for pieces that got no data.
fn parse_extent(path: &Path, text: &str) -> Result<[i64; 6], DataError> {
    let bad = || DataError::format(path, format!("bad extent `{text}`"));
    let numbers = text
        .split_ascii_whitespace()
        .map(|t| t.parse::<i64>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| bad())?;
    let extent: [i64; 6] = numbers.try_into().map_err(|_| bad())?;
    // Bounded so that the counts computed from it cannot overflow.
    const LIMIT: i64 = 1 << 40;
    if extent.iter().any(|e| !(-LIMIT..=LIMIT).contains(e)) {
        return Err(bad());
    }
    Ok(extent)
}

/// `N` finite numbers (Origin, Spacing: 3; Direction: 9).
fn parse_numbers<const N: usize>(
    path: &Path,
    what: &str,
    text: &str,
) -> Result<[f64; N], DataError> {
    let bad = || DataError::format(path, format!("bad {what} `{text}`"));
    let numbers = text
        .split_ascii_whitespace()
        .map(|t| t.parse::<f64>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| bad())?;
    let v: [f64; N] = numbers.try_into().map_err(|_| bad())?;
    if v.iter().any(|x| !x.is_finite()) {
        return Err(bad());
    }
    Ok(v)
}
