//! Convex hull and its arc-length parameterisation against known shapes.

use glam::Vec2;
use hatchery_annotation::{HullPath, convex_contains, convex_hull, signed_area};
use std::f32::consts::{PI, TAU};

fn square_points() -> Vec<Vec2> {
    // Corners, edge midpoints (collinear, must be dropped), inner points and duplicates.
    vec![
        Vec2::new(10.0, 10.0),
        Vec2::new(20.0, 15.0),
        Vec2::new(30.0, 10.0),
        Vec2::new(30.0, 20.0),
        Vec2::new(30.0, 30.0),
        Vec2::new(20.0, 30.0),
        Vec2::new(10.0, 30.0),
        Vec2::new(10.0, 20.0),
        Vec2::new(20.0, 20.0),
        Vec2::new(30.0, 30.0),
        Vec2::new(15.0, 25.0),
    ]
}

#[test]
fn hull_of_square_drops_inner_and_collinear_points() {
    let hull = convex_hull(&square_points());
    assert_eq!(hull.len(), 4, "{hull:?}");
    assert_eq!(
        hull[0],
        Vec2::new(10.0, 10.0),
        "starts at the smallest x, then y"
    );
    assert!((signed_area(&hull) - 400.0).abs() < 1e-3);
    for p in square_points() {
        assert!(convex_contains(&hull, p));
    }
    assert!(!convex_contains(&hull, Vec2::new(31.0, 20.0)));
}

#[test]
fn hull_degenerate_inputs() {
    assert!(convex_hull(&[]).is_empty());
    assert_eq!(convex_hull(&[Vec2::ONE, Vec2::ONE]).len(), 1);
    let line = convex_hull(&[Vec2::ZERO, Vec2::new(1.0, 1.0), Vec2::new(2.0, 2.0)]);
    assert_eq!(line, vec![Vec2::ZERO, Vec2::new(2.0, 2.0)]);
    // A segment grown by r is a stadium of length 2·|ab| + 2πr.
    let path = HullPath::new(&line, 1.0);
    assert!((path.length() - (2.0 * 8f32.sqrt() + TAU)).abs() < 1e-3);
    // A point grown by r is a circle.
    let dot = HullPath::new(&[Vec2::new(5.0, 5.0)], 2.0);
    assert!((dot.length() - 2.0 * TAU).abs() < 1e-4);
    assert!((dot.point_at(0.25).distance(Vec2::new(5.0, 5.0)) - 2.0).abs() < 1e-4);
}

#[test]
fn square_parameterisation_is_arc_length() {
    let hull = convex_hull(&square_points());
    let path = HullPath::new(&hull, 0.0);
    assert!((path.length() - 80.0).abs() < 1e-4);
    // t = k/8 walks corner, midpoint, corner, … in the hull's order: positive signed area, from
    // (10,10) towards +x first (clockwise on screen, where y points down).
    let order = [
        (10.0, 10.0),
        (20.0, 10.0),
        (30.0, 10.0),
        (30.0, 20.0),
        (30.0, 30.0),
        (20.0, 30.0),
        (10.0, 30.0),
        (10.0, 20.0),
    ];
    for (k, &(x, y)) in order.iter().enumerate() {
        let t = k as f32 / 8.0;
        let p = path.point_at(t);
        assert!(
            p.distance(Vec2::new(x, y)) < 1e-3,
            "t={t}: {p} vs ({x}, {y})"
        );
        let back = path.parameter_of(p);
        let d = (back - t + 0.5).rem_euclid(1.0) - 0.5;
        assert!(d.abs() < 1e-5, "t={t} → {p} → {back}");
    }
    // Outward normals: the midpoint of each side points away from the centre.
    for k in 0..4 {
        let t = (2 * k + 1) as f32 / 8.0;
        let n = path.normal_at(t);
        let out = (path.point_at(t) - Vec2::splat(20.0)).normalize();
        assert!(n.dot(out) > 0.999, "t={t} n={n} out={out}");
    }
    // A point inside maps to the closest side.
    let t = path.parameter_of(Vec2::new(28.0, 21.0));
    assert!(path.point_at(t).distance(Vec2::new(30.0, 21.0)) < 1e-3);
}

#[test]
fn grown_square_has_rounded_corners_and_continuous_normal() {
    let hull = convex_hull(&square_points());
    let r = 5.0;
    let path = HullPath::new(&hull, r);
    assert!((path.length() - (80.0 + TAU * r)).abs() < 1e-3);
    let n = 2000;
    for k in 0..n {
        let t = k as f32 / n as f32;
        let s = path.sample(t);
        // Every path point is at distance r from the square's boundary, and base = point − r·n.
        let d = path.distance_to_hull_boundary(s.point);
        assert!((d - r).abs() < 1e-3, "t={t} d={d}");
        assert!((s.point - s.normal * r).distance(s.base) < 1e-4);
        let next = path.sample((k + 1) as f32 / n as f32);
        assert!(s.normal.dot(next.normal) > 0.99, "normal jumps at t={t}");
        assert!(s.point.distance(next.point) <= path.length() / n as f32 + 1e-3);
    }
}

#[test]
fn circle_hull_parameterisation() {
    let (c, radius, n) = (Vec2::new(100.0, 80.0), 50.0f32, 256);
    let pts: Vec<Vec2> = (0..n)
        .map(|k| {
            let a = TAU * k as f32 / n as f32;
            c + radius * Vec2::new(a.cos(), a.sin())
        })
        .collect();
    let hull = convex_hull(&pts);
    assert_eq!(hull.len(), n);
    let perimeter = 2.0 * n as f32 * radius * (PI / n as f32).sin();
    let path = HullPath::new(&hull, 0.0);
    assert!((path.length() - perimeter).abs() < 1e-2);
    // Arc length ∝ angle for a regular polygon: t advances uniformly with the polar angle.
    let t0 = path.parameter_of(c + Vec2::new(radius, 0.0));
    for k in 1..16 {
        let a = TAU * k as f32 / 16.0;
        let t = path.parameter_of(c + radius * Vec2::new(a.cos(), a.sin()));
        let expected = k as f32 / 16.0;
        let got = (t - t0).rem_euclid(1.0);
        // Orientation: positive area turns from +x towards +y, i.e. increasing angle.
        assert!(
            (got - expected).abs() < 2e-3,
            "angle {a}: {got} vs {expected}"
        );
        let p = path.point_at(t);
        assert!((p.distance(c) - radius).abs() < 0.05);
        assert!(path.normal_at(t).dot((p - c).normalize()) > 0.99);
    }
}
