//! ExplodedView (Viola et al., Vis 2005 tutorial §3, volume splitting) on an exploded pair of
//! boxes whose displaced silhouettes are known: a red box in front of a blue one on a grid with
//! a flipped x axis, anisotropic spacing and an offset origin, seen orthographically along −z
//! with one pixel per world unit and pixel centres on voxel centres (so every footprint edge
//! lies half a pixel from the nearest pixel centre). Each part's footprint must be the original
//! one shifted by its displacement, pixel for pixel; nothing may be drawn where parts left; the
//! box behind must show where the front one hid it; with all displacements 0 the picture must
//! be TwoLevelRaycast's within 1/255; guides are drawn along each part's move only.

mod common;

use common::images::{Pixel, assert_images_close};
use glam::{Vec2, Vec3, Vec4};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Compositing, Labels, ObjectStyle, RenderMode, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 48;
const SIZE: u32 = 64;
const STEP: f32 = 0.37;
/// The front box (id 1, red) and the box behind it (id 2, blue): inclusive voxel ranges.
const FRONT: ([u32; 3], [u32; 3]) = ([12, 14, 30], [27, 33, 41]);
const BACK: ([u32; 3], [u32; 3]) = ([20, 18, 6], [35, 29, 17]);
const RED: [f32; 4] = [1.0, 0.0, 0.0, 1.0];
const BLUE: [f32; 4] = [0.0, 0.0, 1.0, 1.0];

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// x flipped (world x = 23 − i), y = j − 24, z = 1.5 k − 30.
fn geometry() -> Geometry {
    Geometry::from_affine([
        [-1.0, 0.0, 0.0, 23.0],
        [0.0, 1.0, 0.0, -24.0],
        [0.0, 0.0, 1.5, -30.0],
    ])
    .unwrap()
}

fn scene() -> (VolumeData, LabelData) {
    let inside = |(lo, hi): ([u32; 3], [u32; 3]), v: [u32; 3]| {
        (0..3).all(|a| (lo[a]..=hi[a]).contains(&v[a]))
    };
    let mut ids = Vec::new();
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                ids.push(if inside(FRONT, [x, y, z]) {
                    1
                } else if inside(BACK, [x, y, z]) {
                    2
                } else {
                    0
                });
            }
        }
    }
    let values = ids.iter().map(|&id| 100.0 * f32::from(id)).collect();
    let volume = VolumeData::with_geometry([N; 3], geometry(), values).unwrap();
    let mut labels = LabelData::new([N; 3], geometry(), ids);
    labels.objects = [(1, "front".to_owned()), (2, "back".to_owned())].into();
    (volume, labels)
}

fn flat(rgba: [f32; 4]) -> TransferFunction1D {
    TransferFunction1D::from_points(&[
        ControlPoint { value: 0.0, rgba },
        ControlPoint { value: 300.0, rgba },
    ])
    .unwrap()
}

fn style(id: u16, rgba: [f32; 4], mode: RenderMode) -> ObjectStyle {
    ObjectStyle {
        id,
        name: format!("object {id}"),
        enabled: true,
        tf: flat(rgba),
        mode,
        compositing: Compositing::Over,
        iso: 0.0,
        importance: 1.0,
    }
}

