//! NRRD volumes: `.nrrd` (header and data in one file) and `.nhdr` (header naming its data files).
//!
//! Parsed by hand. There is no maintained NRRD reader crate: crates.io has no `nrrd` or
//! `nrrd-rs` crate (looked up in 2026-11), and the only Rust NRRD code found, a module of the
//! young `bioformats` 0.1 reimplementation of Bio-Formats, is a large dependency for one
//! format. The format is small (a text header, then raw, gzip or ASCII data), so the reader is
//! here, following teem's format definition (<https://teem.sourceforge.net/nrrd/format.html>)
//! and checked against ITK's NrrdImageIO (through SimpleITK) for the geometry.

use std::io::{BufRead, BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use crate::geometry::Geometry;
use crate::raw_voxels::{self, Element};
use crate::{DataError, VolumeData};

mod space;
use space::{geometry, space_directions, spatial_axes};

/// A header longer than this is not a header (a binary file without the blank line).
const MAX_HEADER_BYTES: u64 = 16 << 20;

/// Field names we know, lower case without spaces (teem accepts `datafile` for `data file`
/// and so on). Any other field is an error, as in teem: a misspelt `space directions` must not
/// silently drop the geometry.
const KNOWN_FIELDS: &str = "content number type blocksize dimension space spacedimension sizes \
    spacedirections spacings thicknesses axismins axismaxs centers centerings kinds labels units \
    min max oldmin oldmax endian encoding lineskip byteskip sampleunits spaceunits spaceorigin \
    measurementframe datafile";

/// Loads a NRRD volume (`.nrrd`, or a detached `.nhdr` header and its data files).
///
/// * Data: `encoding` raw, gzip (`gz`) or ASCII (`text`, `txt`, `ascii`), in one or several
///   files: attached after the header's blank line, `data file: NAME` (relative to the header's
///   folder), `data file: LIST` (names on the following lines) or `data file: FORMAT MIN MAX
///   STEP` (`%d`-style names). `line skip` and `byte skip` apply to each data file (for gzip the
///   byte skip counts decompressed bytes); `byte skip: -1` means the raw data ends the file.
/// * Types: (u)int8/16/32/64, float and double in either `endian`. u8, i8, u16, i16 and f32
///   stay as they are; wider integers and double are converted to f32 (integers above 2^24 and
///   double values lose precision).
/// * `dimension: 3`, or 4 with one non-spatial axis (a `none` space direction, a kind other
///   than `domain`/`space`, or size 1): of a `list` or `time` axis the first 3-D volume is read
///   (said in [`VolumeData::placement`]); per-voxel components (colours, vectors, tensors) are
///   refused.
/// * Geometry: `space directions` (columns: direction × spacing) and `space origin` in
///   `space` right-anterior-superior, left-posterior-superior or left-anterior-superior are
///   turned into hatchery's RAS+ mm world; `3D-right-handed`, `scanner-xyz` or a bare
///   `space dimension: 3` are taken as given. Without space fields: `spacings` (else 1) and
///   `axis mins` (else 0; a cell-centred axis starts half a spacing after its min, as ITK
///   reads it), axis-aligned. `measurement frame` (for vector values) and `space units` are
///   ignored.
///
/// Errors: [`DataError::Format`] for a malformed header or truncated data,
/// [`DataError::Unsupported`] for valid files we do not read (bzip2, block type, other
/// spaces, components, a data file that is not a regular file such as `/dev/zero`), [`DataError::TooLarge`] above [`crate::nifti_file::MAX_VOXELS`] values
/// (checked before anything is allocated), [`DataError::Io`] when a file cannot be read.
pub fn load_nrrd(path: &Path) -> Result<VolumeData, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let header = read_header(path, &mut BufReader::new(file))?;
    let layout = check_header(path, &header, crate::voxels::MAX_VOXELS)?;

    let mut bytes = Vec::new();
    let per_file = layout.element_count * layout.element.size() / layout.sources.len();
    for source in &layout.sources {
        bytes.extend(read_source(path, &layout, source, per_file)?);
        if layout.encoding == Encoding::Text {
            bytes.push(b'\n'); // values of consecutive files must not run together
        }
    }
    if layout.encoding == Encoding::Text {
        let text = String::from_utf8_lossy(&bytes);
        bytes = raw_voxels::parse_ascii(path, &text, layout.element, layout.element_count)?;
    }
    let (inner, size) = layout.skipped_axis;
    let bytes = raw_voxels::first_along_axis(bytes, layout.element, inner, size);
    let big_endian = layout.big_endian && layout.encoding != Encoding::Text;
    let voxels = raw_voxels::decode(&bytes, layout.element, big_endian);
    let mut volume = VolumeData::from_voxels(layout.dims, layout.geometry, voxels)
        .map_err(|e| e.in_file(path))?;
    volume.stored_type = layout.element.name();
    volume.placement = layout.placement;
    Ok(volume)
}

