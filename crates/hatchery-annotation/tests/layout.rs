//! Property tests of the §6.4 layout over many random label sets, and temporal coherence under a
//! small camera orbit. The checks use the independent geometry of `common`, not the crate's own.

mod common;

use common::{FRAME, Rng, Scene, box_hits_polygon, boxes_overlap, cross_f64, random_scene};
use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec2, Vec3};
use hatchery_annotation::{
    Anchor, Layout, LayoutParams, ProjectedAnchor, box_corners, convex_hull, layout,
    project_anchors, project_footprint,
};

/// Checks the §6.4 guidelines on a layout; returns (shown, visible) counts.
fn check(scene: &Scene, result: &Layout, case: usize) -> (usize, usize) {
    let hull = convex_hull(&scene.hull_points);
    let shown: Vec<_> = result.shown().collect();
    for l in &shown {
        assert!(
            scene.anchors[l.anchor].visible,
            "case {case}: invisible anchor shown"
        );
        assert!(
            (l.rect.size() - scene.sizes[l.anchor]).length() < 1e-3,
            "case {case}: label size changed"
        );
        assert!(
            !box_hits_polygon((l.rect.min, l.rect.max), &hull),
            "case {case}: label {} inside the hull: {:?}",
            l.anchor,
            l.rect
        );
        assert_eq!(l.leader[0], scene.anchors[l.anchor].screen);
        assert!((0.0..=1.0).contains(&l.opacity));
    }
    for (k, a) in shown.iter().enumerate() {
        for b in &shown[k + 1..] {
            assert!(
                !boxes_overlap((a.rect.min, a.rect.max), (b.rect.min, b.rect.max)),
                "case {case}: labels {} and {} overlap",
                a.anchor,
                b.anchor
            );
            assert!(
                !cross_f64(a.leader[0], a.leader[1], b.leader[0], b.leader[1]),
                "case {case}: leaders {} and {} cross",
                a.anchor,
                b.anchor
            );
        }
    }
    let visible = scene.anchors.iter().filter(|a| a.visible).count();
    for l in result
        .labels
        .iter()
        .filter(|l| !scene.anchors[l.anchor].visible)
    {
        assert!(!l.shown && l.opacity == 0.0);
    }
    (shown.len(), visible)
}

#[test]
fn random_layouts_meet_the_guidelines() {
    let mut rng = Rng::new(0x5eed_1abe);
    let params = LayoutParams::default();
    let cases = 1200;
    let (mut shown, mut visible, mut inside_frame) = (0usize, 0usize, 0usize);
    let (mut iterations, mut max_iterations, mut swaps) = (0u64, 0u32, 0u64);
    let mut worst = 0.0f32;
    for case in 0..cases {
        let scene = random_scene(&mut rng);
        let result = layout(
            &scene.anchors,
            &scene.sizes,
            &scene.hull_points,
            FRAME,
            &params,
            None,
        );
        let (s, v) = check(&scene, &result, case);
        shown += s;
        visible += v;
        inside_frame += result.shown().filter(|l| l.inside_frame).count();
        iterations += result.iterations as u64;
        max_iterations = max_iterations.max(result.iterations);
        swaps += result.swaps as u64;
        worst = worst.max(1.0 - s as f32 / v.max(1) as f32);
    }
    let disabled = 1.0 - shown as f64 / visible as f64;
    println!(
        "{cases} random layouts of 5–30 labels: {visible} visible labels, {:.2} % disabled \
         (worst case {:.0} %), {:.2} % of shown labels inside the frame, mean {:.1} iterations \
         (max {max_iterations}), mean {:.1} swaps",
        100.0 * disabled,
        100.0 * worst,
        100.0 * inside_frame as f64 / shown as f64,
        iterations as f64 / cases as f64,
        swaps as f64 / cases as f64,
    );
    // Bound: at most 10 % of the visible labels disabled over the whole set.
    assert!(disabled < 0.10, "disabled fraction {disabled}");
}

#[test]
fn priority_keeps_labels_longer() {
    // Two labels that cannot both fit without a conflict get decided by priority before depth.
    let mut rng = Rng::new(7);
    let mut kept_high = 0;
    let mut decided = 0;
    for _ in 0..300 {
        let mut scene = random_scene(&mut rng);
        for (i, a) in scene.anchors.iter_mut().enumerate() {
            a.priority = if i % 2 == 0 { 1.0 } else { 0.0 };
        }
        let result = layout(
            &scene.anchors,
            &scene.sizes,
            &scene.hull_points,
            FRAME,
            &LayoutParams::default(),
            None,
        );
        for l in &result.labels {
            if scene.anchors[l.anchor].visible && !l.shown {
                decided += 1;
                kept_high += usize::from(l.anchor % 2 == 1);
            }
        }
    }
    println!("disabled labels of low priority: {kept_high} of {decided}");
    assert!(decided == 0 || kept_high * 10 >= decided * 9);
}

fn orbit_view_proj(angle_deg: f32) -> Mat4 {
    let a = angle_deg.to_radians();
    let eye = Vec3::new(a.sin(), 0.25, a.cos()).normalize() * 400.0;
    let view = look_at_mat4(eye, Vec3::ZERO, Vec3::Y);
    let proj = directx::perspective(40f32.to_radians(), FRAME.x / FRAME.y, 10.0, 1000.0);
    proj * view
}

