//! Marching cubes (Lorensen & Cline 1987): the iso-surface of a volume as an indexed mesh.
//!
//! * Cube corners `c` in 0..8 sit at offset `(c & 1, c >> 1 & 1, c >> 2 & 1)`; a corner is
//!   "inside" when its value is greater than the iso value.
//! * The 256-case triangle table is derived at first use from the cube's face configurations
//!   (see `build_triangle_table`) instead of being typed in. On the ambiguous faces (two
//!   diagonal inside corners) the inside corners are always kept apart; the choice only depends
//!   on the face itself, so the two cells sharing a face cut it identically and the surface is
//!   closed wherever it does not leave the grid.
//! * A vertex is made once per crossed grid edge, in slabs of z-layers processed in parallel;
//!   neighbouring slabs share the vertices of their common plane, so the mesh is fully welded.
//! * Normals are `-gradient`: they point toward lower values, i.e. out of high-valued blobs.
//!   Triangles are counter-clockwise seen from the side their normal points to.
//! * Where a grid value equals the iso value exactly, several vertices land on that grid point;
//!   the zero-area triangles between them are dropped (the surface stays geometrically closed).
//! * Non-finite values are "no data": cells touching one make no triangles and edges to one no
//!   vertex, so no wall grows along a no-data border.
//! * Positions and normals are in world space (the volume's voxel → world transform); a
//!   mirroring transform reverses the triangles so they stay counter-clockwise.

use std::sync::LazyLock;
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::UVec3;
use rayon::prelude::*;

use crate::{MeshData, VolumeData};

/// Extracts the surface `value == iso` of `volume`, in world coordinates. An iso value outside
/// the volume's value range gives an empty mesh.
pub fn marching_cubes(volume: &VolumeData, iso: f32) -> MeshData {
    marching_cubes_with_progress(volume, iso, &|_| {})
}

/// As [`marching_cubes`], calling `progress` with the finished fraction (0..=1) after each slab.
/// Slabs finish on several threads, so consecutive calls may rarely arrive slightly out of order.
pub fn marching_cubes_with_progress(
    volume: &VolumeData,
    iso: f32,
    progress: &(dyn Fn(f32) + Sync),
) -> MeshData {
    let [min, max] = volume.value_range;
    // Written so that a NaN iso also lands here.
    if !(iso >= min && iso < max) {
        progress(1.0);
        return MeshData::default();
    }

    let cell_layers = volume.dims[2] - 1;
    // Thin enough slabs for load balancing and progress, thick enough that recomputing the shared
    // plane of each slab stays cheap.
    let layers_per_slab = cell_layers.div_ceil(64).max(4);
    let slab_count = cell_layers.div_ceil(layers_per_slab);
    let done = AtomicUsize::new(0);
    let slabs: Vec<Slab> = (0..slab_count)
        .into_par_iter()
        .map(|s| {
            let z0 = s * layers_per_slab;
            let z1 = (z0 + layers_per_slab).min(cell_layers);
            let slab = march_slab(volume, iso, z0, z1);
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            progress(finished as f32 / slab_count as f32);
            slab
        })
        .collect();

    let mut mesh = weld_slabs(slabs);
    if volume.has_no_data() {
        // Edges between valid voxels whose every cell touches no data made vertices no
        // triangle uses.
        drop_unused_vertices(&mut mesh);
    }
    if volume.geometry.direction.determinant() < 0.0 {
        for triangle in mesh.indices.chunks_exact_mut(3) {
            triangle.swap(1, 2);
        }
    }
    repair_zero_normals(&mut mesh);
    mesh
}

/// The vertices and triangles of one slab. Its vertices are ordered so that those on the
/// bottom plane come first and those on the top plane last, in the same scan order; the bottom
/// block of slab `s + 1` is therefore exactly the top block of slab `s`.
struct Slab {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// Slab-local vertex indices.
    indices: Vec<u32>,
    bottom_count: usize,
    top_start: usize,
}

const NONE: u32 = u32::MAX;

/// Vertex ids of the x- and y-edges of one z-plane, indexed by `x + nx * y`.
struct PlaneEdges {
    x: Vec<u32>,
    y: Vec<u32>,
}