/// A raw-encoded NRRD's voxels (attached or in one detached file) read box by box from the
/// memory-mapped data, without holding them (streaming, [`crate::brick_source`]); any size.
/// Errors: as [`load_nrrd`]; encodings other than raw (gzip, text cannot be read a box at a
/// time: `hatchery convert` to OME-Zarr), several data files, a `line skip`, a 4-D file.
pub fn nrrd_source(path: &Path) -> Result<crate::raw_source::RawSource, DataError> {
    let file = crate::files::open(path).map_err(|e| DataError::io(path, e))?;
    let header = read_header(path, &mut BufReader::new(file))?;
    // 2⁴⁸ voxels: far beyond any disk, low enough that byte counts cannot overflow.
    let layout = check_header(path, &header, 1 << 48)?;
    let refuse = |why: &str| {
        Err(DataError::unsupported(
            path,
            format!("{why}: not read a brick at a time (`hatchery convert` it to OME-Zarr)"),
        ))
    };
    if layout.encoding != Encoding::Raw {
        return refuse("compressed or text voxel data");
    }
    let [source] = layout.sources.as_slice() else {
        return refuse("several data files");
    };
    if layout.line_skip > 0 {
        return refuse("`line skip`");
    }
    if layout.skipped_axis != (1, 1) {
        return refuse("a non-spatial axis");
    }
    crate::raw_source::RawSource::open(
        &source.path,
        layout.byte_skip.map(|b| source.offset + b),
        layout.element,
        layout.big_endian,
        layout.dims,
        layout.geometry,
    )
}

/// The header's fields in file order (names lower case without spaces), where the data
/// starts when it is attached, and the file names of a `data file: LIST`.
struct Header {
    fields: Vec<(String, String)>,
    data_offset: u64,
    /// The header ended at the end of the file (no blank line, so nothing attached).
    ended_at_eof: bool,
    list: Vec<String>,
}

impl Header {
    fn get(&self, name: &str) -> Option<&str> {
        self.fields
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }
}