/// Orthographic along −z, 64 world units across 64 pixels, pixel centres at whole world x, y.
fn camera(session: &mut Session) -> Camera {
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let half_width = SIZE as f32 / 2.0;
    let fov = 2.0 * (half_width / 60.0).atan().to_degrees();
    Camera::orbit(
        Vec3::new(0.5, 0.5, 0.0),
        0.0,
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

fn inputs(
    cam: &Camera,
    volume: &VolumeData,
    labels: &LabelData,
    styles: Vec<ObjectStyle>,
) -> Vec<(&'static str, Value)> {
    vec![
        (
            "volume",
            Value::Volume(Arc::new(Volume::new(volume.clone()))),
        ),
        (
            "labels",
            Value::Labels(Arc::new(Labels::new(labels.clone()))),
        ),
        ("styles", Value::ObjectStyles(Arc::new(styles))),
        ("camera", Value::Camera(Arc::new(cam.clone()))),
    ]
}

fn pixels_of(session: &Session, value: &Value) -> Vec<[f32; 4]> {
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let a = export::to_array(value, &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// ExplodedView's image; `extra` parameters over jitter off and the test's step.
fn exploded(
    session: &mut Session,
    cam: &Camera,
    styles: Vec<ObjectStyle>,
    parts: &str,
    extra: &[(&str, ParamValue)],
) -> Vec<[f32; 4]> {
    let (volume, labels) = scene();
    let mut params = vec![
        ("parts", ParamValue::Text(parts.into())),
        ("step", ParamValue::Float(STEP as f64)),
        ("jitter", ParamValue::Bool(false)),
        ("guides", ParamValue::Bool(false)),
    ];
    params.extend(extra.iter().cloned());
    let out = common::run_node(
        session,
        "ExplodedView",
        inputs(cam, &volume, &labels, styles),
        &params,
    );
    pixels_of(session, &out[0])
}

/// The world (x, y) of pixel i's centre.
fn pixel_world(cam: &Camera, i: usize) -> Vec2 {
    let (c, r) = ((i as u32 % SIZE) as f32, (i as u32 / SIZE) as f32);
    let ndc = Vec4::new(
        (c + 0.5) / SIZE as f32 * 2.0 - 1.0,
        1.0 - (r + 0.5) / SIZE as f32 * 2.0,
        0.5,
        1.0,
    );
    let p = cam.view_proj().inverse() * ndc;
    Vec2::new(p.x / p.w, p.y / p.w)
}

/// A world rectangle (x0, x1, y0, y1) on screen.
type Rect = [f32; 4];

/// The world footprint of voxels lo..=hi (their cells: ± half a voxel), the x and y range of
/// the voxel box's corners.
fn footprint((lo, hi): ([u32; 3], [u32; 3])) -> Rect {
    let g = geometry();
    let a = g.voxel_to_world(Vec3::from(lo.map(|v| v as f32)) - 0.5);
    let b = g.voxel_to_world(Vec3::from(hi.map(|v| v as f32)) + 0.5);
    [a.x.min(b.x), a.x.max(b.x), a.y.min(b.y), a.y.max(b.y)]
}

fn shifted(r: Rect, dx: f32, dy: f32) -> Rect {
    [r[0] + dx, r[1] + dx, r[2] + dy, r[3] + dy]
}

/// `r` cut to x ≥ at (keep = 1) or x < at (keep = −1) along axis 0 (x) or 1 (y).
fn cut(r: Rect, axis: usize, at: f32, keep: f32) -> Rect {
    let mut r = r;
    if keep > 0.0 {
        r[2 * axis] = r[2 * axis].max(at);
    } else {
        r[2 * axis + 1] = r[2 * axis + 1].min(at);
    }
    r
}

fn covers(r: &Rect, p: Vec2) -> bool {
    p.x > r[0] && p.x < r[1] && p.y > r[2] && p.y < r[3]
}

/// The picture the parts must make: red where a red rectangle covers the pixel centre (the red
/// box is in front), else blue where a blue one does, else nothing.
fn expected(cam: &Camera, red: &[Rect], blue: &[Rect]) -> Vec<[f32; 4]> {
    (0..(SIZE * SIZE) as usize)
        .map(|i| {
            let p = pixel_world(cam, i);
            if red.iter().any(|r| covers(r, p)) {
                RED
            } else if blue.iter().any(|r| covers(r, p)) {
                BLUE
            } else {
                [0.0; 4]
            }
        })
        .collect()
}

fn opaque_styles() -> Vec<ObjectStyle> {
    vec![
        style(1, RED, RenderMode::Dvr),
        style(2, BLUE, RenderMode::Dvr),
    ]
}

/// Every pixel within 1/255 of the expected picture; pixel centres lie half a voxel from every
/// footprint edge, so no edge pixel is excused.
fn assert_picture(name: &str, got: &[[f32; 4]], want: &[[f32; 4]]) {
    assert_images_close(name, got, want, SIZE, 1.0 / 255.0);
}

#[test]
fn unmoved_parts_render_as_two_level_raycast() {
    let mut session = session();
    let cam = camera(&mut session);
    let (volume, labels) = scene();
    // Translucent, shaded and toned: every sample counts, none terminates a ray early.
    let styles = vec![
        style(1, [1.0, 0.4, 0.2, 0.08], RenderMode::ShadedDvr),
        style(2, [0.2, 0.5, 1.0, 0.15], RenderMode::Tone),
    ];
    let common = [
        ("step", ParamValue::Float(STEP as f64)),
        ("jitter", ParamValue::Bool(false)),
        ("early_termination", ParamValue::Float(1.0)),
    ];
    let out = common::run_node(
        &mut session,
        "TwoLevelRaycast",
        inputs(&cam, &volume, &labels, styles.clone()),
        &common,
    );
    let want = pixels_of(&session, &out[0]);
    assert!(
        want.iter().filter(|p| p[3] > 0.05).count() > 200,
        "the reference shows the boxes"
    );
    for parts in [
        "front: move 0 0 0; back: move 0 0 0",
        "front: split x 0",
        "volume: split y 0",
        "volume: move 0 0 0",
    ] {
        let mut extra = common.to_vec();
        extra.push(("guides", ParamValue::Bool(true)));
        let got = exploded(&mut session, &cam, styles.clone(), parts, &extra);
        let d = common::images::diff_images(&got, &want, SIZE, |_| true, 1.0 / 255.0);
        eprintln!(
            "`{parts}`: worst channel difference {:.2e} at ({}, {})",
            d.worst, d.x, d.y
        );
        assert_images_close(
            &format!("exploded `{parts}` vs two-level"),
            &got,
            &want,
            SIZE,
            1.0 / 255.0,
        );
    }
}

#[test]
fn moved_footprints_are_the_original_ones_shifted() {
    let mut session = session();
    let cam = camera(&mut session);
    let (front, back) = (footprint(FRONT), footprint(BACK));
    // Sanity of the scene: the front box hides part of the back one.
    let unmoved = exploded(&mut session, &cam, opaque_styles(), "", &[]);
    assert_picture("unmoved", &unmoved, &expected(&cam, &[front], &[back]));

    // The front box moved 26 right (partly beyond the grid) and 6 down; the back box stays.
    let got = exploded(
        &mut session,
        &cam,
        opaque_styles(),
        "front: move 26 -6 0",
        &[],
    );
    let moved = shifted(front, 26.0, -6.0);
    assert_picture("front moved", &got, &expected(&cam, &[moved], &[back]));
    // Where the front box was: nothing, except the back box, now uncovered.
    let mut uncovered = 0;
    for (i, p) in got.iter().enumerate() {
        let w = pixel_world(&cam, i);
        if covers(&front, w) && !covers(&moved, w) {
            if covers(&back, w) {
                assert!(p.difference(BLUE) <= 1.0 / 255.0, "pixel {i}: {p:?}");
                if unmoved[i].difference(RED) <= 1.0 / 255.0 {
                    uncovered += 1;
                }
            } else {
                assert!(p[3] <= 1.0 / 255.0, "pixel {i} where the box left: {p:?}");
            }
        }
    }
    assert!(
        uncovered >= 80,
        "{uncovered} hidden pixels of the back box uncovered"
    );

    // Logical splitting: the front box's halves either side of x = its centre moved ±6 along
    // x, the back box showing through the gap; the back box moved too (in world y).
    let centre_x = (front[0] + front[1]) / 2.0;
    let got = exploded(
        &mut session,
        &cam,
        opaque_styles(),
        "front: split x 6; 2: move 0 3 0",
        &[],
    );
    let red = [
        shifted(cut(front, 0, centre_x, 1.0), 6.0, 0.0),
        shifted(cut(front, 0, centre_x, -1.0), -6.0, 0.0),
    ];
    assert_picture(
        "front split",
        &got,
        &expected(&cam, &red, &[shifted(back, 0.0, 3.0)]),
    );

    // Geometrical splitting: both boxes cut by the plane y = centre of all labelled voxels,
    // the halves moved ±8 along y.
    let centre_y = -0.5; // both boxes' voxels are centred on j = 23.5
    let got = exploded(
        &mut session,
        &cam,
        opaque_styles(),
        "volume: split y 8",
        &[],
    );
    let halves = |r: Rect| {
        [
            shifted(cut(r, 1, centre_y, 1.0), 0.0, 8.0),
            shifted(cut(r, 1, centre_y, -1.0), 0.0, -8.0),
        ]
    };
    assert_picture(
        "volume split",
        &got,
        &expected(&cam, &halves(front), &halves(back)),
    );

    // Order: the back box moved onto the front one's place in depth and x, the front box
    // named first keeps the shared samples.
    let got = exploded(
        &mut session,
        &cam,
        opaque_styles(),
        "front: move 0 0 0; back: move 0 0 36",
        &[],
    );
    assert_picture("overlap", &got, &expected(&cam, &[front], &[back]));
}

#[test]
fn guides_run_from_each_original_centre_to_the_moved_one() {
    let mut session = session();
    let cam = camera(&mut session);
    let parts = "front: move 20 -10 0";
    let plain = exploded(&mut session, &cam, opaque_styles(), parts, &[]);
    let width = 1.5;
    let guided = exploded(
        &mut session,
        &cam,
        opaque_styles(),
        parts,
        &[
            ("guides", ParamValue::Bool(true)),
            ("guide_width", ParamValue::Float(width)),
        ],
    );
    let f = footprint(FRONT);
    let from = Vec2::new((f[0] + f[1]) / 2.0, (f[2] + f[3]) / 2.0);
    let to = from + Vec2::new(20.0, -10.0);
    // The head is 3 × width + 6 px long and as wide; the dot 1.5 × width + 1 in radius.
    let reach = (3.0 * width as f32 + 6.0) / 2.0 + 1.5;
    let (mut changed, mut far) = (0, Vec::new());
    for i in 0..plain.len() {
        if plain[i].difference(guided[i]) > 1.0 / 255.0 {
            changed += 1;
            let p = pixel_world(&cam, i);
            let t = ((p - from).dot(to - from) / (to - from).length_squared()).clamp(0.0, 1.0);
            if p.distance(from + (to - from) * t) > reach {
                far.push(i);
            }
        }
    }
    assert!(
        changed >= 22,
        "only {changed} pixels of guide along a 22 px move"
    );
    assert!(far.is_empty(), "guide pixels away from the move: {far:?}");
}

#[test]
fn a_part_that_does_not_parse_is_named() {
    let mut session = session();
    let cam = camera(&mut session);
    // run_node panics with the node's error.
    let failed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let parts = "front: move 1 2; back: move 0 0 1";
        exploded(&mut session, &cam, opaque_styles(), parts, &[])
    }));
    let text = *failed.expect_err("an error").downcast::<String>().unwrap();
    assert!(
        text.contains("parameter `parts`: part `front: move 1 2`"),
        "{text}"
    );
}
