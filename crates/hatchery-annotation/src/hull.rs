//! The silhouette polygon of §6.4 (VolumeShop, Bruckner & Gröller 2005): "the convex hull of the
//! projections of the bounding volumes of all visible objects. The resulting polygon is radially
//! parameterized. Thus, the position of an annotation is defined by one value in the range
//! [0,1]."
//!
//! [`convex_hull`] is Andrew's monotone chain. [`HullPath`] parameterises the boundary of the hull
//! grown by a margin `r` (the Minkowski sum with a disc: the hull's edges moved out by `r`, joined by
//! circular arcs of radius `r` around the vertices) by normalised arc length `t ∈ [0, 1)`. With
//! `r > 0` the outward normal is continuous in `t`, so a label that slides along the path never
//! jumps at a hull corner; with `r = 0` the path is the polygon itself.

use crate::geometry::{cross, point_segment_distance};
use glam::Vec2;
use std::f32::consts::TAU;

/// Convex hull of a 2-D point set by Andrew's monotone chain, O(n log n).
///
/// Returns the hull vertices without repetition and without collinear points, starting at the
/// point with the smallest x (then smallest y), ordered so that the signed area
/// `½ Σ cross(vᵢ, vᵢ₊₁)` is positive, i.e. counter-clockwise in a y-up frame, which is
/// *clockwise on screen* for pixel coordinates with y down. Degenerate inputs give 0, 1 (all points
/// equal) or 2 (all points collinear: the two extremes) vertices. Non-finite points are ignored.
pub fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut pts: Vec<Vec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() <= 2 {
        return pts;
    }
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * pts.len());
    // Lower chain, then upper chain; pop while the turn is not strictly left (drops collinear).
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2 {
                let a = hull[hull.len() - 2];
                let b = hull[hull.len() - 1];
                if cross(b - a, p - a) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(p);
        }
        hull.pop(); // the last point of each chain is the first of the other
    }
    hull
}

/// Whether `p` lies inside or on a convex polygon given in [`convex_hull`]'s orientation.
/// Polygons with fewer than 3 vertices contain nothing.
pub fn convex_contains(polygon: &[Vec2], p: Vec2) -> bool {
    polygon.len() >= 3
        && (0..polygon.len()).all(|i| {
            let a = polygon[i];
            let b = polygon[(i + 1) % polygon.len()];
            cross(b - a, p - a) >= 0.0
        })
}

/// Signed area of a polygon, px² (positive in [`convex_hull`]'s orientation).
pub fn signed_area(polygon: &[Vec2]) -> f32 {
    let n = polygon.len();
    0.5 * (0..n)
        .map(|i| cross(polygon[i], polygon[(i + 1) % n]))
        .sum::<f32>()
}

#[derive(Clone, Debug, PartialEq)]
enum Piece {
    /// A hull edge moved out by the margin: from `a` to `b`, outward normal `normal`.
    Segment { a: Vec2, b: Vec2, normal: Vec2 },
    /// The arc of radius `r` around hull vertex `center`, from angle `start` over `sweep` ≥ 0 rad
    /// (angles of the outward normal, increasing in the hull's orientation); `from` and `to` are
    /// the unit normals at its ends, for the trigonometry-free tests of `parameter_of`.
    Arc {
        center: Vec2,
        start: f32,
        sweep: f32,
        from: Vec2,
        to: Vec2,
    },
}

/// One point of a [`HullPath`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSample {
    /// The point on the grown path, px.
    pub point: Vec2,
    /// Unit outward normal there (continuous in `t` when the margin is positive).
    pub normal: Vec2,
    /// The hull polygon point this path point was grown from: `point − margin · normal` (a hull
    /// vertex along an arc), px.
    pub base: Vec2,
}

/// The boundary of a convex hull grown by a margin, parameterised by normalised arc length
/// `t ∈ [0, 1)` (0 at the start of the edge leaving the first hull vertex, increasing in the
/// hull's orientation, clockwise on screen). Parameters outside [0, 1) wrap around.
#[derive(Clone, Debug, PartialEq)]
pub struct HullPath {
    vertices: Vec<Vec2>,
    margin: f32,
    pieces: Vec<Piece>,
    /// Arc length at the start of each piece, px.
    starts: Vec<f32>,
    length: f32,
}

impl HullPath {
    /// The path around the convex polygon `hull` (as returned by [`convex_hull`]: convex, no
    /// repeated vertices, positive signed area) grown by `margin` ≥ 0 px.
    ///
    /// Degenerate hulls work: one vertex gives a circle of radius `margin` (a single point when
    /// `margin` = 0), two vertices a stadium around the segment. An empty hull gives an empty path
    /// whose samples are all at the origin; check [`HullPath::is_empty`].
    pub fn new(hull: &[Vec2], margin: f32) -> Self {
        let margin = margin.max(0.0);
        let mut pieces = Vec::new();
        match hull.len() {
            0 => {}
            1 => pieces.push(Piece::Arc {
                center: hull[0],
                start: 0.0,
                sweep: TAU,
                from: Vec2::X,
                to: Vec2::X,
            }),
            n => {
                let normal_of = |i: usize| {
                    let d = hull[(i + 1) % n] - hull[i];
                    Vec2::new(d.y, -d.x).normalize_or_zero()
                };
                for i in 0..n {
                    let a = hull[i];
                    let b = hull[(i + 1) % n];
                    let normal = normal_of(i);
                    pieces.push(Piece::Segment {
                        a: a + normal * margin,
                        b: b + normal * margin,
                        normal,
                    });
                    let next = normal_of((i + 1) % n);
                    let start = normal.y.atan2(normal.x);
                    let sweep = (next.y.atan2(next.x) - start).rem_euclid(TAU);
                    // A collinear corner sweeps 0 (or TAU through rounding); skip it.
                    if sweep > 1e-6 && sweep < TAU - 1e-4 {
                        pieces.push(Piece::Arc {
                            center: b,
                            start,
                            sweep,
                            from: normal,
                            to: next,
                        });
                    }
                }
            }
        }
        let mut starts = Vec::with_capacity(pieces.len());
        let mut length = 0.0;
        for piece in &pieces {
            starts.push(length);
            length += match piece {
                Piece::Segment { a, b, .. } => a.distance(*b),
                Piece::Arc { sweep, .. } => sweep * margin,
            };
        }
        Self {
            vertices: hull.to_vec(),
            margin,
            pieces,
            starts,
            length,
        }
    }