fn read_header(path: &Path, reader: &mut dyn BufRead) -> Result<Header, DataError> {
    let mut header = Header {
        fields: Vec::new(),
        data_offset: 0,
        ended_at_eof: true,
        list: Vec::new(),
    };
    let mut in_list = false;
    let mut raw = Vec::new();
    let mut first = true;
    loop {
        raw.clear();
        let n = reader
            .take(MAX_HEADER_BYTES + 1)
            .read_until(b'\n', &mut raw)
            .map_err(|e| DataError::io(path, e))?;
        if n == 0 {
            break;
        }
        header.data_offset += n as u64;
        if header.data_offset > MAX_HEADER_BYTES {
            return Err(DataError::format(
                path,
                "header is longer than 16 MiB (no blank line ends it)",
            ));
        }
        let line = String::from_utf8_lossy(&raw);
        let line = line.trim_end_matches(['\n', '\r']);
        if first {
            first = false;
            if !(line.len() == 8 && line.starts_with("NRRD000")) {
                return Err(DataError::format(
                    path,
                    "not a NRRD file (the first line is not a NRRD000x magic)",
                ));
            }
            continue;
        }
        if line.is_empty() {
            header.ended_at_eof = false;
            break;
        }
        if line.starts_with('#') {
            continue;
        }
        if in_list {
            header.list.push(line.trim().to_string());
            continue;
        }
        let (name, value) = line.split_once(':').unwrap_or((line, ""));
        if value.starts_with('=') {
            continue; // key:=value pairs carry no geometry or data layout.
        }
        let name = name.to_ascii_lowercase().replace(' ', "");
        if !KNOWN_FIELDS.split_whitespace().any(|f| f == name) {
            return Err(DataError::format(
                path,
                format!("unknown header field `{line}`"),
            ));
        }
        if header.get(&name).is_some() {
            return Err(DataError::format(
                path,
                format!("field `{name}` is given twice"),
            ));
        }
        let value = value.trim().to_string();
        in_list = name == "datafile" && value.split_whitespace().next() == Some("LIST");
        header.fields.push((name, value));
    }
    if first {
        return Err(DataError::format(path, "empty file, not a NRRD file"));
    }
    Ok(header)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Raw,
    Gzip,
    Text,
}

/// What the header says about the data, validated.
struct Layout {
    element: Element,
    encoding: Encoding,
    big_endian: bool,
    /// Elements in the data files (including any non-spatial axis).
    element_count: usize,
    /// Of a 4-D file: (elements before the non-spatial axis, its size); else (1, 1).
    skipped_axis: (usize, usize),
    dims: [u32; 3],
    geometry: Geometry,
    placement: String,
    sources: Vec<Source>,
    line_skip: u64,
    /// `None`: -1, the data ends the file.
    byte_skip: Option<u64>,
}

/// One data file and where in it this header's part starts.
struct Source {
    path: PathBuf,
    offset: u64,
}

/// The header's layout, refused above `limit` voxels.
fn check_header(path: &Path, h: &Header, limit: u64) -> Result<Layout, DataError> {
    let require = |name: &str| {
        h.get(name)
            .ok_or_else(|| DataError::format(path, format!("header has no `{name}` field")))
    };
    let dimension: usize = parse(path, "dimension", require("dimension")?)?;
    if !(3..=4).contains(&dimension) {
        return Err(DataError::unsupported(
            path,
            format!("dimension {dimension}: only 3-D volumes (and 4-D series of them) are read"),
        ));
    }
    let sizes: Vec<u64> = list(path, "sizes", require("sizes")?)?;
    if sizes.len() != dimension || sizes.contains(&0) {
        return Err(DataError::format(
            path,
            format!("`sizes` must give {dimension} positive sizes, got {sizes:?}"),
        ));
    }
    let element_count = raw_voxels::checked_count_within(path, &sizes, limit)? as usize;
    let element = element_type(path, require("type")?)?;
    let encoding = match require("encoding")?.to_ascii_lowercase().as_str() {
        "raw" => Encoding::Raw,
        "gzip" | "gz" => Encoding::Gzip,
        "text" | "txt" | "ascii" => Encoding::Text,
        other => {
            return Err(DataError::unsupported(
                path,
                format!("encoding `{other}` is not supported (raw, gzip and ascii are)"),
            ));
        }
    };
    let big_endian = match h.get("endian").map(str::to_ascii_lowercase).as_deref() {
        Some("big") => true,
        Some("little") => false,
        Some(other) => return Err(DataError::format(path, format!("bad endian `{other}`"))),
        None if element.size() > 1 && encoding != Encoding::Text => {
            return Err(DataError::format(
                path,
                format!("{} data needs an `endian` field", element.name()),
            ));
        }
        None => false,
    };

    let kinds: Option<Vec<String>> = h.get("kinds").map(|k| {
        k.split_whitespace()
            .map(|s| s.to_ascii_lowercase())
            .collect()
    });
    if kinds.as_ref().is_some_and(|k| k.len() != dimension) {
        return Err(DataError::format(
            path,
            format!("`kinds` must name {dimension} axes"),
        ));
    }
    let directions = match h.get("spacedirections") {
        Some(v) => Some(space_directions(path, v, dimension)?),
        None => None,
    };
    let (spatial, skipped_axis, series) =
        spatial_axes(path, &sizes, kinds.as_deref(), directions.as_deref())?;
    let dims = spatial.map(|a| sizes[a] as u32);
    let (geometry, mut placement) = geometry(path, h, dimension, &spatial, directions.as_deref())?;
    if let Some(series) = series {
        placement.push_str(&format!("; {series}"));
    }

    let line_skip: u64 = h
        .get("lineskip")
        .map_or(Ok(0), |v| parse(path, "line skip", v))?;
    let byte_skip = match h
        .get("byteskip")
        .map_or(Ok(0), |v| parse::<i64>(path, "byte skip", v))?
    {
        -1 if encoding == Encoding::Raw => None,
        -1 => {
            return Err(DataError::format(
                path,
                "`byte skip: -1` needs raw encoding",
            ));
        }
        n if n >= 0 => Some(n as u64),
        n => return Err(DataError::format(path, format!("bad byte skip {n}"))),
    };
    let sources = data_sources(path, h)?;
    if !element_count.is_multiple_of(sources.len()) {
        return Err(DataError::format(
            path,
            format!(
                "{element_count} values do not split evenly over {} data files",
                sources.len()
            ),
        ));
    }
    Ok(Layout {
        element,
        encoding,
        big_endian,
        element_count,
        skipped_axis,
        dims,
        geometry,
        placement,
        sources,
        line_skip,
        byte_skip,
    })
}

