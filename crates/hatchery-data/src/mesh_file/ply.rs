//! PLY: the header and binary data through ply-rs-bw, ASCII data read here.
//!
//! The header is cleaned before ply-rs-bw sees it (blank lines dropped, white space trimmed and
//! collapsed), as the crate takes a blank or indented header line for an error. Its ASCII data
//! reader wants exactly one entry per line and numbers in its own grammar (no `1.`, `.5`,
//! `nan`); MeshLab, trimesh and rply read ASCII data as a stream of white-space separated words,
//! and so does this module.

use std::collections::HashSet;
use std::io::Cursor;
use std::path::Path;

use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};

use super::{ENDS_EARLY, Words};
use crate::{DataError, MeshData};

/// Names under which the face element holds its vertex index list.
const INDEX_LISTS: [&str; 2] = ["vertex_indices", "vertex_index"];

/// Reads a PLY file from its bytes (see [`super::load_mesh`] for the variants accepted).
pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<MeshData, DataError> {
    let error = |message: String| DataError::format(path, message);
    let raw = split_header(bytes).map_err(error)?;
    let header = Parser::<Skip>::new()
        .read_header(&mut Reader::new(Cursor::new(raw.text.as_bytes())))
        .map_err(|e| error(header_message(&e, &raw)))?;
    check_header(&header, bytes.len()).map_err(error)?;

    let body = &bytes[raw.body_start..];
    let (vertices, faces) = match header.encoding {
        Encoding::Ascii => {
            let text = String::from_utf8_lossy(body);
            read_ascii(&header, &mut Words::new(&text, raw.body_line))
        }
        Encoding::BinaryBigEndian | Encoding::BinaryLittleEndian => read_binary(&header, body),
    }
    .map_err(error)?;

    let has_normals = ["nx", "ny", "nz"]
        .iter()
        .all(|k| header.elements["vertex"].properties.contains_key(*k));
    let positions = vertices.iter().map(|v| v.position).collect();
    let normals = has_normals.then(|| vertices.iter().map(|v| v.normal).collect());
    let mut indices = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let polygon = face
            .indices
            .iter()
            .map(|&i| u32::try_from(i))
            .collect::<Result<Vec<u32>, _>>()
            .map_err(|_| error(format!("face {f} has a negative vertex index")))?;
        // Fan triangulation: fine for the convex polygons PLY files hold in practice.
        for i in 1..polygon.len().saturating_sub(1) {
            indices.extend([polygon[0], polygon[i], polygon[i + 1]]);
        }
    }
    MeshData::new(positions, normals, indices).map_err(|e| e.in_file(path))
}

/// The header as ply-rs-bw reads it, with where things are in the file.
struct RawHeader {
    /// Non-blank lines, trimmed, runs of white space made one space, each ending in `\n`.
    text: String,
    /// File line number (from 1) of each line of `text`.
    lines: Vec<usize>,
    /// Byte offset and line number of the data after `end_header`.
    body_start: usize,
    body_line: usize,
}

/// Finds the header and cleans it up: blank lines and white space around words do not matter,
/// line ends may be LF, CRLF or CR, text need not be UTF-8. Elements and properties declared
/// twice are refused (ply-rs-bw would keep only one and misread the data).
fn split_header(bytes: &[u8]) -> Result<RawHeader, String> {
    let mut pos = if bytes.starts_with(b"\xEF\xBB\xBF") {
        3
    } else {
        0
    };
    let mut line_number = 0;
    let mut raw = RawHeader {
        text: String::new(),
        lines: Vec::new(),
        body_start: 0,
        body_line: 0,
    };
    let mut elements = HashSet::new();
    let mut properties = HashSet::new();
    while pos < bytes.len() {
        let rest = &bytes[pos..];
        let end = rest
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
        pos += end
            + match rest.get(end..end + 2) {
                Some(b"\r\n") => 2,
                _ => usize::from(end < rest.len()),
            };
        line_number += 1;
        let line = String::from_utf8_lossy(&rest[..end]);
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some(&first) = words.first() else {
            continue;
        };
        if raw.lines.is_empty() && words != ["ply"] {
            return Err("not a PLY file: the first line is not 'ply'".to_string());
        }
        let twice = match (first, words.get(1)) {
            ("element", Some(name)) => {
                properties.clear();
                !elements.insert(name.to_string())
            }
            ("property", _) => !properties.insert(words[words.len() - 1].to_string()),
            _ => false,
        };
        if twice {
            return Err(format!("line {line_number}: '{line}' declared twice"));
        }
        raw.text += &words.join(" ");
        raw.text.push('\n');
        raw.lines.push(line_number);
        if first == "end_header" {
            raw.body_start = pos;
            raw.body_line = line_number + 1;
            return Ok(raw);
        }
    }
    Err(if raw.lines.is_empty() {
        "the file is empty".to_string()
    } else {
        format!("{ENDS_EARLY}: the header has no 'end_header' line")
    })
}

