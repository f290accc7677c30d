//! Mesh loading: the shared meshes and files written here from a known mesh.
//!
//! Over 600 lines: one test file per capability (every mesh format, as other tools write it, and
//! every malformed case).

use std::path::{Path, PathBuf};

use glam::Vec3;
use hatchery_data::mesh_file::load_mesh;
use hatchery_data::{DataError, MeshData};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data")
        .join(rel)
}

fn assert_unit_normals(m: &MeshData) {
    assert_eq!(m.normals.len(), m.positions.len());
    for n in &m.normals {
        let len = Vec3::from_array(*n).length();
        assert!((len - 1.0).abs() < 1e-4, "normal length {len}");
    }
}

/// An octahedron: 6 vertices, 8 outward counter-clockwise triangles.
fn octahedron() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 2.0, 0.0],
        [0.0, -2.0, 0.0],
        [0.0, 0.0, 0.5],
        [0.0, 0.0, -0.5],
    ];
    let mut t = Vec::new();
    for (x, sx) in [(0u32, 1.0f32), (1, -1.0)] {
        for (y, sy) in [(2u32, 1.0f32), (3, -1.0)] {
            for (z, sz) in [(4u32, 1.0f32), (5, -1.0)] {
                // (x, y, z) is counter-clockwise seen from outside iff the octant has an even
                // number of negative axes.
                t.push(if sx * sy * sz > 0.0 {
                    [x, y, z]
                } else {
                    [x, z, y]
                });
            }
        }
    }
    (p, t)
}

/// Checks a loaded mesh against the octahedron: same triangle count and the same triangles
/// (as position triples, in winding order, up to rotation), whatever the vertex order.
fn assert_is_octahedron(m: &MeshData) {
    let (p, t) = octahedron();
    assert_eq!(m.triangle_count(), t.len());
    let key = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
        let rots = [[a, b, c], [b, c, a], [c, a, b]];
        let best = rots
            .iter()
            .min_by(|u, v| u[0].partial_cmp(&v[0]).unwrap())
            .unwrap();
        format!("{best:?}")
    };
    let mut want: Vec<String> = t
        .iter()
        .map(|t| key(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]))
        .collect();
    let mut got: Vec<String> = m
        .indices
        .chunks_exact(3)
        .map(|t| {
            key(
                m.positions[t[0] as usize],
                m.positions[t[1] as usize],
                m.positions[t[2] as usize],
            )
        })
        .collect();
    want.sort();
    got.sort();
    assert_eq!(got, want);
    assert_unit_normals(m);
    // Computed normals of a convex shape centred at the origin point outward.
    for (p, n) in m.positions.iter().zip(&m.normals) {
        assert!(Vec3::from_array(*p).dot(Vec3::from_array(*n)) > 0.0);
    }
    let area: f64 = 8.0
        * 0.5
        * Vec3::new(-1.0, 2.0, 0.0)
            .cross(Vec3::new(-1.0, 0.0, 0.5))
            .length() as f64;
    assert!((m.surface_area() - area).abs() < 1e-5);
}

#[test]
fn bunny_obj() {
    let m = load_mesh(&data("meshes/bunny.obj")).unwrap();
    assert_eq!(m.positions.len(), 1839);
    assert_eq!(m.triangle_count(), 3674);
    assert_unit_normals(&m);
    // First vertex of the file (tobj orders vertices by first use).
    assert!(m.positions.contains(&[1.301895, 0.122622, 2.550061]));
}

#[test]
fn airplane_ply() {
    // ASCII with CRLF line ends; all 2452 faces are triangles (checked with awk on the file).
    let m = load_mesh(&data("meshes/airplane.ply")).unwrap();
    assert_eq!(m.positions.len(), 1335);
    assert_eq!(m.triangle_count(), 2452);
    assert_eq!(m.positions[0], [896.994, 48.7601, 82.2656]);
    assert_eq!(&m.indices[..6], &[0, 1, 2, 0, 2, 3]);
    assert_unit_normals(&m);
}

