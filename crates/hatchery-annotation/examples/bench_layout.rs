//! Times `layout` for 30 labels (§6.4: "usually no more than 30 annotations are used in a single
//! illustration"): 30 anchors in a 3-D box seen by an orbiting camera, hull from the box's projected
//! corners, 84 × 14 px labels, 800 × 600 frame. Prints the median and 90th percentile of many runs,
//! from scratch (no previous layout) and per animation frame (from the previous 1° step).
//!
//! `cargo run --release -p hatchery-annotation --example bench_layout`
//!
//! Measured on the 2-core development machine (shared, so ±40 % between runs): from scratch
//! median 0.36–0.37 ms (90 % 0.63–0.64 ms; 85 iterations, all 30 labels shown), from the previous
//! frame median 0.12 ms. Before step 3 moved by the overlap depth from scratch
//! (`LayoutParams::overlap_shift`), from scratch took 1.3–2.0 ms (311 iterations, 28.9 shown).

use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec2, Vec3};
use hatchery_annotation::{
    Anchor, Layout, LayoutParams, box_corners, layout, project_anchors, project_footprint,
};
use std::time::Instant;

const FRAME: Vec2 = Vec2::new(800.0, 600.0);

fn view_proj(angle_deg: f32) -> Mat4 {
    let a = angle_deg.to_radians();
    let eye = Vec3::new(a.sin(), 0.25, a.cos()).normalize() * 400.0;
    directx::perspective(40f32.to_radians(), FRAME.x / FRAME.y, 10.0, 1000.0)
        * look_at_mat4(eye, Vec3::ZERO, Vec3::Y)
}

/// SplitMix64 in [0, 1).
fn next(state: &mut u64) -> f32 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
}

fn stats(mut ms: Vec<f64>) -> (f64, f64) {
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], ms[ms.len() * 9 / 10])
}

fn main() {
    let mut seed = 0xbe4c_u64;
    let half = Vec3::new(90.0, 70.0, 60.0);
    let anchors: Vec<Anchor> = (0..30)
        .map(|i| Anchor {
            position: Vec3::new(
                next(&mut seed) * 2.0 - 1.0,
                next(&mut seed) * 2.0 - 1.0,
                next(&mut seed) * 2.0 - 1.0,
            ) * half
                * 0.8,
            text: format!("structure {i:02}"),
            object: i as u16,
            priority: 0.0,
        })
        .collect();
    let sizes: Vec<Vec2> = anchors
        .iter()
        .map(|a| Vec2::new(7.0 * a.text.len() as f32, 14.0))
        .collect();
    let corners = box_corners(-half, half);
    let params = LayoutParams::default();

    let (mut scratch, mut animated) = (Vec::new(), Vec::new());
    let (mut shown, mut iterations) = (0usize, 0u64);
    let mut previous: Option<Layout> = None;
    let frames = 360;
    for step in 0..frames {
        let vp = view_proj(step as f32);
        let projected = project_anchors(&anchors, vp, FRAME);
        let footprint = project_footprint(&corners, vp, FRAME);
        let start = Instant::now();
        let fresh = layout(&projected, &sizes, &footprint, FRAME, &params, None);
        scratch.push(start.elapsed().as_secs_f64() * 1e3);
        shown += fresh.shown().count();
        iterations += fresh.iterations as u64;
        let start = Instant::now();
        let next_layout = layout(
            &projected,
            &sizes,
            &footprint,
            FRAME,
            &params,
            previous.as_ref(),
        );
        animated.push(start.elapsed().as_secs_f64() * 1e3);
        previous = Some(next_layout);
    }
    let (m0, p0) = stats(scratch);
    let (m1, p1) = stats(animated);
    println!(
        "layout of 30 labels, {frames} views: from scratch median {m0:.3} ms (90 % {p0:.3} ms, \
         mean {:.0} iterations, {:.1} labels shown); from the previous frame median {m1:.3} ms \
         (90 % {p1:.3} ms)",
        iterations as f64 / frames as f64,
        shown as f64 / frames as f64
    );
}