fn element_type(path: &Path, name: &str) -> Result<Element, DataError> {
    // teem's spellings of the C types.
    Ok(match name.to_ascii_lowercase().as_str() {
        "signed char" | "int8" | "int8_t" => Element::I8,
        "uchar" | "unsigned char" | "uint8" | "uint8_t" => Element::U8,
        "short" | "short int" | "signed short" | "signed short int" | "int16" | "int16_t" => {
            Element::I16
        }
        "ushort" | "unsigned short" | "unsigned short int" | "uint16" | "uint16_t" => Element::U16,
        "int" | "signed int" | "int32" | "int32_t" => Element::I32,
        "uint" | "unsigned int" | "uint32" | "uint32_t" => Element::U32,
        "longlong"
        | "long long"
        | "long long int"
        | "signed long long"
        | "signed long long int"
        | "int64"
        | "int64_t" => Element::I64,
        "ulonglong" | "unsigned long long" | "unsigned long long int" | "uint64" | "uint64_t" => {
            Element::U64
        }
        "float" => Element::F32,
        "double" => Element::F64,
        "block" => {
            return Err(DataError::unsupported(
                path,
                "type `block` is not supported",
            ));
        }
        other => return Err(DataError::format(path, format!("unknown type `{other}`"))),
    })
}

/// The data files, in order, from `data file` (or the file itself when the data is attached).
fn data_sources(path: &Path, h: &Header) -> Result<Vec<Source>, DataError> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let file = |name: &str| Source {
        path: dir.join(name),
        offset: 0,
    };
    let Some(value) = h.get("datafile") else {
        if h.ended_at_eof {
            return Err(DataError::format(
                path,
                "no data: the header has no `data file` and no blank line before attached data",
            ));
        }
        return Ok(vec![Source {
            path: path.to_path_buf(),
            offset: h.data_offset,
        }]);
    };
    let words: Vec<&str> = value.split_whitespace().collect();
    let sources: Vec<Source> = match words[..] {
        ["LIST", ..] => h.list.iter().map(|n| file(n)).collect(),
        [pattern, min, max, step, ..] if pattern.contains('%') => {
            let min: i64 = parse(path, "data file", min)?;
            let max: i64 = parse(path, "data file", max)?;
            let step: i64 = parse(path, "data file", step)?;
            // Checked: the numbers come from the file.
            let count = max.checked_sub(min).and_then(|d| d.checked_div(step));
            let count = count.filter(|c| (0..100_000).contains(c)).unwrap_or(-1);
            if count < 0 {
                return Err(DataError::format(
                    path,
                    format!("bad data file range `{value}`"),
                ));
            }
            (0..=count)
                .map(|i| format_name(path, pattern, min.saturating_add(i.saturating_mul(step))))
                .map(|name| name.map(|n| file(&n)))
                .collect::<Result<_, _>>()?
        }
        _ => vec![file(value)],
    };
    if sources.is_empty() {
        return Err(DataError::format(path, "`data file: LIST` names no files"));
    }
    Ok(sources)
}