/// ply-rs-bw messages can span lines and count lines in the cleaned header; give the first
/// line of the message, with the file's line number and text.
fn header_message(e: &ParseError, raw: &RawHeader) -> String {
    let text = e.to_string();
    let first = text.lines().next().unwrap_or_default().trim();
    let Some(line) = e.line() else {
        return format!("invalid PLY header: {first}");
    };
    let message = first.split_once(": ").map_or(first, |(_, rest)| rest);
    let (number, cleaned) = match raw.lines.get(line.wrapping_sub(1)) {
        Some(&n) => (n, raw.text.lines().nth(line - 1).unwrap_or_default()),
        None => return format!("invalid PLY header: {message}"),
    };
    format!("line {number}: invalid PLY header line '{cleaned}': {message}")
}

/// Refuses what the data readers would misread or spend long on: counts the file cannot hold,
/// a vertex element without scalar x, y, z, a face element without an integer index list.
fn check_header(header: &Header, file_len: usize) -> Result<(), String> {
    for (name, element) in &header.elements {
        // Each entry takes at least one byte, so larger counts are lies.
        if element.count > file_len {
            return Err(format!(
                "element '{name}' declares {} entries the file cannot hold",
                element.count
            ));
        }
    }
    let vertex = header.elements.get("vertex").ok_or("no vertex element")?;
    for axis in ["x", "y", "z"] {
        match vertex.properties.get(axis).map(|p| &p.data_type) {
            Some(PropertyType::Scalar(_)) => {}
            _ => {
                return Err(format!(
                    "the vertex element has no scalar property '{axis}'"
                ));
            }
        }
    }
    let face = header.elements.get("face").ok_or("no face element")?;
    let list = INDEX_LISTS
        .iter()
        .find_map(|name| face.properties.get(*name))
        .ok_or("the face element has no 'vertex_indices' list")?;
    match &list.data_type {
        PropertyType::List(_, item) if !matches!(item, ScalarType::Float | ScalarType::Double) => {
            Ok(())
        }
        other => Err(format!(
            "face property '{}' has type {other:?}, not a list of integers",
            list.name
        )),
    }
}

type Mesh = (Vec<PlyVertex>, Vec<PlyFace>);

fn read_binary(header: &Header, body: &[u8]) -> Result<Mesh, String> {
    let mut reader = Reader::new(Cursor::new(body));
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    // Elements must be read in header order; skip the ones we do not use.
    for (name, element) in &header.elements {
        let failed = |e: ParseError| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                format!("{ENDS_EARLY} in element '{name}'")
            } else {
                let text = e.to_string();
                let first = text.lines().next().unwrap_or_default().to_string();
                format!("invalid data in element '{name}': {first}")
            }
        };
        match name.as_str() {
            "vertex" => {
                vertices = Parser::<PlyVertex>::new()
                    .read_payload_for_element(&mut reader, element, header)
                    .map_err(failed)?;
            }
            "face" => {
                faces = Parser::<PlyFace>::new()
                    .read_payload_for_element(&mut reader, element, header)
                    .map_err(failed)?;
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, element, header)
                    .map_err(failed)?;
            }
        }
    }
    let end = reader.get_ref().position() as usize;
    let rest = &body[end.min(body.len())..];
    if rest.iter().any(|&b| b != 0 && !b.is_ascii_whitespace()) {
        return Err(format!(
            "{} bytes of data after the last element (does the header declare too few entries?)",
            rest.len()
        ));
    }
    Ok((vertices, faces))
}

fn read_ascii(header: &Header, words: &mut Words) -> Result<Mesh, String> {
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for (name, element) in &header.elements {
        match name.as_str() {
            "vertex" => vertices = read_ascii_element(element, words)?,
            "face" => faces = read_ascii_element(element, words)?,
            _ => {
                read_ascii_element::<Skip>(element, words)?;
            }
        }
    }
    if let Some((word, line)) = words.next() {
        return Err(format!(
            "line {line}: data after the last element ('{word}'); \
             does the header declare too few entries?"
        ));
    }
    Ok((vertices, faces))
}

