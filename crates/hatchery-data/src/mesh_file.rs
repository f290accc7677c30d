//! Triangle meshes from OBJ, PLY and STL files.

use std::io::Cursor;
use std::path::Path;

use ply_rs::parser::Parser;
use ply_rs::ply::{Property, PropertyAccess};

use crate::{DataError, MeshData};

const SUPPORTED: &str = ".obj, .ply, .stl";

/// Loads a mesh, choosing the format by the (case-insensitive) extension:
///
/// * `.obj`: all objects merged, polygons triangulated, normals used if every vertex has one.
/// * `.ply`: ASCII and binary (both endiannesses); polygons fan-triangulated; faces from a
///   `vertex_indices` or `vertex_index` list; normals from `nx`, `ny`, `nz` if present.
/// * `.stl`: ASCII and binary; identical positions are welded. STL only has face normals, so
///   vertex normals are computed.
///
/// Missing or degenerate normals are computed from the triangles (area-weighted). A file
/// without any triangle is an error.
pub fn load_mesh(path: &Path) -> Result<MeshData, DataError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let mesh = match extension.as_str() {
        "obj" => load_obj(path),
        "ply" => load_ply(path),
        "stl" => load_stl(path),
        _ => Err(DataError::unsupported(
            path,
            format!("unknown mesh file extension, supported are {SUPPORTED}"),
        )),
    }?;
    if mesh.triangle_count() == 0 {
        return Err(DataError::format(path, "the file contains no triangles"));
    }
    Ok(mesh)
}

fn load_obj(path: &Path) -> Result<MeshData, DataError> {
    let file = std::fs::File::open(path).map_err(|e| DataError::io(path, e))?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    // Materials are irrelevant here; do not go looking for .mtl files.
    let (models, _materials) =
        tobj::load_obj_buf(&mut std::io::BufReader::new(file), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|e| DataError::format(path, format!("invalid OBJ: {e}")))?;

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

fn load_stl(path: &Path) -> Result<MeshData, DataError> {
    let mut bytes = std::fs::read(path).map_err(|e| DataError::io(path, e))?;
    // Many binary STL writers start the 80-byte header with "solid", which stl_io takes for
    // ASCII. A file whose size is exactly that of a binary STL with the stated triangle count is
    // binary; hide the misleading word from stl_io.
    if bytes.len() >= 84 && bytes.starts_with(b"solid") {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        if bytes.len() as u64 == 84 + 50 * count {
            bytes[..5].copy_from_slice(b"SOLID");
        }
    }
    let stl = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| {
        let reason = if e.kind() == std::io::ErrorKind::UnexpectedEof {
            ENDS_EARLY.to_string()
        } else {
            e.to_string()
        };
        DataError::format(path, format!("invalid STL: {reason}"))
    })?;
    let positions = stl.vertices.iter().map(|v| v.0).collect();
    let mut indices = Vec::with_capacity(stl.faces.len() * 3);
    for face in &stl.faces {
        for &i in &face.vertices {
            indices
                .push(u32::try_from(i).map_err(|_| DataError::format(path, "too many vertices"))?);
        }
    }
    MeshData::new(positions, None, indices).map_err(|e| e.in_file(path))
}

