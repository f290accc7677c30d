//! Triangle meshes from OBJ, PLY and STL files.
//!
//! The readers aim to take whatever the common readers (trimesh, VTK, MeshLab) take, and to
//! refuse, with an error naming the file and where possible the line, what they cannot read
//! whole: a file is never loaded in part without saying so.

mod ply;
mod stl;

use std::path::Path;

use crate::{DataError, MeshData};

/// The file endings `load_mesh` reads (any case).
pub const MESH_ENDINGS: [&str; 3] = [".obj", ".ply", ".stl"];

/// Loads a mesh, choosing the format by the (case-insensitive) extension:
///
/// * `.obj`: all objects merged, polygons triangulated, normals used if every vertex has one.
///   Comments anywhere, also after data on a line (`v 1 2 3 # note`), blank lines, lines
///   continued with a trailing `\`, LF, CRLF or CR line ends, text that is not UTF-8.
///   Materials are not read.
/// * `.ply`: ASCII and binary (both endiannesses); polygons fan-triangulated; faces from a
///   `vertex_indices` or `vertex_index` list; normals from `nx`, `ny`, `nz` if present; other
///   elements and properties skipped. The header may have blank lines, indented lines and
///   `comment`/`obj_info` lines anywhere; ASCII data is read as white-space separated words,
///   so blank lines and entries spread over lines or run together do not matter, and numbers
///   may be written `1.`, `.5`, `1e3` or (in integer properties) `3.0`. Data after the last
///   declared entry is an error, not dropped.
/// * `.stl`: binary, or ASCII with one or more `solid … endsolid` blocks (all read), a bare
///   `solid` or `endsolid` or a name glued to them, keywords in any case, NULs padding the end, any mix of spaces, tabs, blank lines and
///   line ends, with or without a final line end or final `endsolid`. A file is binary when its
///   size is exactly 84 + 50 × the triangle count in its header (so a binary header starting
///   with "solid" is no trouble), or when it does not start with "solid"; a binary triangle
///   count smaller than the data (some writers leave it 0) is overridden by the data, as VTK
///   does, while a count larger than the data is an error (truncated file). Identical
///   positions are welded. STL only has face normals, so vertex normals are computed.
///
/// Missing or degenerate normals are computed from the triangles (area-weighted). A file
/// without any triangle is an error.
pub fn load_mesh(path: &Path) -> Result<MeshData, DataError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let read = || crate::files::read(path).map_err(|e| DataError::io(path, e));
    let mesh = match extension.as_str() {
        "obj" => load_obj(path, &read()?),
        "ply" => ply::read(path, &read()?),
        "stl" => stl::read(path, &read()?),
        _ => Err(DataError::unsupported(
            path,
            format!(
                "unknown mesh file extension, supported are {}",
                MESH_ENDINGS.join(", ")
            ),
        )),
    }?;
    if mesh.triangle_count() == 0 {
        return Err(DataError::format(path, "the file contains no triangles"));
    }
    Ok(mesh)
}

fn load_obj(path: &Path, bytes: &[u8]) -> Result<MeshData, DataError> {
    let text = clean_obj(bytes);
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    // tobj 4.0.5 multiplies texture coordinate and normal indices unchecked, so an index out of
    // range (e.g. `f 1/-9 ...` after three `vt`) overflows: a panic in debug builds, a wrong or
    // refused index in release ones. Refuse those faces first, as tobj refuses the others.
    for (slot, error) in [
        (0, tobj::LoadError::FaceVertexOutOfBounds),
        (1, tobj::LoadError::FaceTexCoordOutOfBounds),
        (2, tobj::LoadError::FaceNormalOutOfBounds),
    ] {
        if let Some(line) = first_bad_face(&text, slot) {
            return Err(DataError::format(
                path,
                format!("line {line}: invalid OBJ: {error}"),
            ));
        }
    }
    // tobj reads line by line and stops at a bad one, so what it has consumed tells the line.
    let mut rest = text.as_bytes();
    // Materials are irrelevant here; do not go looking for .mtl files.
    let result = tobj::load_obj_buf(&mut rest, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    });
    let (models, _materials) = result.map_err(|e| {
        use tobj::LoadError::*;
        let line = match e {
            // Found when an object is finished, after its faces were read.
            FaceVertexOutOfBounds => first_bad_face(&text, 0),
            FaceTexCoordOutOfBounds => first_bad_face(&text, 1),
            FaceNormalOutOfBounds => first_bad_face(&text, 2),
            FaceColorOutOfBounds | InvalidPolygon => None,
            _ => Some(text[..text.len() - rest.len()].matches('\n').count()),
        };
        let at = line.map(|n| format!("line {n}: ")).unwrap_or_default();
        DataError::format(path, format!("{at}invalid OBJ: {e}"))
    })?;

    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut indices = Vec::new();
    let mut all_have_normals = true;
    for model in models {
        let mesh = model.mesh;
        let base = u32::try_from(positions.len())
            .map_err(|_| DataError::format(path, "too many vertices"))?;
        let count = mesh.positions.len() / 3;
        positions.extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if mesh.normals.len() == mesh.positions.len() {
            normals.extend(mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
        } else {
            all_have_normals = false;
            normals.extend(std::iter::repeat_n([0.0; 3], count));
        }
        indices.extend(mesh.indices.iter().map(|&i| base.saturating_add(i)));
    }
    MeshData::new(positions, all_have_normals.then_some(normals), indices)
        .map_err(|e| e.in_file(path))
}