fn read_ascii_element<E: PropertyAccess>(
    element: &ElementDef,
    words: &mut Words,
) -> Result<Vec<E>, String> {
    let mut entries = Vec::new();
    for _ in 0..element.count {
        let mut entry = E::new();
        for (name, property) in &element.properties {
            let what = format!("property '{name}' of element '{}'", element.name);
            let value = match &property.data_type {
                PropertyType::Scalar(kind) => {
                    let (word, line) = words.required(&what)?;
                    ascii_scalar(kind, word).ok_or_else(|| {
                        words.unexpected(word, line, &format!("{} for {what}", name_of(kind)))
                    })?
                }
                PropertyType::List(count_kind, kind) => {
                    let (word, line) = words.required(&what)?;
                    let count = ascii_scalar(count_kind, word)
                        .and_then(|c| usize::try_from(int_value(&c)?).ok())
                        .ok_or_else(|| {
                            let expected = format!("a list length for {what}");
                            words.unexpected(word, line, &expected)
                        })?;
                    let items = (0..count)
                        .map(|_| words.required(&what))
                        .collect::<Result<Vec<_>, _>>()?;
                    let list: Vec<&str> = items.iter().map(|&(w, _)| w).collect();
                    ascii_list(kind, &list).ok_or_else(|| {
                        let (word, line) = items
                            .iter()
                            .find(|(w, _)| ascii_scalar(kind, w).is_none())
                            .copied()
                            .unwrap_or((word, line));
                        words.unexpected(word, line, &format!("{} for {what}", name_of(kind)))
                    })?
                }
            };
            entry.set_property(name, value);
        }
        entries.push(entry);
    }
    Ok(entries)
}

fn name_of(kind: &ScalarType) -> String {
    format!("{kind:?}").to_lowercase()
}

/// Integers may be written as `3.0` (trimesh reads every ASCII value as a float too).
fn ascii_int<T: TryFrom<i64>>(word: &str) -> Option<T> {
    let value = word.parse::<i64>().ok().or_else(|| {
        let v = word.parse::<f64>().ok()?;
        (v.fract() == 0.0 && v.abs() < 9.0e15).then_some(v as i64)
    })?;
    T::try_from(value).ok()
}

fn ascii_scalar(kind: &ScalarType, word: &str) -> Option<Property> {
    Some(match kind {
        ScalarType::Char => Property::Char(ascii_int(word)?),
        ScalarType::UChar => Property::UChar(ascii_int(word)?),
        ScalarType::Short => Property::Short(ascii_int(word)?),
        ScalarType::UShort => Property::UShort(ascii_int(word)?),
        ScalarType::Int => Property::Int(ascii_int(word)?),
        ScalarType::UInt => Property::UInt(ascii_int(word)?),
        ScalarType::Float => Property::Float(word.parse().ok()?),
        ScalarType::Double => Property::Double(word.parse().ok()?),
    })
}

fn ascii_list(kind: &ScalarType, words: &[&str]) -> Option<Property> {
    fn all<T>(words: &[&str], parse: impl Fn(&str) -> Option<T>) -> Option<Vec<T>> {
        words.iter().map(|w| parse(w)).collect()
    }
    Some(match kind {
        ScalarType::Char => Property::ListChar(all(words, ascii_int)?),
        ScalarType::UChar => Property::ListUChar(all(words, ascii_int)?),
        ScalarType::Short => Property::ListShort(all(words, ascii_int)?),
        ScalarType::UShort => Property::ListUShort(all(words, ascii_int)?),
        ScalarType::Int => Property::ListInt(all(words, ascii_int)?),
        ScalarType::UInt => Property::ListUInt(all(words, ascii_int)?),
        ScalarType::Float => Property::ListFloat(all(words, |w| w.parse().ok())?),
        ScalarType::Double => Property::ListDouble(all(words, |w| w.parse().ok())?),
    })
}

fn int_value(property: &Property) -> Option<i64> {
    Some(match *property {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        _ => return None,
    })
}

/// Reads any scalar property as f64; lists give `None`.
fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        ref other => int_value(other)? as f64,
    })
}

/// Reads any integer list as indices.
fn index_list(property: Property) -> Option<Vec<i64>> {
    fn conv<T: Into<i64>>(v: Vec<T>) -> Vec<i64> {
        v.into_iter().map(Into::into).collect()
    }
    Some(match property {
        Property::ListChar(v) => conv(v),
        Property::ListUChar(v) => conv(v),
        Property::ListShort(v) => conv(v),
        Property::ListUShort(v) => conv(v),
        Property::ListInt(v) => conv(v),
        Property::ListUInt(v) => conv(v),
        _ => return None,
    })
}

#[derive(Default)]
struct PlyVertex {
    position: [f32; 3],
    normal: [f32; 3],
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        Self::default()
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(v) = scalar(&property) else {
            return PropertyAccessResult::Ignored;
        };
        let v = v as f32;
        match name {
            "x" => self.position[0] = v,
            "y" => self.position[1] = v,
            "z" => self.position[2] = v,
            "nx" => self.normal[0] = v,
            "ny" => self.normal[1] = v,
            "nz" => self.normal[2] = v,
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

#[derive(Default)]
struct PlyFace {
    indices: Vec<i64>,
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        Self::default()
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        match index_list(property) {
            Some(list) if INDEX_LISTS.contains(&name) => {
                self.indices = list;
                PropertyAccessResult::Set
            }
            _ => PropertyAccessResult::Ignored,
        }
    }
}

/// Element type that keeps nothing, for elements we only need to get past.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}
