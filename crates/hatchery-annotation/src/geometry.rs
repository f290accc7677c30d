//! Small 2-D primitives shared by the layout, the tracer and the tests: axis-aligned rectangles,
//! segment intersection and a convex-polygon/rectangle test. All coordinates are pixels with the
//! origin at the top-left corner of the frame and y pointing down.

use glam::Vec2;

/// A polyline in pixels (top-left origin, y down).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// Vertices, px. A closed polyline does not repeat its first vertex at the end.
    pub points: Vec<Vec2>,
    /// Whether the last vertex connects back to the first.
    pub closed: bool,
}

/// An axis-aligned rectangle in pixels, `min` the top-left and `max` the bottom-right corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Top-left corner (smallest x and y), px.
    pub min: Vec2,
    /// Bottom-right corner (largest x and y), px.
    pub max: Vec2,
}

impl Rect {
    /// The rectangle of size `size` (w × h px) centred on `center`.
    pub fn from_center_size(center: Vec2, size: Vec2) -> Self {
        let half = size * 0.5;
        Self {
            min: center - half,
            max: center + half,
        }
    }

    /// Width × height, px.
    pub fn size(&self) -> Vec2 {
        self.max - self.min
    }

    /// Centre point, px.
    pub fn center(&self) -> Vec2 {
        (self.min + self.max) * 0.5
    }

    /// This rectangle moved by `offset` px.
    pub fn translated(&self, offset: Vec2) -> Self {
        Self {
            min: self.min + offset,
            max: self.max + offset,
        }
    }

    /// This rectangle grown by `amount` px on every side (shrunk where negative).
    pub fn expanded(&self, amount: f32) -> Self {
        Self {
            min: self.min - Vec2::splat(amount),
            max: self.max + Vec2::splat(amount),
        }
    }

    /// Whether the two rectangles share an area of positive size (touching edges do not count).
    pub fn overlaps(&self, other: &Rect) -> bool {
        self.min.x < other.max.x
            && other.min.x < self.max.x
            && self.min.y < other.max.y
            && other.min.y < self.max.y
    }

    /// The point of the rectangle (boundary or inside) closest to `p`.
    pub fn closest_point(&self, p: Vec2) -> Vec2 {
        p.clamp(self.min, self.max)
    }

    /// Whether `p` lies inside or on the boundary.
    pub fn contains(&self, p: Vec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The four corners, clockwise on screen from the top-left.
    pub fn corners(&self) -> [Vec2; 4] {
        [
            self.min,
            Vec2::new(self.max.x, self.min.y),
            self.max,
            Vec2::new(self.min.x, self.max.y),
        ]
    }

    /// Whether the rectangle lies inside the frame `[0, frame.x] × [0, frame.y]`.
    pub fn inside_frame(&self, frame: Vec2) -> bool {
        self.min.cmpge(Vec2::ZERO).all() && self.max.cmple(frame).all()
    }
}

/// 2-D cross product (z of the 3-D cross product): positive when `b` turns left of `a` in a
/// y-up frame.
#[inline]
pub fn cross(a: Vec2, b: Vec2) -> f32 {
    a.x * b.y - a.y * b.x
}

/// Whether the closed segments `a0–a1` and `b0–b1` properly cross: they share a point that is
/// interior to both (each segment's ends lie strictly on opposite sides of the other's line).
/// Segments that only touch at an end point, or are collinear, do not cross.
pub fn segments_cross(a0: Vec2, a1: Vec2, b0: Vec2, b1: Vec2) -> bool {
    let da = a1 - a0;
    let db = b1 - b0;
    let d1 = cross(da, b0 - a0);
    let d2 = cross(da, b1 - a0);
    let d3 = cross(db, a0 - b0);
    let d4 = cross(db, a1 - b0);
    ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
}

/// Whether an axis-aligned rectangle and a convex polygon share an area of positive size, by the
/// separating-axis theorem (the axes are x, y and the polygon's edge normals). `polygon` may be in
/// either orientation; fewer than 3 vertices (a point or a segment) never intersect, since they
/// have no area.
pub fn rect_intersects_convex_polygon(rect: &Rect, polygon: &[Vec2]) -> bool {
    if polygon.len() < 3 {
        return false;
    }
    let (pmin, pmax) = polygon.iter().fold(
        (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if !(rect.min.x < pmax.x && pmin.x < rect.max.x && rect.min.y < pmax.y && pmin.y < rect.max.y) {
        return false;
    }
    let corners = rect.corners();
    for i in 0..polygon.len() {
        let a = polygon[i];
        let b = polygon[(i + 1) % polygon.len()];
        let axis = Vec2::new(b.y - a.y, a.x - b.x);
        if axis == Vec2::ZERO {
            continue;
        }
        let project = |p: Vec2| axis.dot(p);
        let (rlo, rhi) = corners.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &c| {
            (lo.min(project(c)), hi.max(project(c)))
        });
        let (plo, phi) = polygon.iter().fold((f32::MAX, f32::MIN), |(lo, hi), &c| {
            (lo.min(project(c)), hi.max(project(c)))
        });
        if rhi <= plo || phi <= rlo {
            return false;
        }
    }
    true
}

/// Distance from `p` to the segment `a–b`, px.
pub fn point_segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_segments() {
        let o = Vec2::ZERO;
        assert!(segments_cross(
            o,
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(2.0, 0.0)
        ));
        assert!(!segments_cross(
            o,
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(2.0, 0.0)
        ));
        assert!(!segments_cross(o, Vec2::X, Vec2::Y, Vec2::new(1.0, 1.0)));
    }

    #[test]
    fn rect_polygon() {
        let square = [
            Vec2::new(0.0, 0.0),
            Vec2::new(10.0, 0.0),
            Vec2::new(10.0, 10.0),
            Vec2::new(0.0, 10.0),
        ];
        let r = |x0: f32, y0: f32, x1: f32, y1: f32| Rect {
            min: Vec2::new(x0, y0),
            max: Vec2::new(x1, y1),
        };
        assert!(rect_intersects_convex_polygon(
            &r(5.0, 5.0, 12.0, 12.0),
            &square
        ));
        assert!(!rect_intersects_convex_polygon(
            &r(10.0, 0.0, 12.0, 2.0),
            &square
        ));
        let diamond = [
            Vec2::new(5.0, 0.0),
            Vec2::new(10.0, 5.0),
            Vec2::new(5.0, 10.0),
            Vec2::new(0.0, 5.0),
        ];
        // Inside the bounding box but beyond the diagonal edge.
        assert!(!rect_intersects_convex_polygon(
            &r(8.0, 8.0, 10.0, 10.0),
            &diamond
        ));
        assert!(rect_intersects_convex_polygon(
            &r(6.0, 6.0, 10.0, 10.0),
            &diamond
        ));
    }
}