    /// The hull polygon the path was grown from.
    pub fn vertices(&self) -> &[Vec2] {
        &self.vertices
    }

    /// The margin the hull was grown by, px.
    pub fn margin(&self) -> f32 {
        self.margin
    }

    /// Total arc length, px (the hull's perimeter plus 2π·margin).
    pub fn length(&self) -> f32 {
        self.length
    }

    /// Whether the path has no length (an empty hull, or a single point with zero margin).
    pub fn is_empty(&self) -> bool {
        self.length <= 0.0
    }

    /// The point, outward normal and hull base point at parameter `t` (wrapped into [0, 1)).
    pub fn sample(&self, t: f32) -> PathSample {
        if self.is_empty() {
            let p = self.vertices.first().copied().unwrap_or(Vec2::ZERO);
            return PathSample {
                point: p,
                normal: Vec2::NEG_Y,
                base: p,
            };
        }
        let s = t.rem_euclid(1.0) * self.length;
        let k = self.starts.partition_point(|&start| start <= s).max(1) - 1;
        let local = s - self.starts[k];
        match self.pieces[k] {
            Piece::Segment { a, b, normal } => {
                let len = a.distance(b);
                let point = if len > 0.0 {
                    a + (b - a) * (local / len).min(1.0)
                } else {
                    a
                };
                PathSample {
                    point,
                    normal,
                    base: point - normal * self.margin,
                }
            }
            Piece::Arc {
                center,
                start,
                sweep,
                ..
            } => {
                let angle = start + (local / self.margin).min(sweep);
                let normal = Vec2::new(angle.cos(), angle.sin());
                PathSample {
                    point: center + normal * self.margin,
                    normal,
                    base: center,
                }
            }
        }
    }

    /// The point at parameter `t`, px.
    pub fn point_at(&self, t: f32) -> Vec2 {
        self.sample(t).point
    }

    /// The unit outward normal at parameter `t`.
    pub fn normal_at(&self, t: f32) -> Vec2 {
        self.sample(t).normal
    }

    /// The parameter in [0, 1) of the path point closest to `p` (the closest point of the hull
    /// boundary for a point inside, since the path is parallel to it). O(hull vertices). Returns 0
    /// for an empty path.
    pub fn parameter_of(&self, p: Vec2) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        // Closest piece by distance first (no trigonometry), then the position along it.
        let mut best = (f32::MAX, 0usize);
        for (k, piece) in self.pieces.iter().enumerate() {
            let dist = match *piece {
                Piece::Segment { a, b, .. } => point_segment_distance(p, a, b),
                Piece::Arc {
                    center,
                    sweep,
                    from,
                    to,
                    ..
                } => {
                    let d = p - center;
                    // Arcs sweep at most π (a full turn only for a one-point hull).
                    let within =
                        sweep >= TAU - 1e-3 || (cross(from, d) >= 0.0 && cross(d, to) >= 0.0);
                    if within {
                        (d.length() - self.margin).abs()
                    } else {
                        p.distance(center + from * self.margin)
                            .min(p.distance(center + to * self.margin))
                    }
                }
            };
            if dist < best.0 {
                best = (dist, k);
            }
        }
        let k = best.1;
        let local = match self.pieces[k] {
            Piece::Segment { a, b, .. } => {
                let ab = b - a;
                let len2 = ab.length_squared();
                if len2 > 0.0 {
                    ((p - a).dot(ab) / len2).clamp(0.0, 1.0) * len2.sqrt()
                } else {
                    0.0
                }
            }
            Piece::Arc {
                center,
                start,
                sweep,
                ..
            } => {
                let d = p - center;
                let rel = (d.y.atan2(d.x) - start).rem_euclid(TAU);
                // Outside the arc's angular range the nearest arc point is an end.
                let rel = if rel <= sweep {
                    rel
                } else if rel - sweep < TAU - rel {
                    sweep
                } else {
                    0.0
                };
                rel * self.margin
            }
        };
        ((self.starts[k] + local) / self.length).rem_euclid(1.0)
    }

    /// Distance from `p` to the hull polygon's boundary, px (for tests and diagnostics).
    pub fn distance_to_hull_boundary(&self, p: Vec2) -> f32 {
        let n = self.vertices.len();
        (0..n)
            .map(|i| point_segment_distance(p, self.vertices[i], self.vertices[(i + 1) % n]))
            .fold(f32::MAX, f32::min)
    }
}

/// Signed difference `b − a` of two path parameters, wrapped into [−½, ½): the shorter way round.
pub fn parameter_delta(a: f32, b: f32) -> f32 {
    (b - a + 0.5).rem_euclid(1.0) - 0.5
}
