//! Smooth label surfaces where the segmentation is coarse (issue 24, item 6): TwoLevelRaycast's
//! `surface_smoothing` shades an object's iso-surface with its mask's gradient averaged over
//! ±h voxels (the 3-D Sobel operator at spacing h) instead of central differences, which turn
//! every slice of a slice-by-slice segmentation into a band of shading (the frog's terraces).
//!
//! Known answer: a ball of radius 14 mm shaded with its exact normals (a smooth field through
//! the radius, normals from the data, on a 0.5 mm grid). The coarse label map has the frog's
//! spacing (1 × 1 × 1.5 mm) and each slice's disc radius off by up to ±0.7 mm, as a segmenter
//! working slice by slice leaves it. Seen from the side (slices as horizontal bands), inside the
//! disc (the outer 20 % of the radius left out, where the outlines differ), the RMS luminance
//! difference to the exact shading falls from 0.101 with central differences to 0.044 with
//! h = 2 (asserted: below half); on a finely segmented ball from 0.091 (voxel stairs) to 0.035
//! (asserted: no worse). SelectionRender's `surface_smoothing` shades the selection with its
//! mask's smoothed gradient instead of the data's (a label map given as the data): 0.098 with the
//! data's gradient, 0.047 with h = 2.

mod common;

use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{
    Compositing, Labels, ObjectStyle, RenderMode, TransferFunction, Volume,
};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const SIZE: u32 = 96;
const RADIUS: f32 = 14.0;
const HALF_WIDTH: f32 = 18.0;

/// Label 1 inside the ball (radius `RADIUS` + `jitter(slice)`), on a grid of `spacing` mm
/// centred at the origin, 36 mm across; data 100 · id, or with `smooth_data` a ramp through 50
/// at the radius (its gradient: the exact normal).
fn ball(
    spacing: [f64; 3],
    jitter: impl Fn(u32) -> f32,
    smooth_data: bool,
) -> (VolumeData, LabelData) {
    let dims = spacing.map(|s| (36.0 / s).round() as u32 + 1);
    let origin = [0, 1, 2].map(|a| -f64::from(dims[a] - 1) * spacing[a] / 2.0);
    let mut ids = Vec::new();
    let mut values = Vec::new();
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let p = Vec3::new(
                    (origin[0] + x as f64 * spacing[0]) as f32,
                    (origin[1] + y as f64 * spacing[1]) as f32,
                    (origin[2] + z as f64 * spacing[2]) as f32,
                );
                let id = u16::from(p.length() < RADIUS + jitter(z));
                ids.push(id);
                values.push(if smooth_data {
                    (50.0 + 10.0 * (RADIUS - p.length())).clamp(0.0, 100.0)
                } else {
                    100.0 * f32::from(id)
                });
            }
        }
    }
    let geometry = Geometry::axis_aligned(spacing, origin);
    let volume = VolumeData::with_geometry(dims, geometry, values).unwrap();
    (volume, LabelData::new(dims, geometry, ids))
}

/// Each slice's radius off by up to ±0.7 mm, differently from slice to slice.
fn slice_jitter(z: u32) -> f32 {
    0.7 * ((z as f32 * 2.39).sin() * 0.6 + (z as f32 * 5.17).cos() * 0.4)
}

/// Orthographic from the side (+x), the ball filling most of the frame.
fn side_camera() -> Camera {
    let fov = 2.0 * (HALF_WIDTH / 60.0).atan().to_degrees();
    Camera::orbit(
        Vec3::ZERO,
        90.0,
        0.0,
        60.0,
        fov,
        true,
        0.05,
        200.0,
        false,
        SIZE,
        SIZE,
    )
}

/// Opaque (or `alpha`) light grey for every value.
fn grey(alpha: f32) -> TransferFunction1D {
    let rgba = [0.8, 0.8, 0.8, alpha];
    TransferFunction1D::from_points(&[
        ControlPoint { value: 0.0, rgba },
        ControlPoint { value: 100.0, rgba },
    ])
    .unwrap()
}

/// Luminance and coverage of each pixel of a rendered picture (no GPU errors on the way).
fn luminance(session: &mut Session, picture: &Value) -> Vec<(f32, f32)> {
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let a = export::to_array(picture, &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2], c[3]))
        .collect()
}