/// Prepares OBJ text for tobj, keeping one line per file line so line numbers hold: text that
/// is not UTF-8 is read (tobj refuses it), CRLF and CR line ends become LF, comments (from `#`
/// to the end of the line) are removed (tobj only knows `#` as a line's first word), lines
/// ending in `\` are joined to the next, and `mtllib`/`usemtl` lines are dropped (materials
/// are not read, and tobj refuses a `usemtl` without a name).
fn clean_obj(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes)
        .replace("\r\n", "\n")
        .replace('\r', "\n");
    let mut out = String::with_capacity(text.len());
    let mut joined = String::new();
    let mut continued = 0;
    for line in text.split('\n') {
        let code = line.split('#').next().unwrap_or_default().trim_end();
        if let Some(head) = code.strip_suffix('\\') {
            joined += head;
            joined.push(' ');
            continued += 1;
            continue;
        }
        joined += code;
        if !matches!(joined.split_whitespace().next(), Some("mtllib" | "usemtl")) {
            out += &joined;
        }
        // The joined line stands at its first line; the lines it took in stay, empty.
        out.extend(std::iter::repeat_n('\n', continued + 1));
        joined.clear();
        continued = 0;
    }
    out + &joined
}

/// The line of the first face whose `slot` (0 position, 1 texture coordinate, 2 normal)
/// index names nothing: 0, past the last in the file, or relative and before the first.
/// Texture coordinate and normal indices count only when the file has some (tobj ignores
/// them otherwise).
fn first_bad_face(text: &str, slot: usize) -> Option<usize> {
    let keyword = ["v", "vt", "vn"][slot];
    let total = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some(keyword))
        .count() as i64;
    if total == 0 && slot > 0 {
        return None;
    }
    let mut seen = 0;
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some(k) if k == keyword => seen += 1,
            Some("f" | "l") => {
                let bad = words.any(|w| {
                    let index = w.split('/').nth(slot).unwrap_or_default();
                    index
                        .parse::<i64>()
                        .is_ok_and(|i| i == 0 || i > total || i < -seen)
                });
                if bad {
                    return Some(n + 1);
                }
            }
            _ => {}
        }
    }
    None
}

const ENDS_EARLY: &str = "file ends early (truncated?)";

/// White-space separated words of a text format, with their line numbers.
struct Words<'a> {
    text: &'a str,
    pos: usize,
    /// Line of `pos`.
    line: usize,
    /// Line of the last word returned.
    last: usize,
}

impl<'a> Words<'a> {
    /// Words of `text`, whose first line is line `line` of the file.
    fn new(text: &'a str, line: usize) -> Self {
        Words {
            text,
            pos: 0,
            line,
            last: line,
        }
    }