#[test]
fn small_orbit_moves_labels_little() {
    // A 3-D anchor set in a box of ±90 × 70 × 60 mm (the hull: the box's projected corners), the
    // camera 400 mm away orbiting 1° per frame for a full turn, each frame laid out from the
    // previous one; four sets of 12–24 labels. Anchors move about 1–4 px per frame, the box's
    // silhouette up to about 5 px. A label shown in two consecutive frames that took no part in a
    // swap (and with no label shown or hidden in between) must move at most `MAX_MOVE` px, 99 %
    // of them at most `P99_MOVE` px; in frames where other labels swapped, a neighbour may have to
    // make room for them: such larger moves are counted and must stay under 1 in 1000.
    const MAX_MOVE: f32 = 12.0;
    const P99_MOVE: f32 = 6.0;
    let mut rng = Rng::new(0xc0e4e);
    let params = LayoutParams::default();
    let (mut frames, mut swaps, mut swap_frames) = (0u32, 0u32, 0u32);
    let (mut set_changes, mut repeated) = (0u32, 0u32);
    let mut plain_moves: Vec<f32> = Vec::new();
    // Largest move of a label in a frame without any swap.
    let mut calm_max = 0.0f32;
    let mut anchor_moves: Vec<f32> = Vec::new();
    for scene_index in 0..4 {
        let n = 12 + 4 * scene_index;
        let half = Vec3::new(90.0, 70.0, 60.0);
        let anchors: Vec<Anchor> = (0..n)
            .map(|i| Anchor {
                position: Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                ) * half
                    * 0.8,
                text: format!("structure {i}"),
                object: i as u16,
                priority: 0.0,
            })
            .collect();
        let sizes: Vec<Vec2> = anchors
            .iter()
            .map(|a| Vec2::new(7.0 * a.text.len() as f32, 14.0))
            .collect();
        let corners = box_corners(-half, half);
        let mut previous: Option<(Layout, Vec<ProjectedAnchor>)> = None;
        for step in 0..360 {
            let vp = orbit_view_proj(step as f32);
            let projected = project_anchors(&anchors, vp, FRAME);
            let footprint = project_footprint(&corners, vp, FRAME);
            let prev_layout = previous.as_ref().map(|(l, _)| l);
            let result = layout(&projected, &sizes, &footprint, FRAME, &params, prev_layout);
            frames += 1;
            swaps += result.swaps;
            swap_frames += u32::from(result.swaps > 0);
            if let Some((prev, prev_anchors)) = &previous {
                let set_changed = prev
                    .labels
                    .iter()
                    .zip(&result.labels)
                    .any(|(a, b)| a.shown != b.shown);
                set_changes += u32::from(set_changed);
                for (a, b) in prev.labels.iter().zip(&result.labels) {
                    repeated += u32::from(a.swapped && b.swapped);
                    if a.shown && b.shown && !b.swapped && !set_changed {
                        let moved = a.rect.center().distance(b.rect.center());
                        if result.swaps == 0 {
                            calm_max = calm_max.max(moved);
                        }
                        plain_moves.push(moved);
                        anchor_moves.push(
                            prev_anchors[a.anchor]
                                .screen
                                .distance(projected[a.anchor].screen),
                        );
                    }
                }
            }
            previous = Some((result, projected));
        }
    }
    plain_moves.sort_by(f32::total_cmp);
    anchor_moves.sort_by(f32::total_cmp);
    let pct = |v: &[f32], q: f64| v[((v.len() - 1) as f64 * q) as usize];
    println!(
        "orbit: {frames} frames of 1°; {swaps} swaps in {swap_frames} frames ({repeated} labels \
         swapping in two consecutive frames), {set_changes} frames where the shown set changed; \
         {} label moves without swap: median {:.2} px, 99 % {:.2} px, max {:.2} px (in frames \
         without any swap {calm_max:.2} px) (anchors: median {:.2} px, max {:.2} px)",
        plain_moves.len(),
        pct(&plain_moves, 0.5),
        pct(&plain_moves, 0.99),
        pct(&plain_moves, 1.0),
        pct(&anchor_moves, 0.5),
        pct(&anchor_moves, 1.0),
    );
    assert!(calm_max <= MAX_MOVE);
    // In frames with a swap, neighbours making room may jump further (the issue excepts swaps):
    // count those jumps; they stay rare.
    let jumps = plain_moves.iter().filter(|&&m| m > MAX_MOVE).count();
    println!("moves over {MAX_MOVE} px (all in frames with a swap): {jumps}");
    assert!(
        jumps * 1000 <= plain_moves.len(),
        "{jumps} jumps over {MAX_MOVE} px"
    );
    assert!(pct(&plain_moves, 0.99) <= P99_MOVE);
    // Anchors pass each other on screen while the object turns, and each pass is a swap: bound
    // one swap every two frames, and few labels swapping back and forth.
    assert!(swaps <= frames / 2, "{swaps} swaps in {frames} frames");
    assert!(
        repeated <= frames / 50,
        "{repeated} labels swapped in consecutive frames"
    );
    assert!(set_changes <= frames / 50);
}