#[test]
fn sphere_ply() {
    // Binary little-endian, 422 vertices and 840 triangular faces, no normals in the file.
    let m = load_mesh(&data("meshes/sphere.ply")).unwrap();
    assert_eq!(m.positions.len(), 422);
    assert_eq!(m.triangle_count(), 840);
    assert_unit_normals(&m);
    // A closed sphere: the computed normals are all radial, in or out depending on the file's
    // winding; check they agree with each other.
    let (lo, hi) = m.bounds().unwrap();
    let centre = (lo + hi) * 0.5;
    let outward = m
        .positions
        .iter()
        .zip(&m.normals)
        .filter(|(p, n)| {
            (Vec3::from_array(**p) - centre)
                .normalize()
                .dot(Vec3::from_array(**n))
                > 0.95
        })
        .count();
    eprintln!(
        "sphere.ply: {outward} of {} normals point outward",
        m.positions.len()
    );
    assert!(outward == m.positions.len() || outward == 0);
}

fn ply_binary(big_endian: bool) -> Vec<u8> {
    let (p, t) = octahedron();
    let mut out = format!(
        "ply\nformat {} 1.0\ncomment written by a test\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
         element face {}\nproperty list uchar int vertex_indices\nproperty int flags\nend_header\n",
        if big_endian {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        },
        p.len(),
        t.len() - 1,
    )
    .into_bytes();
    let f = |v: f32| {
        if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let i = |v: i32| {
        if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    for v in &p {
        for c in v {
            out.extend(f(*c));
        }
        out.push(200);
    }
    // The first two triangles share the edge (0, 2): write them as one quad to exercise the
    // fan triangulation ([0,2,4] + [0,5,2] = quad [0,5,2,4] fanned from 0 gives [0,5,2], [0,2,4]).
    assert_eq!((t[0], t[1]), ([0, 2, 4], [0, 5, 2]));
    out.push(4);
    for v in [0, 5, 2, 4] {
        out.extend(i(v));
    }
    out.extend(i(-1));
    for tri in &t[2..] {
        out.push(3);
        for &v in tri {
            out.extend(i(v as i32));
        }
        out.extend(i(0));
    }
    out
}

fn stl_binary(header_word: &[u8]) -> Vec<u8> {
    let (p, t) = octahedron();
    let mut out = vec![b' '; 80];
    out[..header_word.len()].copy_from_slice(header_word);
    out.extend((t.len() as u32).to_le_bytes());
    for tri in &t {
        out.extend([0u8; 12]); // zero normal: readers must not depend on it
        for &v in tri {
            for c in p[v as usize] {
                out.extend(c.to_le_bytes());
            }
        }
        out.extend([0u8; 2]);
    }
    out
}

fn stl_ascii() -> String {
    let (p, t) = octahedron();
    let mut s = String::from("solid octahedron\n");
    for tri in &t {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for &v in tri {
            let [x, y, z] = p[v as usize];
            s += &format!("      vertex {x:e} {y:e} {z:e}\n");
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid octahedron\n"
}

#[test]
fn written_files_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    assert_is_octahedron(&load_mesh(&write("le.ply", &ply_binary(false))).unwrap());
    assert_is_octahedron(&load_mesh(&write("be.PLY", &ply_binary(true))).unwrap());
    assert_is_octahedron(&load_mesh(&write("bin.stl", &stl_binary(b"binary"))).unwrap());
    // Binary STL whose header starts with "solid", as many exporters write it.
    assert_is_octahedron(
        &load_mesh(&write("solid.stl", &stl_binary(b"solid octahedron"))).unwrap(),
    );
    let m = load_mesh(&write("ascii.Stl", stl_ascii().as_bytes())).unwrap();
    assert_is_octahedron(&m);
    assert_eq!(m.positions.len(), 6, "STL vertices are welded");

    let (p, t) = octahedron();
    let mut obj = String::from("# octahedron\no first\n");
    for [x, y, z] in &p {
        obj += &format!("v {x} {y} {z}\n");
    }
    for tri in &t[..4] {
        obj += &format!("f {} {} {}\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    // A second object using negative (relative) indices, merged into one mesh.
    obj += "o second\n";
    for tri in &t[4..] {
        obj += &format!(
            "f {} {} {}\n",
            tri[0] as i32 - 6,
            tri[1] as i32 - 6,
            tri[2] as i32 - 6
        );
    }
    assert_is_octahedron(&load_mesh(&write("octa.obj", obj.as_bytes())).unwrap());
}

#[test]
fn obj_with_normals_uses_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tri.OBJ");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 3\nf 1//1 2//1 3//1\nf 2//1 4//1 3//1\n",
    )
    .unwrap();
    let m = load_mesh(&path).unwrap();
    assert_eq!(m.triangle_count(), 2);
    assert_eq!(m.normals, vec![[0.0, 0.0, 1.0]; m.positions.len()]);
}

fn assert_error_names(path: &Path) -> DataError {
    let e = load_mesh(path).unwrap_err();
    let msg = e.to_string();
    let name = path.file_name().unwrap().to_string_lossy();
    assert!(msg.contains(&*name), "message does not name {name}: {msg}");
    assert!(!msg.contains('\n'), "multi-line message: {msg}");
    eprintln!("{msg}");
    e
}

#[test]
fn bad_files_are_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    // Deterministic garbage.
    let mut state = 12345u32;
    let garbage: Vec<u8> = (0..4096)
        .map(|_| {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
            (state >> 16) as u8
        })
        .collect();
    for ext in ["obj", "ply", "stl"] {
        let e = assert_error_names(&dir.path().join(format!("missing.{ext}")));
        assert!(matches!(e, DataError::Io { .. }));
        let path = dir.path().join(format!("garbage.{ext}"));
        std::fs::write(&path, &garbage).unwrap();
        assert_error_names(&path);
        let path = dir.path().join(format!("empty.{ext}"));
        std::fs::write(&path, b"").unwrap();
        assert_error_names(&path);
    }

    let write = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    // Out-of-range and negative indices.
    assert_error_names(&write("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
               0 0 0\n1 0 0\n0 1 0\n3 0 1 ";
    assert_error_names(&write("range.ply", format!("{ply}3\n").as_bytes()));
    assert_error_names(&write("negative.ply", format!("{ply}-1\n").as_bytes()));
    // Truncated binary files.
    let bytes = ply_binary(false);
    assert_error_names(&write("short.ply", &bytes[..bytes.len() - 10]));
    let bytes = stl_binary(b"binary");
    assert_error_names(&write("short.stl", &bytes[..bytes.len() - 10]));
    // Vertices only: nothing to draw.
    assert_error_names(&write("points.obj", b"v 0 0 0\nv 1 0 0\n"));
    // Non-finite position.
    assert_error_names(&write("nan.obj", b"v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n"));
}

// ---------------------------------------------------------------------------------------------
// Tolerance: every variant that common writers produce and common readers (trimesh, VTK,
// MeshLab) take must load whole; what cannot be read whole must be an error.

fn case(name: &str) -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/cases"
    ))
    .join(name)
}

#[test]
fn stl_with_two_solids_loads_both() {
    let m = load_mesh(&case("two_bodies.stl")).unwrap();
    assert_eq!(m.positions.len(), 8, "distinct vertices");
    assert_eq!(m.triangle_count(), 8);
    let (lo, hi) = m.bounds().unwrap();
    assert_eq!((lo.x, hi.x), (0.0, 3.0));
    assert_unit_normals(&m);
}

#[test]
fn stl_with_bare_solid_line_loads() {
    let m = load_mesh(&case("solid_no_name.stl")).unwrap();
    assert_eq!(m.positions.len(), 4, "distinct vertices");
    assert_eq!(m.triangle_count(), 2);
    assert_eq!(m.bounds().unwrap(), (Vec3::ZERO, Vec3::ONE));
}

#[test]
fn stl_with_upper_case_keywords_loads() {
    let m = load_mesh(&case("uppercase_keywords.stl")).unwrap();
    assert_eq!(m.positions.len(), 4, "distinct vertices");
    assert_eq!(m.triangle_count(), 2);
}

/// Writes `bytes` to the file `name` in `dir` and loads it.
fn load_written(dir: &Path, name: &str, bytes: &[u8]) -> Result<MeshData, DataError> {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    load_mesh(&path)
}

#[test]
fn ascii_stl_variants_load_whole() {
    let dir = tempfile::tempdir().unwrap();
    let plain = stl_ascii();
    // Split after the fourth facet into a second solid.
    let (first, rest) = plain.split_at(plain.match_indices("endfacet\n").nth(3).unwrap().0 + 9);
    let variants: Vec<(&str, String)> = vec![
        ("upper case", plain.to_uppercase()),
        (
            "mixed case",
            plain
                .replace("facet normal", "Facet Normal")
                .replace("outer", "OUTER")
                .replace("vertex", "Vertex")
                .replace("solid", "Solid"),
        ),
        ("tabs", plain.replace("  ", "\t").replace(' ', " \t ")),
        ("CRLF", plain.replace('\n', "\r\n")),
        ("CR", plain.replace('\n', "\r")),
        (
            "blank lines",
            plain
                .replace("endfacet\n", "endfacet\n\n  \t\n")
                .replace("outer loop\n", "outer loop\n\r\n"),
        ),
        (
            "bare solid and endsolid",
            plain
                .replace("solid octahedron", "solid")
                .replace("endsolid\n", "endsolid"),
        ),
        (
            "endsolid without name",
            plain.replace("endsolid octahedron", "endsolid"),
        ),
        ("no final line end", plain.trim_end().to_string()),
        (
            "no final endsolid",
            plain.replace("endsolid octahedron\n", ""),
        ),
        (
            "two solids",
            format!("{first}endsolid octahedron\nsolid other half\n{rest}"),
        ),
        (
            "name glued to solid, BOM, leading blank line",
            format!("\u{feff}\n{}", plain.replacen("solid ", "solid_", 1)),
        ),
        (
            "name glued to solid and to endsolid",
            plain.replace("solid octahedron", "solidoctahedron"),
        ),
        (
            // Compact, so that the NULs start within the first KiB, where binary is sniffed.
            "NUL padding after the text",
            {
                let (first_line, body) = plain.split_once('\n').unwrap();
                let body = body.split_whitespace().collect::<Vec<_>>().join(" ");
                format!("{first_line}\n{body}\n{}", "\0".repeat(300))
            },
        ),
        (
            "one facet per line",
            plain
                .replace("\n    ", " ")
                .replace("\n      ", " ")
                .replace("\n  endfacet", " endfacet"),
        ),
        (
            "nan face normals",
            plain.replace("normal 0 0 0", "normal -nan nan 1.#QNAN"),
        ),
    ];
    for (i, (what, text)) in variants.iter().enumerate() {
        let m = load_written(dir.path(), &format!("v{i}.stl"), text.as_bytes())
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_is_octahedron(&m);
        assert_eq!(m.positions.len(), 6, "{what}: vertices welded");
    }
}

#[test]
fn stl_welds_negative_zero_and_fans_polygon_loops() {
    let dir = tempfile::tempdir().unwrap();
    // Facets on one line (the solid's name is the rest of its line); -0 and 0 are the same
    // position.
    let text = "solid t\nfacet normal 0 0 -1 outer loop vertex 0 0 0 vertex 0 1 0 vertex 1 0 0 \
                endloop endfacet facet normal 0 -1 0 outer loop vertex -0 -0 -0 vertex 1 0 -0 \
                vertex 0 -0 1 endloop endfacet endsolid t";
    let m = load_written(dir.path(), "zeros.stl", text.as_bytes()).unwrap();
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.triangle_count(), 2);
    // A loop of four vertices (some old writers) is two triangles.
    let text = "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n";
    let m = load_written(dir.path(), "quad.stl", text.as_bytes()).unwrap();
    assert_eq!((m.positions.len(), m.triangle_count()), (4, 2));
    assert!((m.surface_area() - 1.0).abs() < 1e-9);
}