    fn next(&mut self) -> Option<(&'a str, usize)> {
        let bytes = self.text.as_bytes();
        while let Some(&b) = bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            // CRLF counts once, at its LF; a lone CR (old Mac files) counts too.
            if b == b'\n' || (b == b'\r' && bytes.get(self.pos + 1) != Some(&b'\n')) {
                self.line += 1;
            }
            self.pos += 1;
        }
        let start = self.pos;
        while bytes
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        if self.pos == start {
            return None;
        }
        self.last = self.line;
        // Cutting at ASCII bytes keeps to char boundaries.
        Some((&self.text[start..self.pos], self.line))
    }

    /// Moves to the end of the current line (the line end is left to `next`).
    fn skip_line(&mut self) {
        let rest = &self.text.as_bytes()[self.pos..];
        self.pos += rest
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
    }

    /// The next word, or an error saying what was expected if the text ends.
    fn required(&mut self, what: &str) -> Result<(&'a str, usize), String> {
        self.next()
            .ok_or_else(|| format!("{ENDS_EARLY} after line {}, expected {what}", self.last))
    }

    /// The next word, which must be `keyword` in any case.
    fn expect(&mut self, keyword: &str) -> Result<(), String> {
        let (word, line) = self.required(&format!("'{keyword}'"))?;
        if word.eq_ignore_ascii_case(keyword) {
            Ok(())
        } else {
            Err(self.unexpected(word, line, &format!("'{keyword}'")))
        }
    }

    /// The message for a wrong `word` just read: if it is the last word of the text, the file
    /// was probably cut short in the middle of it.
    fn unexpected(&self, word: &str, line: usize, expected: &str) -> String {
        if self.text[self.pos..].trim_ascii().is_empty() {
            format!("{ENDS_EARLY} at line {line} in '{word}', expected {expected}")
        } else {
            format!("line {line}: expected {expected}, found '{word}'")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_face_indices_are_errors_with_their_line() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("faces.obj");
        let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvn 0 0 -1\n";
        for (face, what) in [
            // Relative, before the first texture coordinate: tobj's unchecked index arithmetic
            // overflowed (a panic in debug builds).
            ("f 1/-9 2/1 3/1", "texcoord"),
            // Relative, wrapping: 3 x the index wrapped to 1, so release builds read a normal
            // made of parts of normals 1 and 2 instead of refusing the face.
            ("f 1//-6148914691236517209 2//1 3//1", "normal"),
            ("f 1//9223372036854775807 2//1 3//1", "normal"),
        ] {
            std::fs::write(&p, format!("{head}# faces\n{face}\n")).unwrap();
            let msg = load_mesh(&p).unwrap_err().to_string();
            assert!(
                msg.contains("faces.obj: line 10: invalid OBJ") && msg.contains(what),
                "{face}: {msg}"
            );
        }
    }

    #[test]
    fn unknown_extension_lists_supported_ones() {
        let e = load_mesh(Path::new("model.fbx")).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, DataError::Unsupported { .. }));
        assert!(
            msg.starts_with("model.fbx: ") && msg.contains(".obj, .ply, .stl"),
            "{msg}"
        );
    }

    #[test]
    fn ply_header_with_huge_number_is_an_error_not_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("huge.ply");
        std::fs::write(
            &p,
            "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nend_header\n",
        )
        .unwrap();
        let msg = load_mesh(&p).unwrap_err().to_string();
        assert!(msg.contains("huge.ply"), "{msg}");
        // A count the file cannot hold.
        std::fs::write(
            &p,
            "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n",
        )
        .unwrap();
        let msg = load_mesh(&p).unwrap_err().to_string();
        assert!(
            msg.contains("huge.ply") && msg.contains("4000000000"),
            "{msg}"
        );
    }

    #[test]
    fn ply_ascii_quads_and_normals() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("Quad.PLY");
        std::fs::write(
            &p,
            "ply\r\nformat ascii 1.0\r\ncomment a unit square\r\nelement vertex 4\r\n\
             property float x\r\nproperty float y\r\nproperty float z\r\n\
             property float nx\r\nproperty float ny\r\nproperty float nz\r\n\
             element face 1\r\nproperty list uchar uint vertex_index\r\n\
             element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n\
             0 0 0 0 0 2\r\n1 0 0 0 0 2\r\n1 1 0 0 0 2\r\n0 1 0 0 0 2\r\n4 0 1 2 3\r\n0 1\r\n",
        )
        .unwrap();
        let m = load_mesh(&p).unwrap();
        assert_eq!(m.triangle_count(), 2);
        assert_eq!(m.indices, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(m.normals, vec![[0.0, 0.0, 1.0]; 4]);
        assert!((m.surface_area() - 1.0).abs() < 1e-9);
    }
}