/// Luminance and coverage per pixel of TwoLevelRaycast drawing the ball as a shaded
/// iso-surface (iso 50 of the data, normals from the mask), orthographic from the side.
fn render(
    session: &mut Session,
    (volume, labels): &(VolumeData, LabelData),
    normals: &str,
    smoothing: f64,
) -> Vec<(f32, f32)> {
    let camera = side_camera();
    let style = ObjectStyle {
        id: 1,
        name: "ball".into(),
        enabled: true,
        tf: grey(1.0),
        mode: RenderMode::Iso,
        compositing: Compositing::Iso,
        iso: 50.0,
        importance: 1.0,
    };
    let out = common::run_node(
        session,
        "TwoLevelRaycast",
        vec![
            (
                "volume",
                Value::Volume(Arc::new(Volume::new(volume.clone()))),
            ),
            (
                "labels",
                Value::Labels(Arc::new(Labels::new(labels.clone()))),
            ),
            ("styles", Value::ObjectStyles(Arc::new(vec![style]))),
            ("camera", Value::Camera(Arc::new(camera))),
        ],
        &[
            ("normals", ParamValue::Choice(normals.into())),
            ("surface_smoothing", ParamValue::Float(smoothing)),
            ("step", ParamValue::Float(0.37)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    luminance(session, &out[0])
}

/// Luminance and coverage per pixel of SelectionRender drawing the ball as the selection (in
/// place, opaque grey, lit), with the selection mask's smoothed gradient where `smoothing` > 0.
fn render_selection(
    session: &mut Session,
    (volume, labels): &(VolumeData, LabelData),
    smoothing: f64,
) -> Vec<(f32, f32)> {
    let camera = side_camera();
    let tf = |alpha| Value::TransferFunction(Arc::new(TransferFunction::Color(grey(alpha))));
    let out = common::run_node(
        session,
        "SelectionRender",
        vec![
            (
                "volume",
                Value::Volume(Arc::new(Volume::new(volume.clone()))),
            ),
            (
                "labels",
                Value::Labels(Arc::new(Labels::new(labels.clone()))),
            ),
            ("camera", Value::Camera(Arc::new(camera))),
            ("tf", tf(0.0)),
            ("tf_ghost", tf(0.0)),
            ("tf_selection", tf(1.0)),
        ],
        &[
            ("objects", ParamValue::Text("1".into())),
            ("surface_smoothing", ParamValue::Float(smoothing)),
            ("step", ParamValue::Float(0.37)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    luminance(session, &out[0])
}

/// RMS luminance difference inside 80 % of the ball's projected radius, where both cover.
fn rms_inside(a: &[(f32, f32)], b: &[(f32, f32)]) -> f32 {
    let pixels_per_mm = SIZE as f32 / (2.0 * HALF_WIDTH);
    let limit = 0.8 * RADIUS * pixels_per_mm;
    let (mut sum, mut n) = (0.0, 0);
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        let x = (i as u32 % SIZE) as f32 + 0.5 - SIZE as f32 / 2.0;
        let y = (i as u32 / SIZE) as f32 + 0.5 - SIZE as f32 / 2.0;
        if x.hypot(y) < limit && p.1 > 0.99 && q.1 > 0.99 {
            sum += (p.0 - q.0).powi(2);
            n += 1;
        }
    }
    assert!(n > 1000, "only {n} pixels inside the disc");
    (sum / n as f32).sqrt()
}

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

#[test]
fn smoothed_normals_remove_the_terraces_of_a_slice_by_slice_segmentation() {
    let mut session = session();
    // The reference: the ball shaded with the exact normals (a smooth field's gradient).
    let exact = ball([0.5; 3], |_| 0.0, true);
    let reference = render(&mut session, &exact, "data", 0.0);
    let coarse = ball([1.0, 1.0, 1.5], slice_jitter, false);
    let terraced = rms_inside(&render(&mut session, &coarse, "objects", 0.0), &reference);
    let smoothed = rms_inside(&render(&mut session, &coarse, "objects", 2.0), &reference);
    let fine = ball([0.5; 3], |_| 0.0, false);
    let fine_plain = rms_inside(&render(&mut session, &fine, "objects", 0.0), &reference);
    let fine_smoothed = rms_inside(&render(&mut session, &fine, "objects", 2.0), &reference);
    println!(
        "RMS to the exact shading: coarse, central differences {terraced:.3}, h = 2 \
         {smoothed:.3}; fine, {fine_plain:.3} and {fine_smoothed:.3}"
    );
    assert!(
        smoothed < 0.5 * terraced,
        "h = 2 leaves {smoothed:.3} of the terraces' {terraced:.3}"
    );
    assert!(
        fine_smoothed <= fine_plain,
        "h = 2 moves a finely segmented surface away from the exact shading: \
         {fine_smoothed:.3} vs {fine_plain:.3}"
    );
}

#[test]
fn smoothing_applies_only_to_normals_from_the_masks() {
    let mut session = session();
    let coarse = ball([1.0, 1.0, 1.5], slice_jitter, false);
    assert_eq!(
        render(&mut session, &coarse, "data", 0.0),
        render(&mut session, &coarse, "data", 2.0),
        "with normals from the data, surface_smoothing changes nothing"
    );
}

#[test]
fn the_selection_of_a_slice_by_slice_label_map_is_shaded_smooth() {
    let mut session = session();
    // The reference: a smooth field's gradient (normals from the data, no smoothing).
    let reference = render_selection(&mut session, &ball([0.5; 3], |_| 0.0, true), 0.0);
    let coarse = ball([1.0, 1.0, 1.5], slice_jitter, false);
    let terraced = rms_inside(&render_selection(&mut session, &coarse, 0.0), &reference);
    let smoothed = rms_inside(&render_selection(&mut session, &coarse, 2.0), &reference);
    println!(
        "SelectionRender, RMS to the exact shading: data gradient {terraced:.3}, h = 2 {smoothed:.3}"
    );
    assert!(
        smoothed < 0.5 * terraced,
        "h = 2 leaves {smoothed:.3} of the terraces' {terraced:.3}"
    );
}
