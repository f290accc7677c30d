//! Shared test helpers: a seeded SplitMix64 generator and independent geometry checks (written
//! separately from the crate's own, so the tests do not check the code against itself).
#![allow(dead_code)]

use glam::Vec2;
use hatchery_annotation::{ProjectedAnchor, convex_hull};

/// The frame of the layout tests, px.
pub const FRAME: Vec2 = Vec2::new(800.0, 600.0);

/// SplitMix64 (Steele, Lea & Flood 2014): deterministic, seedable, good enough for test inputs.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
    pub fn int(&mut self, lo: usize, hi_inclusive: usize) -> usize {
        lo + (self.next_u64() % (hi_inclusive - lo + 1) as u64) as usize
    }
}

fn orient(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (ax, ay, bx, by, cx, cy) = (
        a.x as f64, a.y as f64, b.x as f64, b.y as f64, c.x as f64, c.y as f64,
    );
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// Proper crossing of two segments, in f64: each segment's ends strictly on opposite sides of the
/// other's line.
pub fn cross_f64(a0: Vec2, a1: Vec2, b0: Vec2, b1: Vec2) -> bool {
    let d1 = orient(a0, a1, b0);
    let d2 = orient(a0, a1, b1);
    let d3 = orient(b0, b1, a0);
    let d4 = orient(b0, b1, a1);
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Strict overlap (positive area) of two boxes given as (min, max).
pub fn boxes_overlap(a: (Vec2, Vec2), b: (Vec2, Vec2)) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// Whether point p is strictly inside the convex polygon (either orientation).
fn strictly_inside_convex(poly: &[Vec2], p: Vec2) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let signs: Vec<f64> = (0..n)
        .map(|i| orient(poly[i], poly[(i + 1) % n], p))
        .collect();
    signs.iter().all(|&s| s > 1e-6) || signs.iter().all(|&s| s < -1e-6)
}

/// Whether a box (min, max) and a convex polygon share interior points: a corner strictly inside
/// the polygon, a polygon vertex strictly inside the box, the box centre inside the polygon, or
/// two edges crossing.
pub fn box_hits_polygon(b: (Vec2, Vec2), poly: &[Vec2]) -> bool {
    let corners = [b.0, Vec2::new(b.1.x, b.0.y), b.1, Vec2::new(b.0.x, b.1.y)];
    if corners.iter().any(|&c| strictly_inside_convex(poly, c))
        || strictly_inside_convex(poly, (b.0 + b.1) * 0.5)
    {
        return true;
    }
    if poly
        .iter()
        .any(|p| p.x > b.0.x && p.x < b.1.x && p.y > b.0.y && p.y < b.1.y)
    {
        return true;
    }
    let n = poly.len();
    (0..n).any(|i| {
        (0..4).any(|k| cross_f64(poly[i], poly[(i + 1) % n], corners[k], corners[(k + 1) % 4]))
    })
}

/// A random scene: a hull from 4–40 points in a rotated ellipse around the frame centre, 5–30
/// anchors inside it, label boxes of 40–120 × 12–18 px, random depths, 5 % invisible anchors.
pub struct Scene {
    pub anchors: Vec<ProjectedAnchor>,
    pub sizes: Vec<Vec2>,
    pub hull_points: Vec<Vec2>,
}

pub fn random_scene(rng: &mut Rng) -> Scene {
    let center = FRAME * 0.5 + Vec2::new(rng.range(-60.0, 60.0), rng.range(-40.0, 40.0));
    let radii = Vec2::new(rng.range(60.0, 220.0), rng.range(50.0, 160.0));
    let rotation = rng.range(0.0, std::f32::consts::TAU);
    let (s, c) = rotation.sin_cos();
    let in_ellipse = |rng: &mut Rng, on_rim: bool| {
        let a = rng.range(0.0, std::f32::consts::TAU);
        let r = if on_rim {
            rng.range(0.7, 1.0)
        } else {
            rng.unit().sqrt() * 0.95
        };
        let e = Vec2::new(a.cos() * radii.x, a.sin() * radii.y) * r;
        center + Vec2::new(c * e.x - s * e.y, s * e.x + c * e.y)
    };
    let hull_points: Vec<Vec2> = (0..rng.int(4, 40)).map(|_| in_ellipse(rng, true)).collect();
    let hull = convex_hull(&hull_points);
    let n = rng.int(5, 30);
    let mut anchors = Vec::with_capacity(n);
    while anchors.len() < n {
        // Anchors inside the hull: convex combinations of hull vertices.
        let w: Vec<f32> = hull.iter().map(|_| rng.unit().powi(3)).collect();
        let sum: f32 = w.iter().sum();
        if sum <= 0.0 {
            continue;
        }
        let p = hull.iter().zip(&w).map(|(&v, &wi)| v * wi).sum::<Vec2>() / sum;
        anchors.push(ProjectedAnchor {
            screen: p,
            depth: rng.range(0.2, 0.95),
            visible: rng.unit() > 0.05,
            priority: 0.0,
        });
    }
    let sizes = (0..n)
        .map(|_| Vec2::new(rng.range(40.0, 120.0), rng.range(12.0, 18.0)))
        .collect();
    Scene {
        anchors,
        sizes,
        hull_points,
    }
}