/// A `data file` pattern with one `%d`, `%Nd` or `%0Nd`.
fn format_name(path: &Path, pattern: &str, n: i64) -> Result<String, DataError> {
    let bad = || DataError::unsupported(path, format!("data file pattern `{pattern}`"));
    let start = pattern.find('%').ok_or_else(bad)?;
    let rest = &pattern[start + 1..];
    let end = rest.find('d').ok_or_else(bad)?;
    let spec = &rest[..end];
    let width: usize = if spec.is_empty() {
        0
    } else {
        spec.parse().map_err(|_| bad())?
    };
    let number = if spec.starts_with('0') {
        format!("{n:0width$}")
    } else {
        format!("{n:width$}")
    };
    Ok(format!("{}{number}{}", &pattern[..start], &rest[end + 1..]))
}

/// Reads one data file's share (`len` bytes once decoded; text is read whole).
fn read_source(
    header: &Path,
    layout: &Layout,
    source: &Source,
    len: usize,
) -> Result<Vec<u8>, DataError> {
    // Errors name the data file when it is not the header itself.
    let path = source.path.as_path();
    let what = if path == header {
        "the attached data"
    } else {
        "the data file"
    };
    let (mut file, file_len) = raw_voxels::open_data_file(path, what)?;
    if layout.byte_skip.is_none() {
        let start = file_len
            .checked_sub(len as u64)
            .filter(|&s| s >= source.offset);
        let start = start.ok_or_else(|| {
            DataError::format(
                path,
                format!("truncated data: {what} is shorter than {len} bytes"),
            )
        })?;
        file.seek(SeekFrom::Start(start))
            .map_err(|e| DataError::io(path, e))?;
        return raw_voxels::read_bytes(path, &mut file, len, what, len as u64);
    }
    // What the file can hold after the offset (line and byte skips only take from it).
    let available = raw_voxels::decoded_bound(
        file_len.saturating_sub(source.offset),
        layout.encoding == Encoding::Gzip,
    );
    file.seek(SeekFrom::Start(source.offset))
        .map_err(|e| DataError::io(path, e))?;
    let mut reader = BufReader::new(file);
    raw_voxels::skip_lines(path, &mut reader, layout.line_skip, what)?;
    let mut data: Box<dyn Read> = match layout.encoding {
        Encoding::Gzip => {
            raw_voxels::inflate(Box::new(reader)).map_err(|e| DataError::io(path, e))?
        }
        _ => Box::new(reader),
    };
    raw_voxels::skip_bytes(path, &mut data, layout.byte_skip.unwrap_or(0), what)?;
    if layout.encoding == Encoding::Text {
        // Enough for any number in text form; a shorter read is found by the value count.
        let mut text = Vec::new();
        data.take(len as u64 * 16 + 4096)
            .read_to_end(&mut text)
            .map_err(|e| DataError::io(path, e))?;
        return Ok(text);
    }
    raw_voxels::read_bytes(path, &mut data, len, what, available)
}

fn parse<T: std::str::FromStr>(path: &Path, field: &str, value: &str) -> Result<T, DataError> {
    value
        .trim()
        .parse()
        .map_err(|_| DataError::format(path, format!("bad {field} `{value}`")))
}

fn list<T: std::str::FromStr>(path: &Path, field: &str, value: &str) -> Result<Vec<T>, DataError> {
    value
        .split_whitespace()
        .map(|v| parse(path, field, v))
        .collect()
}