fn march_slab(volume: &VolumeData, iso: f32, z0: u32, z1: u32) -> Slab {
    let [nx, ny, _] = volume.dims;
    let plane_len = nx as usize * ny as usize;
    let at = |x: u32, y: u32| x as usize + nx as usize * y as usize;
    let mut out = Slab {
        positions: Vec::new(),
        normals: Vec::new(),
        indices: Vec::new(),
        bottom_count: 0,
        top_start: 0,
    };
    let mut lower = PlaneEdges {
        x: vec![NONE; plane_len],
        y: vec![NONE; plane_len],
    };
    let mut upper = PlaneEdges {
        x: vec![NONE; plane_len],
        y: vec![NONE; plane_len],
    };
    let mut vertical = vec![NONE; plane_len];

    plane_vertices(volume, iso, z0, &mut lower, &mut out);
    out.bottom_count = out.positions.len();
    let table = &*TRIANGLE_TABLE;
    for z in z0..z1 {
        for y in 0..ny {
            for x in 0..nx {
                vertical[at(x, y)] = edge_vertex(volume, iso, UVec3::new(x, y, z), 2, &mut out);
            }
        }
        if z + 1 == z1 {
            out.top_start = out.positions.len();
        }
        plane_vertices(volume, iso, z + 1, &mut upper, &mut out);

        for y in 0..ny - 1 {
            for x in 0..nx - 1 {
                let mut case = 0usize;
                let mut no_data = false;
                for c in 0..8 {
                    let v = volume.value(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2));
                    no_data |= !v.is_finite();
                    if v > iso {
                        case |= 1 << c;
                    }
                }
                if no_data {
                    continue;
                }
                let edges = &table[case];
                for triangle in edges.chunks_exact(3).take_while(|t| t[0] >= 0) {
                    let ids = [0, 1, 2].map(|k| {
                        let (axis, bits) = (triangle[k] / 4, triangle[k] as u32 % 4);
                        let (b0, b1) = (bits & 1, bits >> 1);
                        match axis {
                            0 => [&lower, &upper][b1 as usize].x[at(x, y + b0)],
                            1 => [&lower, &upper][b1 as usize].y[at(x + b0, y)],
                            _ => vertical[at(x + b0, y + b1)],
                        }
                    });
                    debug_assert!(!ids.contains(&NONE), "table edge without a crossing");
                    // A grid value exactly at iso puts the vertices of all its edges on the grid
                    // point; the triangles between them have no area and no orientation.
                    let [a, b, c] = ids.map(|i| out.positions[i as usize]);
                    if a != b && b != c && c != a {
                        out.indices.extend(ids);
                    }
                }
            }
        }
        std::mem::swap(&mut lower, &mut upper);
    }
    out
}

/// Makes the vertices on the crossed x- and y-edges of plane `z`, scanning y then x.
fn plane_vertices(volume: &VolumeData, iso: f32, z: u32, edges: &mut PlaneEdges, out: &mut Slab) {
    let [nx, ny, _] = volume.dims;
    for y in 0..ny {
        for x in 0..nx {
            let i = x as usize + nx as usize * y as usize;
            let p = UVec3::new(x, y, z);
            edges.x[i] = if x + 1 < nx {
                edge_vertex(volume, iso, p, 0, out)
            } else {
                NONE
            };
            edges.y[i] = if y + 1 < ny {
                edge_vertex(volume, iso, p, 1, out)
            } else {
                NONE
            };
        }
    }
}

/// The vertex where the surface crosses the grid edge from `p` one voxel along `axis`, or
/// `NONE` if it does not cross.
fn edge_vertex(volume: &VolumeData, iso: f32, p: UVec3, axis: usize, out: &mut Slab) -> u32 {
    let mut q = p;
    q[axis] += 1;
    if q[axis] >= volume.dims[axis] {
        return NONE;
    }
    let a = volume.value(p.x, p.y, p.z);
    let b = volume.value(q.x, q.y, q.z);
    if !a.is_finite() || !b.is_finite() || (a > iso) == (b > iso) {
        return NONE;
    }
    // a != b here because exactly one of them is above iso.
    let t = ((iso - a) / (b - a)).clamp(0.0, 1.0);
    let mut voxel = p.as_vec3();
    voxel[axis] += t;
    let normal = -volume.gradient(voxel).normalize_or_zero();
    out.positions.push(volume.voxel_to_world(voxel).to_array());
    out.normals.push(normal.to_array());
    (out.positions.len() - 1) as u32
}