#[test]
fn binary_stl_variants() {
    let dir = tempfile::tempdir().unwrap();
    let load = |name: &str, bytes: &[u8]| load_written(dir.path(), name, bytes);
    let with_count = |word: &[u8], count: u32| {
        let mut b = stl_binary(word);
        b[80..84].copy_from_slice(&count.to_le_bytes());
        b
    };
    // A count of 0 or too small (streaming writers) is overridden by the data, as VTK does;
    // also with a header starting with "solid", which is not then taken for ASCII.
    assert_is_octahedron(&load("zero.stl", &with_count(b"binary", 0)).unwrap());
    assert_is_octahedron(&load("five.stl", &with_count(b"solid made by x", 5)).unwrap());
    assert_is_octahedron(&load("SOLID.stl", &with_count(b"SOLID", 0)).unwrap());
    // Bytes after the last triangle too few to be another one.
    let mut padded = stl_binary(b"solid x");
    padded.extend([0u8; 10]);
    assert_is_octahedron(&load("padded.stl", &padded).unwrap());
    // More triangles declared than present: truncated.
    let e = load("more.stl", &with_count(b"binary", 9))
        .unwrap_err()
        .to_string();
    assert!(e.contains("more.stl") && e.contains("9 triangles"), "{e}");
    // A count that fits neither the data nor a whole number of triangles.
    let mut odd = with_count(b"binary", 5);
    odd.extend([1u8; 10]);
    let e = load("odd.stl", &odd).unwrap_err().to_string();
    assert!(e.contains("odd.stl") && e.contains("5 triangles"), "{e}");
}

