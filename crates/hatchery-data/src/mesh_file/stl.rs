//! STL, ASCII and binary, read by hand.
//!
//! stl_io (used before) was stricter and lossier than trimesh, VTK and MeshLab: its ASCII reader
//! stops after the first `solid … endsolid` block, refuses a bare `solid` line and upper-case
//! keywords; its binary reader trusts the triangle count of the header (so a file with a bogus
//! count of 0, which VTK recovers from, loses its triangles silently); and it welds vertices by
//! bit pattern, so `0.0` and `-0.0` stay apart. Both formats are short enough to read here.

use std::collections::HashMap;
use std::path::Path;

use super::{ENDS_EARLY, Words};
use crate::{DataError, MeshData};

/// Binary STL: 80-byte header, u32 triangle count, then 50 bytes per triangle.
const HEADER: usize = 84;
const RECORD: usize = 50;

/// Reads an STL file from its bytes (see [`super::load_mesh`] for the variants accepted).
pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<MeshData, DataError> {
    let mut welder = Welder::default();
    if is_binary(bytes) {
        read_binary(bytes, &mut welder).map_err(|m| DataError::format(path, m))?;
    } else {
        let text = String::from_utf8_lossy(without_padding(bytes));
        read_ascii(&text, &mut welder).map_err(|m| DataError::format(path, m))?;
    }
    MeshData::new(welder.positions, None, welder.indices).map_err(|e| e.in_file(path))
}

/// The bytes without trailing NUL and white space (some tools pad text files with NULs to a
/// block size).
fn without_padding(bytes: &[u8]) -> &[u8] {
    let end = bytes
        .iter()
        .rposition(|&b| b != 0 && !b.is_ascii_whitespace())
        .map_or(0, |last| last + 1);
    &bytes[..end]
}

/// Binary if the size is exactly that of a binary STL with the count in the header (as
/// trimesh decides; many binary writers start the header with "solid"). Otherwise ASCII if the
/// file starts with "solid" (any case, after white space) and has no NUL byte near the start
/// before any trailing padding (binary headers and counts nearly always hold one; text never
/// does).
fn is_binary(bytes: &[u8]) -> bool {
    if let Some(count) = header_count(bytes)
        && bytes.len() as u64 == HEADER as u64 + RECORD as u64 * count as u64
    {
        return true;
    }
    let text = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let start = text.iter().position(|b| !b.is_ascii_whitespace());
    let starts_with_solid = start.is_some_and(|s| {
        text.get(s..s + 5)
            .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
    });
    let content = without_padding(bytes);
    !starts_with_solid || content[..content.len().min(1024)].contains(&0)
}

fn header_count(bytes: &[u8]) -> Option<u32> {
    let count: [u8; 4] = bytes.get(80..HEADER)?.try_into().ok()?;
    Some(u32::from_le_bytes(count))
}

fn read_binary(bytes: &[u8], welder: &mut Welder) -> Result<(), String> {
    let Some(count) = header_count(bytes) else {
        return Err(if bytes.is_empty() {
            "the file is empty".to_string()
        } else {
            format!(
                "not an STL file: {} bytes, too short for binary STL (at least {HEADER}), \
                 and it does not start with 'solid' as ASCII STL does",
                bytes.len()
            )
        });
    };
    let count = count as usize;
    let records = (bytes.len() - HEADER) / RECORD;
    let extra = (bytes.len() - HEADER) % RECORD;
    let triangles = if count > records {
        return Err(format!(
            "{ENDS_EARLY}, or is not STL: the header says {count} triangles, \
             the file holds {records}"
        ));
    } else if count == records {
        // Fewer than 50 bytes after the last triangle cannot hold another one.
        count
    } else if extra == 0 {
        // A count smaller than the data, often 0 from writers that stream: read every
        // triangle, as VTK does.
        records
    } else {
        return Err(format!(
            "binary STL whose size does not fit its header: {count} triangles declared, \
             room for {records} and {extra} bytes more"
        ));
    };
    for (t, record) in bytes[HEADER..]
        .chunks_exact(RECORD)
        .take(triangles)
        .enumerate()
    {
        // 12 bytes of face normal (unused: vertex normals are computed), 3 vertices, 2 bytes
        // of attributes.
        let f = |i: usize| {
            let at = 12 + 4 * i;
            f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]])
        };
        let vertices = [0, 1, 2].map(|v| [f(3 * v), f(3 * v + 1), f(3 * v + 2)]);
        if vertices.iter().flatten().any(|c| !c.is_finite()) {
            return Err(format!("triangle {t} has a non-finite vertex coordinate"));
        }
        welder.triangle(vertices)?;
    }
    Ok(())
}