/// Concatenates the slabs, dropping each slab's bottom plane vertices in favour of the identical
/// top plane vertices of the slab below.
fn weld_slabs(slabs: Vec<Slab>) -> MeshData {
    let mut mesh = MeshData::default();
    let mut previous_top = 0usize;
    for (s, slab) in slabs.into_iter().enumerate() {
        let base = mesh.positions.len();
        let skip = if s == 0 { 0 } else { slab.bottom_count };
        let top = base + slab.top_start - skip;
        mesh.positions.extend_from_slice(&slab.positions[skip..]);
        mesh.normals.extend_from_slice(&slab.normals[skip..]);
        mesh.indices.extend(slab.indices.iter().map(|&i| {
            let i = i as usize;
            (if i < skip {
                previous_top + i
            } else {
                base + i - skip
            }) as u32
        }));
        previous_top = top;
    }
    mesh
}

/// A vanishing gradient (flat region exactly at the iso value) gives no normal; use the
/// geometry there so every normal is unit length.
fn drop_unused_vertices(mesh: &mut MeshData) {
    let mut new_index = vec![NONE; mesh.positions.len()];
    let mut kept = 0u32;
    for &i in &mesh.indices {
        if new_index[i as usize] == NONE {
            new_index[i as usize] = kept;
            kept += 1;
        }
    }
    let mut positions = vec![[0.0; 3]; kept as usize];
    let mut normals = vec![[0.0; 3]; kept as usize];
    for (old, &new) in new_index.iter().enumerate() {
        if new != NONE {
            positions[new as usize] = mesh.positions[old];
            normals[new as usize] = mesh.normals[old];
        }
    }
    for i in &mut mesh.indices {
        *i = new_index[*i as usize];
    }
    mesh.positions = positions;
    mesh.normals = normals;
}

fn repair_zero_normals(mesh: &mut MeshData) {
    if mesh.normals.iter().all(|n| *n != [0.0; 3]) {
        return;
    }
    let mut geometric = mesh.clone();
    geometric.compute_vertex_normals();
    for (n, g) in mesh.normals.iter_mut().zip(geometric.normals) {
        if *n == [0.0; 3] {
            *n = g;
        }
    }
}

/// Cube edges: `4 * axis + k`, where bit 0 of `k` is the corner offset along the lower of the
/// two other axes and bit 1 the offset along the higher one. Returns the edge joining corners
/// `a` and `b`, which must differ in exactly one bit.
fn edge_between(a: usize, b: usize) -> usize {
    let axis = (a ^ b).trailing_zeros() as usize;
    let others: Vec<usize> = (0..3).filter(|&x| x != axis).collect();
    let k = (a >> others[0] & 1) | (a >> others[1] & 1) << 1;
    4 * axis + k
}

/// Up to 5 triangles per case as cube edge triples, terminated by -1, as in the classic tables.
type TriangleTable = [[i8; 16]; 256];

static TRIANGLE_TABLE: LazyLock<TriangleTable> = LazyLock::new(build_triangle_table);