#[test]
fn bad_ascii_stl_is_an_error_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let plain = stl_ascii();
    let cases = [
        ("cut.stl", plain[..plain.len() / 2].to_string(), "truncated"),
        (
            "cut2.stl",
            plain[..plain.len() / 2 + 3].to_string(),
            "truncated",
        ),
        (
            "word.stl",
            plain.replacen("vertex 1e0", "vertex one", 1),
            "line 4: expected a finite vertex coordinate, found 'one'",
        ),
        (
            "after.stl",
            plain.clone() + "extra words\n",
            "line 59: expected 'solid', found 'extra'",
        ),
        (
            "keyword.stl",
            plain.replacen("outer loop", "outer lop", 1),
            "line 3: expected 'loop'",
        ),
        (
            "two.stl",
            plain.replacen("      vertex 0e0 2e0 0e0\n", "", 1),
            "line 2: facet has 2 vertices",
        ),
    ];
    for (name, text, want) in cases {
        let msg = load_written(dir.path(), name, text.as_bytes())
            .unwrap_err()
            .to_string();
        eprintln!("{msg}");
        assert!(msg.contains(name) && msg.contains(want), "{msg}");
    }
}

#[test]
fn obj_with_comments_blank_lines_and_continuations() {
    let dir = tempfile::tempdir().unwrap();
    let (p, t) = octahedron();
    let mut obj = b"# octahedron\r\n\r\nmtllib materials.mtl # not there\r\nusemtl\r\n".to_vec();
    obj.extend(b"# caf\xe9 (Latin-1, not UTF-8)\r\no first # object name\r\n");
    for (i, [x, y, z]) in p.iter().enumerate() {
        let line = match i {
            0 => format!("v {x} {y} {z} # note"),
            1 => format!("  v {x} {y} {z}#glued note"),
            2 => format!("v {x} \\\r\n   {y} {z}"),
            _ => format!("\tv\t{x}\t{y}\t{z}\t"),
        };
        obj.extend(line.as_bytes());
        obj.extend(b"\r\n\r\n   \r\n");
    }
    for (i, tri) in t.iter().enumerate() {
        let [a, b, c] = tri.map(|v| v + 1);
        obj.extend(format!("f {a} {b} {c} # face {i}\n").as_bytes());
        obj.extend(b"# a comment between faces\n\n");
    }
    obj.extend(b"# last line, no line end");
    let m = load_written(dir.path(), "comments.obj", &obj).unwrap();
    assert_is_octahedron(&m);
    assert_eq!(m.positions.len(), 6);
}

