//! Marching squares and RDP on analytic shapes.

use glam::Vec2;
use hatchery_annotation::{Polyline, signed_area, simplify, trace_mask};

/// Binary disc mask: pixel centres within `r` of `c`.
fn disc(width: usize, height: usize, c: Vec2, r: f32) -> Vec<f32> {
    (0..width * height)
        .map(|i| {
            let p = Vec2::new((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
            f32::from(p.distance(c) <= r)
        })
        .collect()
}

/// Largest distance from the polyline (its vertices and points along its segments) to the
/// circle.
fn circle_error(line: &Polyline, c: Vec2, r: f32) -> (f32, f32) {
    let n = line.points.len();
    let segments = if line.closed { n } else { n - 1 };
    let mut vertex_err = 0.0f32;
    let mut segment_err = 0.0f32;
    for k in 0..n {
        vertex_err = vertex_err.max((line.points[k].distance(c) - r).abs());
    }
    for k in 0..segments {
        let (a, b) = (line.points[k], line.points[(k + 1) % n]);
        for s in 0..=16 {
            let p = a.lerp(b, s as f32 / 16.0);
            segment_err = segment_err.max((p.distance(c) - r).abs());
        }
    }
    (vertex_err, segment_err)
}

#[test]
fn binary_disc_traces_to_the_circle() {
    let (c, r) = (Vec2::new(40.3, 37.8), 25.0);
    let mask = disc(80, 76, c, r);
    for tolerance in [0.0f32, 0.5, 1.0, 2.0] {
        let lines = trace_mask(&mask, 80, 76, 0.5, tolerance);
        assert_eq!(lines.len(), 1, "one contour");
        let line = &lines[0];
        assert!(line.closed);
        let (vertex_err, segment_err) = circle_error(line, c, r);
        // Contour vertices lie halfway between an inside and an outside pixel centre: within
        // 0.5 px of the circle; simplified segments add at most the tolerance.
        assert!(
            vertex_err <= 0.5 + 1e-4,
            "tolerance {tolerance}: vertex error {vertex_err}"
        );
        assert!(
            segment_err <= tolerance + 0.5 + 1e-3,
            "tolerance {tolerance}: segment error {segment_err}"
        );
        // Orientation: inside on the left when walking on screen (y down), so the signed area
        // in pixel coordinates is negative for an outer contour.
        let area = signed_area(&line.points);
        assert!(area < 0.0);
        assert!(
            (area.abs() - std::f32::consts::PI * r * r).abs() < 0.02 * std::f32::consts::PI * r * r
        );
        println!(
            "disc r = {r}, tolerance {tolerance}: {} vertices, vertex error {vertex_err:.3} px, segment error {segment_err:.3} px",
            line.points.len()
        );
    }
}

#[test]
fn antialiased_disc_is_subpixel_accurate() {
    // Coverage-like mask: 1 inside, 0 outside, linear over one pixel across the circle, so the
    // 0.5 level is the circle itself.
    let (c, r, w, h) = (Vec2::new(50.0, 45.5), 30.0, 100usize, 90usize);
    let mask: Vec<f32> = (0..w * h)
        .map(|i| {
            let p = Vec2::new((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
            (r - p.distance(c) + 0.5).clamp(0.0, 1.0)
        })
        .collect();
    let lines = trace_mask(&mask, w, h, 0.5, 0.0);
    assert_eq!(lines.len(), 1);
    let (vertex_err, _) = circle_error(&lines[0], c, r);
    assert!(vertex_err < 0.1, "vertex error {vertex_err}");
}

#[test]
fn square_simplifies_to_its_corners() {
    // Pixels 10..30 × 20..35 inside: the 0.5 contour runs along the pixel edges between inside
    // and outside centres, x = 10 and 30, y = 20 and 35, with corners cut by half a pixel.
    let (w, h) = (48usize, 50usize);
    let mask: Vec<f32> = (0..w * h)
        .map(|i| f32::from((10..30).contains(&(i % w)) && (20..35).contains(&(i / w))))
        .collect();
    let on_boundary = |p: Vec2| {
        let dx = (p.x - 10.0).abs().min((p.x - 30.0).abs());
        let dy = (p.y - 20.0).abs().min((p.y - 35.0).abs());
        (p.x >= 9.99 && p.x <= 30.01 && dy < 1e-3)
            || (p.y >= 19.99 && p.y <= 35.01 && dx < 1e-3)
            || (dx <= 0.5 + 1e-3 && dy <= 0.5 + 1e-3)
    };
    for tolerance in [0.25f32, 0.75] {
        let lines = trace_mask(&mask, w, h, 0.5, tolerance);
        assert_eq!(lines.len(), 1);
        let line = &lines[0];
        assert!(line.closed);
        for &p in &line.points {
            assert!(on_boundary(p), "{p} off the square");
        }
        let area = signed_area(&line.points).abs();
        if tolerance < 0.35 {
            // Below the corner cuts' depth (0.35 px) the octagon stays: 8 vertices, 300 − 4 · ⅛.
            assert_eq!(line.points.len(), 8, "{:?}", line.points);
            assert!((area - 299.5).abs() < 1e-3, "area {area}");
        } else {
            // Above it RDP may drop the corners too; the area stays within tolerance · perimeter.
            assert!(line.points.len() >= 4 && line.points.len() <= 8);
            assert!((area - 300.0).abs() <= tolerance * 70.0, "area {area}");
        }
    }
}

#[test]
fn shapes_touching_the_border_stay_open_and_holes_are_separate() {
    // A band across the whole width: two open contours (top and bottom), the frame not traced.
    let (w, h) = (30usize, 20usize);
    let band: Vec<f32> = (0..w * h)
        .map(|i| f32::from((5..12).contains(&(i / w))))
        .collect();
    let lines = trace_mask(&band, w, h, 0.5, 0.5);
    assert_eq!(lines.len(), 2);
    for line in &lines {
        assert!(!line.closed);
        assert_eq!(
            line.points.len(),
            2,
            "a straight contour simplifies to its ends"
        );
        assert!((line.points[0].y - line.points[1].y).abs() < 1e-4);
    }
    // A ring (annulus): an outer and an inner contour, oppositely oriented.
    let c = Vec2::new(25.0, 25.0);
    let ring: Vec<f32> = (0..50 * 50)
        .map(|i| {
            let d = Vec2::new((i % 50) as f32 + 0.5, (i / 50) as f32 + 0.5).distance(c);
            f32::from((8.0..=18.0).contains(&d))
        })
        .collect();
    let lines = trace_mask(&ring, 50, 50, 0.5, 0.5);
    assert_eq!(lines.len(), 2);
    let mut areas: Vec<f32> = lines.iter().map(|l| signed_area(&l.points)).collect();
    areas.sort_by(f32::total_cmp);
    assert!(areas[0] < 0.0 && areas[1] > 0.0, "{areas:?}");
    assert!(areas[0].abs() > areas[1].abs());
}

#[test]
fn rdp_keeps_ends_and_drops_collinear_points() {
    let line = Polyline {
        points: (0..=10)
            .map(|k| Vec2::new(k as f32, 0.0))
            .chain([Vec2::new(10.0, 5.0)])
            .collect(),
        closed: false,
    };
    let s = simplify(&line, 0.1);
    assert_eq!(
        s.points,
        vec![Vec2::ZERO, Vec2::new(10.0, 0.0), Vec2::new(10.0, 5.0)]
    );
    assert_eq!(simplify(&line, 0.0), line);
}

#[test]
fn empty_and_degenerate_masks() {
    assert!(trace_mask(&[], 0, 0, 0.5, 1.0).is_empty());
    assert!(trace_mask(&[1.0; 12], 4, 3, 0.5, 1.0).is_empty());
    assert!(trace_mask(&[0.0; 12], 4, 3, 0.5, 1.0).is_empty());
    // A single inside pixel: a closed diamond of 4 vertices around its centre.
    let mut one = vec![0.0; 25];
    one[12] = 1.0;
    let lines = trace_mask(&one, 5, 5, 0.5, 0.0);
    assert_eq!(lines.len(), 1);
    assert!(lines[0].closed);
    assert_eq!(lines[0].points.len(), 4);
}