/// Derives the triangles of every corner configuration.
///
/// On each cube face, walk its corners counter-clockwise seen from outside the cube. The walk
/// crosses the surface on the face's cut edges, alternately entering and leaving the inside
/// corners. Joining each entry to the following exit cuts the inside corners off separately
/// (which also settles the ambiguous faces), and the resulting segment runs so that, seen from
/// the outside region (lower values), the surface patch in the cube is on its left. Each cut
/// edge is entered on one of its two faces and left on the other, so the segments chain into
/// closed, consistently oriented loops, which are fan-triangulated: counter-clockwise seen
/// from the low side, where the normals point.
fn build_triangle_table() -> TriangleTable {
    let mut table = [[-1i8; 16]; 256];
    for (case, row) in table.iter_mut().enumerate() {
        let inside = |c: usize| case >> c & 1 == 1;
        let mut next = [usize::MAX; 12];
        for axis in 0..3 {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for side in 0..2 {
                // (u, v) = (0,0), (1,0), (1,1), (0,1) is counter-clockwise around +axis.
                let mut quad = [(0, 0), (1, 0), (1, 1), (0, 1)];
                if side == 0 {
                    quad.reverse();
                }
                let corners = quad.map(|(a, b)| side << axis | a << u | b << v);
                // (edge, entering) for each cut edge, in walk order.
                let cuts: Vec<(usize, bool)> = (0..4)
                    .filter_map(|i| {
                        let (a, b) = (corners[i], corners[(i + 1) % 4]);
                        (inside(a) != inside(b)).then(|| (edge_between(a, b), inside(b)))
                    })
                    .collect();
                for (j, &(edge, entering)) in cuts.iter().enumerate() {
                    if entering {
                        next[edge] = cuts[(j + 1) % cuts.len()].0;
                    }
                }
            }
        }
        let mut written = 0;
        let mut visited = [false; 12];
        for start in 0..12 {
            if next[start] == usize::MAX || visited[start] {
                continue;
            }
            let mut ring = Vec::new();
            let mut e = start;
            while !visited[e] {
                visited[e] = true;
                ring.push(e);
                e = next[e];
            }
            for i in 1..ring.len() - 1 {
                for e in [ring[0], ring[i], ring[i + 1]] {
                    row[written] = e as i8;
                    written += 1;
                }
            }
        }
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::collections::HashMap;

    /// The two corners of an edge, the one at offset 0 along its axis first.
    fn edge_corners(edge: usize) -> (usize, usize) {
        let (axis, k) = (edge / 4, edge % 4);
        let others: Vec<usize> = (0..3).filter(|&a| a != axis).collect();
        let c0 = (k & 1) << others[0] | (k >> 1) << others[1];
        (c0, c0 | 1 << axis)
    }

    #[test]
    fn edge_numbering_round_trips() {
        for e in 0..12 {
            let (a, b) = edge_corners(e);
            assert_eq!(edge_between(a, b), e);
            assert_eq!(edge_between(b, a), e);
            assert_eq!((a ^ b).count_ones(), 1);
        }
    }

    #[test]
    fn table_is_well_formed() {
        let table = &*TRIANGLE_TABLE;
        assert!(table[0][0] == -1 && table[255][0] == -1);
        let mut triangle_total = 0;
        for (case, row) in table.iter().enumerate() {
            let n = row.iter().take_while(|&&e| e >= 0).count();
            assert_eq!(n % 3, 0, "case {case}");
            assert!(n <= 15, "case {case} needs {n} entries");
            triangle_total += n / 3;
            // Exactly the cut edges are used, each one at least once.
            let cut = |e: usize| {
                let (a, b) = edge_corners(e);
                (case >> a & 1) != (case >> b & 1)
            };
            for e in 0..12 {
                let used = row[..n].contains(&(e as i8));
                assert_eq!(used, cut(e), "case {case} edge {e}");
            }
            // Each loop is closed: inside one cube, every triangle side between two cube faces'
            // cut points is used once; interior diagonals twice in opposite directions.
            let mut sides: HashMap<(i8, i8), i32> = HashMap::new();
            for t in row[..n].chunks(3) {
                for k in 0..3 {
                    *sides.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
                }
            }
            for (&(a, b), &count) in &sides {
                assert_eq!(count, 1, "case {case}: side {a}->{b} used {count} times");
            }
        }
        // The total depends on how ambiguous faces are resolved; recorded to catch changes.
        assert_eq!(triangle_total, 820);
    }

    #[test]
    fn single_corner_case_faces_away_from_the_inside_corner() {
        // Only corner 0 inside: one triangle whose normal points away from (0,0,0).
        let row = TRIANGLE_TABLE[1];
        assert_eq!(row[3], -1);
        let mid = |e: i8| {
            let (a, b) = edge_corners(e as usize);
            let p = |c: usize| Vec3::new((c & 1) as f32, (c >> 1 & 1) as f32, (c >> 2) as f32);
            (p(a) + p(b)) * 0.5
        };
        let [a, b, c] = [mid(row[0]), mid(row[1]), mid(row[2])];
        assert!((b - a).cross(c - a).dot(Vec3::ONE) > 0.0);
    }

    #[test]
    fn iso_outside_range_gives_empty_mesh() {
        let v = crate::procedural::sphere(8, 0.5).unwrap();
        let calls = AtomicUsize::new(0);
        for iso in [10.0, v.value_range[1], -10.0, f32::NAN] {
            let m = marching_cubes_with_progress(&v, iso, &|_| {
                calls.fetch_add(1, Ordering::Relaxed);
            });
            assert_eq!(m, MeshData::default());
        }
        assert_eq!(calls.load(Ordering::Relaxed), 4);
    }

    #[test]
    fn tiny_volume_single_cell() {
        // A 2x2x2 volume with one high corner: one triangle, normal away from that corner.
        let mut values = vec![0.0; 8];
        values[0] = 1.0;
        let v = VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], values).unwrap();
        let m = marching_cubes(&v, 0.5);
        assert_eq!(m.triangle_count(), 1);
        assert_eq!(m.positions.len(), 3);
        for p in &m.positions {
            assert!((Vec3::from_array(*p).element_sum() - 0.5).abs() < 1e-6);
        }
        for n in &m.normals {
            assert!(Vec3::from_array(*n).dot(Vec3::ONE) > 0.5);
        }
    }
}