#[test]
fn bad_obj_line_is_named() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text, line) in [
        ("word.obj", "v 0 0 0\nv 1 0 0\n# x\nv 0 one 0\nf 1 2 3\n", 4),
        ("cont.obj", "v 0 0 \\\n 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 5),
        (
            "range.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\nf 1 2 7\n",
            6,
        ),
        (
            "zero.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 0 1 2\n",
            5,
        ),
        ("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", 3),
        (
            "normal.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n",
            5,
        ),
    ] {
        let msg = load_written(dir.path(), name, text.as_bytes())
            .unwrap_err()
            .to_string();
        eprintln!("{msg}");
        assert!(
            msg.contains(name) && msg.contains(&format!("line {line}:")),
            "{msg}"
        );
    }
}

/// The octahedron as ASCII PLY in an untidy but valid layout: blank lines, indented lines,
/// comments and obj_info anywhere in the header; entries split over lines and run together;
/// numbers like `1.` and `.5`.
fn ply_ascii_untidy() -> String {
    let (p, t) = octahedron();
    let mut s = String::from(
        "ply\n\ncomment before the format\n  format   ascii  1.0  \n\
         obj_info\tmade by hand\nelement vertex 6\ncomment between element and property\n\
         property float x\n\nproperty float y\nobj_info between properties\n\
         property float z\n   comment indented\nelement face 8\n\
         property list uchar int vertex_indices\ncomment just before the end\nend_header\n\n",
    );
    for (i, [x, y, z]) in p.iter().enumerate() {
        let [x, y, z] = [x, y, z].map(|v| match *v {
            1.0 => "1.".to_string(),
            0.5 => ".5".to_string(),
            -0.5 => "-.5e0".to_string(),
            v => format!("{v}"),
        });
        s += &match i {
            0 => format!("{x} {y}\n{z}\n\n"),
            1 | 2 => format!("{x} {y} {z} "),
            _ => format!("\t{x}\t{y}\t{z}\r\n"),
        };
    }
    for (i, [a, b, c]) in t.iter().enumerate() {
        s += &if i == 3 {
            format!("3\n{a}\n{b} {c}\n\n")
        } else {
            format!("3 {a} {b} {c}\n")
        };
    }
    s + "\n\n"
}