/// ASCII STL: one or more `solid [name] … endsolid [name]` blocks of
/// `facet normal n n n / outer loop / vertex x y z (×3) / endloop / endfacet`. Keywords in any
/// case, any white space and line ends (LF, CRLF, CR) between words, names ignored. The last
/// `endsolid` may be missing. A loop of more than three vertices is fan-triangulated.
fn read_ascii(text: &str, welder: &mut Welder) -> Result<(), String> {
    let mut words = Words::new(text.strip_prefix('\u{feff}').unwrap_or(text), 1);
    while let Some((word, line)) = words.next() {
        // The name, if any, is the rest of the line; "solidname" (no space) is seen too.
        if !word
            .get(..5)
            .is_some_and(|w| w.eq_ignore_ascii_case("solid"))
        {
            return Err(words.unexpected(word, line, "'solid'"));
        }
        words.skip_line();
        read_solid(&mut words, welder)?;
    }
    Ok(())
}

/// Reads facets up to `endsolid` (or the end of the file).
fn read_solid(words: &mut Words, welder: &mut Welder) -> Result<(), String> {
    loop {
        let Some((word, line)) = words.next() else {
            return Ok(());
        };
        // "endsolidname" (no space) is seen too, as "solidname" is.
        if word
            .get(..8)
            .is_some_and(|w| w.eq_ignore_ascii_case("endsolid"))
        {
            words.skip_line();
            return Ok(());
        }
        if !word.eq_ignore_ascii_case("facet") {
            return Err(words.unexpected(word, line, "'facet' or 'endsolid'"));
        }
        words.expect("normal")?;
        // The face normal is not used (vertex normals are computed), so any three words do,
        // e.g. the "nan" or "1.#QNAN" some writers give degenerate facets.
        for _ in 0..3 {
            words.required("a normal component")?;
        }
        words.expect("outer")?;
        words.expect("loop")?;
        let mut polygon = Vec::with_capacity(3);
        loop {
            let (word, line) = words.required("'vertex' or 'endloop'")?;
            if word.eq_ignore_ascii_case("endloop") {
                break;
            }
            if !word.eq_ignore_ascii_case("vertex") {
                return Err(words.unexpected(word, line, "'vertex' or 'endloop'"));
            }
            polygon.push([coordinate(words)?, coordinate(words)?, coordinate(words)?]);
        }
        if polygon.len() < 3 {
            return Err(format!(
                "line {line}: facet has {} vertices, a triangle needs 3",
                polygon.len()
            ));
        }
        words.expect("endfacet")?;
        for i in 1..polygon.len() - 1 {
            welder.triangle([polygon[0], polygon[i], polygon[i + 1]])?;
        }
    }
}

fn coordinate(words: &mut Words) -> Result<f32, String> {
    let (word, line) = words.required("a vertex coordinate")?;
    match word.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(words.unexpected(word, line, "a finite vertex coordinate")),
    }
}

/// Builds an indexed mesh from triangles, sharing vertices at identical positions (STL stores
/// every triangle's corners separately). `-0.0` and `0.0` are the same position.
#[derive(Default)]
struct Welder {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    index_of: HashMap<[u32; 3], u32>,
}

impl Welder {
    fn triangle(&mut self, corners: [[f32; 3]; 3]) -> Result<(), String> {
        for p in corners {
            // Adding +0.0 turns -0.0 into +0.0 and leaves every other value alone.
            let key = p.map(|c| (c + 0.0).to_bits());
            let next = u32::try_from(self.positions.len())
                .map_err(|_| "too many vertices for 32-bit indices".to_string())?;
            let index = *self.index_of.entry(key).or_insert(next);
            if index == next {
                self.positions.push(p.map(|c| c + 0.0));
            }
            self.indices.push(index);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ascii(text: &str) -> Result<Welder, String> {
        let mut w = Welder::default();
        read_ascii(text, &mut w).map(|()| w)
    }

    #[test]
    fn words_count_lines_for_every_line_end() {
        let mut w = Words::new("a\r\nb\rc\n\n d\te", 1);
        let all: Vec<_> = std::iter::from_fn(|| w.next()).collect();
        assert_eq!(all, vec![("a", 1), ("b", 2), ("c", 3), ("d", 5), ("e", 5)]);
    }

    #[test]
    fn errors_give_the_line() {
        let text = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                    vertex 0 1 zero\nendloop\nendfacet\nendsolid\n";
        let e = ascii(text).err().unwrap();
        assert!(e.starts_with("line 6:") && e.contains("'zero'"), "{e}");
        let e = ascii("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n")
            .err()
            .unwrap();
        assert!(e.contains("truncated") && e.contains("line 4"), "{e}");
        let e = ascii("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop")
            .err()
            .unwrap();
        assert!(e.contains("1 vertices"), "{e}");
        let e = ascii("solid x\nendsolid x\nsomething else\n")
            .err()
            .unwrap();
        assert!(e.starts_with("line 3: expected 'solid'"), "{e}");
    }

    #[test]
    fn negative_zero_is_welded_to_zero() {
        let mut w = Welder::default();
        w.triangle([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
            .unwrap();
        w.triangle([[-0.0, 0.0, -0.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])
            .unwrap();
        assert_eq!(w.positions.len(), 4);
        assert_eq!(w.indices, vec![0, 1, 2, 0, 3, 1]);
        assert!(
            w.positions
                .iter()
                .flatten()
                .all(|c| c.to_bits() != (-0.0f32).to_bits())
        );
    }
}
