//! Mask → polylines: iso-contours of a scalar mask by marching squares, joined into polylines and
//! simplified with Ramer–Douglas–Peucker ([`simplify`](crate::simplify)). For the line layer of
//! a vector export: a rendered silhouette or line mask becomes resolution-independent paths.

use crate::simplify::simplify;
use glam::Vec2;
use std::collections::HashMap;

pub use crate::geometry::Polyline;

/// Traces the `threshold` iso-contours of `mask` (row-major, `width × height` values, row 0 at
/// the top) by marching squares and simplifies them with Ramer–Douglas–Peucker at `tolerance` px
/// (0 keeps every contour vertex).
///
/// Sample `(x, y)` sits at the pixel centre `(x + 0.5, y + 0.5)`; contour vertices lie on the
/// segments between 4-neighbouring samples, placed by linear interpolation of the values. Values
/// `≥ threshold` are inside. Saddle cells are resolved by the cell's mean value (inside when the
/// mean is `≥ threshold`: the inside is connected through the cell). Contours that reach the
/// outermost sample centres stay open there (the frame border is not traced); all others are
/// closed. Polylines are oriented with the inside on the left when walking along them on screen
/// (y down): outer contours run counter-clockwise on screen (negative
/// [`signed_area`](crate::signed_area) in pixel coordinates), holes clockwise.
///
/// Returns an empty list for an empty mask. Panics if `mask.len() != width * height`. NaN values
/// count as outside.
pub fn trace_mask(
    mask: &[f32],
    width: usize,
    height: usize,
    threshold: f32,
    tolerance: f32,
) -> Vec<Polyline> {
    assert_eq!(
        mask.len(),
        width * height,
        "mask must have width × height values"
    );
    if width < 2 || height < 2 {
        return Vec::new();
    }
    let value = |x: usize, y: usize| mask[y * width + x];
    let inside = |x: usize, y: usize| value(x, y) >= threshold;

    // Edge ids: horizontal edge (x, y)–(x+1, y) is 2·(y·width + x), vertical (x, y)–(x, y+1) is
    // 2·(y·width + x) + 1. Each crossing gets one vertex, shared by the two cells beside it.
    let mut vertex_of: HashMap<usize, usize> = HashMap::new();
    let mut vertices: Vec<Vec2> = Vec::new();
    let mut vertex = |edge: usize| -> usize {
        *vertex_of.entry(edge).or_insert_with(|| {
            let cell = edge / 2;
            let (x, y) = (cell % width, cell / width);
            let (x1, y1) = if edge.is_multiple_of(2) {
                (x + 1, y)
            } else {
                (x, y + 1)
            };
            let (a, b) = (value(x, y), value(x1, y1));
            let t = if (b - a).abs() > f32::EPSILON {
                ((threshold - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                0.5
            };
            let p0 = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let p1 = Vec2::new(x1 as f32 + 0.5, y1 as f32 + 0.5);
            vertices.push(p0 + (p1 - p0) * t);
            vertices.len() - 1
        })
    };
    // next[v] = the vertex following v along its contour.
    let mut next: HashMap<usize, usize> = HashMap::new();
    for y in 0..height - 1 {
        for x in 0..width - 1 {
            // Corners clockwise on screen: top-left, top-right, bottom-right, bottom-left; edge k
            // joins corner k and k+1.
            let corners = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)];
            let ins = corners.map(|(cx, cy)| inside(cx, cy));
            let count = ins.iter().filter(|&&b| b).count();
            if count == 0 || count == 4 {
                continue;
            }
            let edges = [
                2 * (y * width + x),
                2 * (y * width + x + 1) + 1,
                2 * ((y + 1) * width + x),
                2 * (y * width + x) + 1,
            ];
            // Walking the cell's corners clockwise on screen, an edge from outside to inside is an
            // "entry", inside to outside an "exit". A segment runs from an entry to an exit, which
            // keeps the inside on its left on screen; neighbouring cells see a shared edge in
            // opposite directions, so their segments chain head to tail.
            let entries: Vec<usize> = (0..4).filter(|&k| !ins[k] && ins[(k + 1) % 4]).collect();
            let exits: Vec<usize> = (0..4).filter(|&k| ins[k] && !ins[(k + 1) % 4]).collect();
            let pairs: Vec<(usize, usize)> = if entries.len() == 1 {
                vec![(entries[0], exits[0])]
            } else {
                // Saddle: two entries, two exits. Inside connected through the centre: each entry
                // pairs with the exit just before it (cutting off the outside corners);
                // otherwise with the exit just after it (cutting off the inside corners).
                let mean = corners.iter().map(|&(cx, cy)| value(cx, cy)).sum::<f32>() * 0.25;
                entries
                    .iter()
                    .map(|&e| {
                        let exit = if mean >= threshold {
                            (e + 3) % 4
                        } else {
                            (e + 1) % 4
                        };
                        (e, exit)
                    })
                    .collect()
            };
            for (entry, exit) in pairs {
                let a = vertex(edges[entry]);
                let b = vertex(edges[exit]);
                next.insert(a, b);
            }
        }
    }
    join(&vertices, &next)
        .into_iter()
        .map(|polyline| simplify(&polyline, tolerance))
        .collect()
}

/// Follows `next` from every vertex with no predecessor (open chains), then around the remaining
/// cycles (closed chains). Output order is deterministic (by first vertex index).
fn join(vertices: &[Vec2], next: &HashMap<usize, usize>) -> Vec<Polyline> {
    let mut has_prev = vec![false; vertices.len()];
    for &b in next.values() {
        has_prev[b] = true;
    }
    let mut used = vec![false; vertices.len()];
    let mut out = Vec::new();
    let mut starts: Vec<usize> = next.keys().copied().collect();
    starts.sort_unstable();
    for pass in 0..2 {
        for &start in &starts {
            if used[start] || (pass == 0 && has_prev[start]) {
                continue;
            }
            let mut points = Vec::new();
            let mut v = start;
            let closed = loop {
                used[v] = true;
                points.push(vertices[v]);
                // An open chain ends at a vertex without successor (pushed above).
                match next.get(&v) {
                    Some(&w) if w == start => break true,
                    Some(&w) if !used[w] => v = w,
                    _ => break false,
                }
            };
            out.push(Polyline { points, closed });
        }
    }
    out
}