#[test]
fn ply_untidy_ascii_loads_whole() {
    let dir = tempfile::tempdir().unwrap();
    let text = ply_ascii_untidy();
    assert_is_octahedron(&load_written(dir.path(), "untidy.ply", text.as_bytes()).unwrap());
    let crlf = text.replace('\n', "\r\n");
    assert_is_octahedron(&load_written(dir.path(), "crlf.ply", crlf.as_bytes()).unwrap());
    // Integer properties written as floats (trimesh reads them so).
    let floats = text.replace("3 0 2 4", "3.0 0.0 2 4.0");
    assert_is_octahedron(&load_written(dir.path(), "floats.ply", floats.as_bytes()).unwrap());
}

#[test]
fn ply_binary_with_untidy_header_loads_whole() {
    let dir = tempfile::tempdir().unwrap();
    for big_endian in [false, true] {
        let bytes = ply_binary(big_endian);
        let end = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap();
        let header = String::from_utf8(bytes[..end].to_vec()).unwrap();
        let mut untidy = b"ply\r\n\r\ncomment caf\xe9 (Latin-1)\r\n".to_vec();
        let header = header
            .strip_prefix("ply\n")
            .unwrap()
            .replace("element face", "obj_info x\n\n  element   face")
            .replace('\n', "\r\n");
        untidy.extend(header.as_bytes());
        untidy.extend(b"comment last\r\nend_header\r\n");
        untidy.extend(&bytes[end + 11..]);
        let m = load_written(dir.path(), "untidy.ply", &untidy).unwrap();
        assert_is_octahedron(&m);
    }
}

