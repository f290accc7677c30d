//! Ramer–Douglas–Peucker polyline simplification.

use crate::geometry::Polyline;
use crate::geometry::point_segment_distance;
use glam::Vec2;

/// Simplifies `polyline` with Ramer–Douglas–Peucker: keeps a subset of its vertices such that
/// every removed vertex lies within `tolerance` px of the simplified polyline's segment that
/// replaced it. Closed polylines are split at the first vertex and the vertex farthest from it,
/// each half simplified, so a closed result keeps at least 3 vertices when the input has them.
/// `tolerance ≤ 0` returns the input unchanged.
pub fn simplify(polyline: &Polyline, tolerance: f32) -> Polyline {
    let pts = &polyline.points;
    if tolerance <= 0.0 || pts.len() < 3 {
        return polyline.clone();
    }
    let mut keep = vec![false; pts.len()];
    if polyline.closed {
        let far = (1..pts.len())
            .max_by(|&a, &b| {
                pts[0]
                    .distance_squared(pts[a])
                    .total_cmp(&pts[0].distance_squared(pts[b]))
            })
            .unwrap_or(1);
        keep[0] = true;
        keep[far] = true;
        rdp(pts, 0, far, tolerance, &mut keep);
        // Second half: far … last, then back to 0 (index pts.len() stands for 0).
        let mut ring: Vec<Vec2> = pts[far..].to_vec();
        ring.push(pts[0]);
        let mut keep_ring = vec![false; ring.len()];
        keep_ring[0] = true;
        keep_ring[ring.len() - 1] = true;
        rdp(&ring, 0, ring.len() - 1, tolerance, &mut keep_ring);
        for (k, &kept) in keep_ring.iter().enumerate().take(ring.len() - 1) {
            keep[far + k] |= kept;
        }
        // Keep a triangle at least.
        if keep.iter().filter(|&&k| k).count() < 3 {
            let mid = (far + pts.len()) / 2;
            keep[mid.min(pts.len() - 1)] = true;
        }
    } else {
        keep[0] = true;
        keep[pts.len() - 1] = true;
        rdp(pts, 0, pts.len() - 1, tolerance, &mut keep);
    }
    Polyline {
        points: pts
            .iter()
            .zip(&keep)
            .filter(|(_, k)| **k)
            .map(|(p, _)| *p)
            .collect(),
        closed: polyline.closed,
    }
}

/// Marks in `keep` the vertices of `pts[first..=last]` that RDP keeps (iterative, no recursion
/// depth limit).
fn rdp(pts: &[Vec2], first: usize, last: usize, tolerance: f32, keep: &mut [bool]) {
    let mut stack = vec![(first, last)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (mut worst, mut worst_d) = (a, -1.0f32);
        for (k, &p) in pts.iter().enumerate().take(b).skip(a + 1) {
            let d = point_segment_distance(p, pts[a], pts[b]);
            if d > worst_d {
                (worst, worst_d) = (k, d);
            }
        }
        if worst_d > tolerance {
            keep[worst] = true;
            stack.push((a, worst));
            stack.push((worst, b));
        }
    }
}
