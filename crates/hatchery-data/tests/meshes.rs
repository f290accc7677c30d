//! Mesh loading: the shared meshes and files written here from a known mesh.

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