#[test]
fn bad_ply_is_an_error_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let text = ply_ascii_untidy();
    let cases = [
        (
            "extra.ply",
            text.clone() + "1 2 3\n",
            "data after the last element",
        ),
        (
            "word.ply",
            text.replacen("3 0 2 4", "3 0 two 4", 1),
            "line 25: expected int for property 'vertex_indices' of element 'face', found 'two'",
        ),
        ("cut.ply", text[..text.len() - 30].to_string(), "truncated"),
        (
            "header.ply",
            text.replacen("element face", "elemnt face", 1),
            "line 14: invalid PLY header line 'elemnt face 8'",
        ),
        (
            "twice.ply",
            text.replacen("property float y", "property float x", 1),
            "line 10:",
        ),
        (
            "noz.ply",
            text.replacen("property float z", "property float w", 1),
            "no scalar property 'z'",
        ),
        (
            "noend.ply",
            text.replacen("end_header", "", 1),
            "no 'end_header'",
        ),
    ];
    for (name, text, want) in cases {
        let msg = load_written(dir.path(), name, text.as_bytes())
            .unwrap_err()
            .to_string();
        eprintln!("{msg}");
        assert!(msg.contains(name) && msg.contains(want), "{msg}");
        assert!(!msg.contains('\n'), "{msg}");
    }
    // Binary data longer than the header says.
    let mut bytes = ply_binary(false);
    bytes.extend([7u8; 13]);
    let msg = load_written(dir.path(), "long.ply", &bytes)
        .unwrap_err()
        .to_string();
    assert!(msg.contains("13 bytes of data after"), "{msg}");
}

#[test]
fn mangled_files_are_errors_or_meshes_never_panics() {
    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::new();
    let (p, t) = octahedron();
    for [x, y, z] in &p {
        obj += &format!("v {x} {y} {z} # c\n");
    }
    for tri in &t {
        obj += &format!("f {}//1 {} {}\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    let bases: [(&str, Vec<u8>); 6] = [
        ("stl", stl_ascii().into_bytes()),
        ("stl", stl_binary(b"solid x")),
        ("ply", ply_ascii_untidy().into_bytes()),
        ("ply", ply_binary(false)),
        ("ply", ply_binary(true)),
        ("obj", format!("vn 0 0 1\n{obj}").into_bytes()),
    ];
    let mut state = 7u32;
    let mut random = |n: usize| {
        state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
        (state >> 8) as usize % n.max(1)
    };
    let (mut loaded, mut refused) = (0, 0);
    for (b, (ext, base)) in bases.iter().enumerate() {
        for i in 0..150 {
            let mut bytes = base.clone();
            match i % 3 {
                0 => bytes.truncate(random(bytes.len())),
                1 => {
                    let at = random(bytes.len());
                    bytes[at] = random(256) as u8;
                }
                _ => {
                    let at = random(bytes.len());
                    let choices = b" \n0-9e.#\x00\xff";
                    let byte = choices[random(choices.len())];
                    bytes.insert(at, byte);
                }
            }
            match load_written(dir.path(), &format!("m{b}_{i}.{ext}"), &bytes) {
                Ok(m) => {
                    assert!(m.triangle_count() > 0);
                    loaded += 1;
                }
                Err(e) => {
                    let msg = e.to_string();
                    assert!(msg.contains(&format!("m{b}_{i}.{ext}")) && !msg.contains('\n'));
                    refused += 1;
                }
            }
        }
    }
    eprintln!("mangled files: {loaded} loaded, {refused} refused");
}