fn load_ply(path: &Path) -> Result<MeshData, DataError> {
    let bytes = std::fs::read(path).map_err(|e| DataError::io(path, e))?;
    precheck_ply_header(path, &bytes)?;
    let file_len = bytes.len();
    let mut reader = Cursor::new(bytes);
    let ply_error = |what: &str, e: std::io::Error| {
        DataError::format(path, format!("invalid PLY {what}: {}", ply_message(&e)))
    };

    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| ply_error("header", e))?;
    for (name, element) in &header.elements {
        // Each element takes at least one byte, so larger counts are lies; and an element
        // without properties would make the parser loop `count` times reading nothing.
        if element.count > file_len || (element.count > 0 && element.properties.is_empty()) {
            return Err(DataError::format(
                path,
                format!(
                    "element '{name}' declares {} entries the file cannot hold",
                    element.count
                ),
            ));
        }
    }

    let mut vertices = None;
    let mut faces = None;
    // Elements must be read in header order; skip the ones we do not use.
    for (name, element) in &header.elements {
        match name.as_str() {
            "vertex" => {
                let has_normals = ["nx", "ny", "nz"]
                    .iter()
                    .all(|k| element.properties.contains_key(*k));
                let list = Parser::<PlyVertex>::new()
                    .read_payload_for_element(&mut reader, element, &header)
                    .map_err(|e| ply_error("vertex data", e))?;
                vertices = Some((list, has_normals));
            }
            "face" => {
                let list = Parser::<PlyFace>::new()
                    .read_payload_for_element(&mut reader, element, &header)
                    .map_err(|e| ply_error("face data", e))?;
                faces = Some(list);
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, element, &header)
                    .map_err(|e| ply_error(&format!("'{name}' data"), e))?;
            }
        }
    }
    let (vertices, has_normals) =
        vertices.ok_or_else(|| DataError::format(path, "no vertex element"))?;
    let faces = faces.ok_or_else(|| DataError::format(path, "no face element"))?;

    let positions = vertices.iter().map(|v| v.position).collect();
    let normals = has_normals.then(|| vertices.iter().map(|v| v.normal).collect());
    let mut indices = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let polygon = face
            .indices
            .iter()
            .map(|&i| u32::try_from(i))
            .collect::<Result<Vec<u32>, _>>()
            .map_err(|_| {
                DataError::format(path, format!("face {f} has a negative vertex index"))
            })?;
        // Fan triangulation: fine for the convex polygons PLY files hold in practice.
        for i in 1..polygon.len().saturating_sub(1) {
            indices.extend([polygon[0], polygon[i], polygon[i + 1]]);
        }
    }
    MeshData::new(positions, normals, indices).map_err(|e| e.in_file(path))
}

const ENDS_EARLY: &str = "file ends early (truncated?)";

/// ply-rs messages span several lines and end in Debug dumps of the inner error; keep the first
/// line, without its line number (counted from the start of each element, so misleading).
fn ply_message(e: &std::io::Error) -> String {
    let text = e.to_string();
    if e.kind() == std::io::ErrorKind::UnexpectedEof || text.contains("UnexpectedEof") {
        return ENDS_EARLY.to_string();
    }
    let first = text.lines().next().unwrap_or_default().trim();
    match first.split_once(": ") {
        Some((line, rest)) if line.starts_with("Line ") => rest.to_string(),
        _ => first.to_string(),
    }
}

/// ply-rs panics on integers in `element`/`format` lines that overflow u64; catch those first.
fn precheck_ply_header(path: &Path, bytes: &[u8]) -> Result<(), DataError> {
    for line in bytes.split(|&b| b == b'\n').take(10_000) {
        let line = String::from_utf8_lossy(line);
        let line = line.trim();
        if line.starts_with("end_header") {
            return Ok(());
        }
        if (line.starts_with("element") || line.starts_with("format"))
            && line
                .split(|c: char| !c.is_ascii_digit())
                .any(|digits| digits.len() > 18)
        {
            return Err(DataError::format(
                path,
                format!("number too large in PLY header line '{line}'"),
            ));
        }
    }
    Ok(())
}

/// Reads any scalar property as f64; lists give `None`.
fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Char(v) => v as f64,
        Property::UChar(v) => v as f64,
        Property::Short(v) => v as f64,
        Property::UShort(v) => v as f64,
        Property::Int(v) => v as f64,
        Property::UInt(v) => v as f64,
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        _ => return None,
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
    fn set_property(&mut self, name: String, property: Property) {
        let Some(v) = scalar(&property) else { return };
        let v = v as f32;
        match name.as_str() {
            "x" => self.position[0] = v,
            "y" => self.position[1] = v,
            "z" => self.position[2] = v,
            "nx" => self.normal[0] = v,
            "ny" => self.normal[1] = v,
            "nz" => self.normal[2] = v,
            _ => {}
        }
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
    fn set_property(&mut self, name: String, property: Property) {
        if (name == "vertex_indices" || name == "vertex_index")
            && let Some(list) = index_list(property)
        {
            self.indices = list;
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

#[cfg(test)]
mod tests {
    use super::*;

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
