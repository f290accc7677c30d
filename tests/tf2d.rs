//! 2-D transfer functions (Kniss et al. 2002; Svakhine, Jang, Ebert & Gaither 2005 §3.3):
//! `TransferFunction2D` into `Raycast`'s `tf`, classifying DVR samples by value × normalised
//! gradient magnitude or value × Laplacian. Checked on axis-aligned columns of constant value and
//! gradient against closed forms, against the same picture under a 1-D transfer function, and
//! against the CPU reference ray caster (tests/common/raycast_reference.rs, `render_2d`).

mod common;

use common::ray_columns::{
    assert_matches, column_alpha, columns, on_columns, raycast_image, reference_params,
};
use common::raycast_reference::{self as reference, Enhancement, Shading};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_data::transfer_function_2d::{SecondAxis, TransferFunction2D, parse_widgets};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{TransferFunction, Volume};
use hatchery_nodes::{Session, Value};
use std::sync::Arc;

struct Scene {
    session: Session,
    volume: Arc<Volume>,
    data: VolumeData,
    camera: Camera,
}

impl Scene {
    fn new(data: VolumeData, camera: Camera) -> Self {
        let session = common::ray_columns::session_for(&camera);
        Self {
            session,
            volume: Arc::new(Volume::new(data.clone())),
            data,
            camera,
        }
    }

    /// The `TransferFunction2D` node's output for these parameters.
    fn tf2d(&mut self, axis: &str, value: [f32; 2], second: [f32; 2], widgets: &str) -> Value {
        let f = |x: f32| ParamValue::Float(x.into());
        let out = common::run_node(
            &mut self.session,
            "TransferFunction2D",
            vec![],
            &[
                ("axis", ParamValue::Choice(axis.into())),
                ("value_min", f(value[0])),
                ("value_max", f(value[1])),
                ("second_min", f(second[0])),
                ("second_max", f(second[1])),
                ("widgets", ParamValue::Text(widgets.into())),
            ],
        );
        out.into_iter().next().unwrap()
    }

    /// The Raycast node's image through `tf` (see `raycast_image`).
    fn gpu(
        &mut self,
        tf: Value,
        shading: &str,
        step: f32,
        extra: &[(&str, ParamValue)],
    ) -> Vec<[f32; 4]> {
        let (volume, camera) = (&self.volume, &self.camera);
        raycast_image(&mut self.session, volume, camera, tf, shading, step, extra)
    }

    /// The CPU reference with the same rays (the node's default headlight).
    fn cpu(&self, tf: &TransferFunction2D, shading: Shading, step: f32) -> Vec<[f32; 4]> {
        let p = reference_params(&self.camera, shading, step);
        reference::render_2d(&self.data, tf, &p, Enhancement::default())
    }
}

/// The baked function the node makes (the same parse and bake).
fn baked(axis: SecondAxis, value: [f32; 2], second: [f32; 2], widgets: &str) -> TransferFunction2D {
    TransferFunction2D::new(axis, value, second, &parse_widgets(widgets).unwrap()).unwrap()
}

/// Two ramps over the same values 0 … 240 side by side: slope 10 per voxel for x ≤ 24, then back
/// down at slope 30. Normalised gradient magnitude (the largest is 30): 1/3 on the shallow ramp, 1
/// on the steep one.
fn two_slopes(x: u32) -> f32 {
    let x = x as f32;
    if x <= 24.0 {
        10.0 * x
    } else {
        240.0 - 30.0 * (x - 24.0)
    }
}
const W: u32 = 33;
/// Columns whose central differences lie inside one slope.
const SHALLOW: std::ops::RangeInclusive<u32> = 1..=23;
const STEEP: std::ops::RangeInclusive<u32> = 25..=32;

/// A widget selecting high gradient magnitude (0.5 … 1) over every value shows only the steep
/// ramp, each column compositing α = 1 − (1 − 0.2)^16 (closed form within 10⁻³); the shallow ramp
/// stays exactly transparent. GPU = CPU reference.
#[test]
fn high_gradient_widget_shows_only_the_steep_ramp() {
    let (h, d) = (2u32, 16u32);
    let mut scene = Scene::new(columns(W, h, d, two_slopes), on_columns(W, h));
    let widgets = "rect 0..255 x 0.5..1: 1 0.5 0.25 0.2";
    let tf = scene.tf2d("gradient_magnitude", [0.0, 255.0], [0.0, 1.0], widgets);
    let gpu = scene.gpu(tf, "none", 1.0, &[]);
    let reference_tf = baked(
        SecondAxis::GradientMagnitude,
        [0.0, 255.0],
        [0.0, 1.0],
        widgets,
    );
    assert_matches(
        "high gradient",
        &gpu,
        &scene.cpu(&reference_tf, Shading::None, 1.0),
        W,
    );
    let alpha = column_alpha(0.2, d);
    let mut worst = 0.0f32;
    for row in 0..h {
        for x in STEEP {
            let got = gpu[(row * W + x) as usize];
            let want = [alpha, alpha * 0.5, alpha * 0.25, alpha];
            for k in 0..4 {
                worst = worst.max((got[k] - want[k]).abs());
            }
            assert!(
                (0..4).all(|k| (got[k] - want[k]).abs() <= 1e-3),
                "steep column {x}: GPU {got:?}, closed form {want:?}"
            );
        }
        for x in SHALLOW {
            let got = gpu[(row * W + x) as usize];
            assert_eq!(got, [0.0; 4], "shallow column {x} must stay transparent");
        }
    }
    eprintln!("high gradient: worst difference from the closed form {worst:.6} (alpha {alpha})");
}

/// Kniss's triangle (apex at value 120, gradient 0; 240 wide at gradient 1): on the steep ramp
/// (s = 1, half-width 120) a sample of value v has opacity 0.5·(1 − |v − 120|/120); on the
/// shallow one (s = 1/3, half-width 40) only values within 40 of 120 show. Closed form of each
/// column within 0.01 (the table is 256 × 256); GPU = CPU reference; skipping changes nothing.
#[test]
fn triangle_widget_selects_the_boundary_arc() {
    let (h, d) = (2u32, 16u32);
    let mut scene = Scene::new(columns(W, h, d, two_slopes), on_columns(W, h));
    let widgets = "tri 120 x 0..1 width 240: 0.2 0.6 1 0.5";
    let reference_tf = baked(
        SecondAxis::GradientMagnitude,
        [0.0, 255.0],
        [0.0, 1.0],
        widgets,
    );
    let tf = scene.tf2d("gradient_magnitude", [0.0, 255.0], [0.0, 1.0], widgets);
    let gpu = scene.gpu(tf.clone(), "none", 1.0, &[]);
    assert_matches(
        "triangle",
        &gpu,
        &scene.cpu(&reference_tf, Shading::None, 1.0),
        W,
    );
    let unskipped = scene.gpu(tf, "none", 1.0, &[("skip_empty", ParamValue::Bool(false))]);
    assert_eq!(gpu, unskipped, "empty-space skipping changed the picture");
    let mut worst = 0.0f32;
    for x in SHALLOW.chain(STEEP) {
        let v = two_slopes(x);
        let half = if x <= 24 { 40.0 } else { 120.0 };
        let o = 0.5 * (1.0 - (v - 120.0).abs() / half).max(0.0);
        let want = column_alpha(o, d);
        let got = gpu[x as usize][3];
        worst = worst.max((got - want).abs());
        assert!(
            (got - want).abs() <= 0.01,
            "column {x} (value {v}): GPU alpha {got}, closed form {want}"
        );
    }
    eprintln!("triangle: worst alpha difference from the closed form {worst:.6}");
    // The shallow ramp shows only near the boundary value: columns with |v − 120| ≥ 40 are clear.
    assert_eq!(gpu[2][3], 0.0);
    assert!(gpu[12][3] > 0.5);
}

/// A rectangle over the whole second axis is the 1-D transfer function of the same box: the
/// pictures agree within 1/255 (value domains chosen so both tables have the same columns).
#[test]
fn full_height_rect_equals_the_one_dimensional_function() {
    let (h, d) = (2u32, 16u32);
    let mut scene = Scene::new(columns(W, h, d, two_slopes), on_columns(W, h));
    let tf = scene.tf2d(
        "gradient_magnitude",
        [0.0, 255.0],
        [0.0, 1.0],
        "rect 79.5..160.5 x 0..1: 0.9 0.8 0.7 0.3",
    );
    let two_d = scene.gpu(tf, "phong", 0.5, &[]);
    let c = |value: f32, rgba: [f32; 4]| ControlPoint { value, rgba };
    let one_d = TransferFunction1D::from_points(&[
        c(0.0, [0.0; 4]),
        c(79.0, [0.0; 4]),
        c(80.0, [0.9, 0.8, 0.7, 0.3]),
        c(160.0, [0.9, 0.8, 0.7, 0.3]),
        c(161.0, [0.0; 4]),
        c(255.0, [0.0; 4]),
    ])
    .unwrap();
    let one_d = scene.gpu(
        Value::TransferFunction(Arc::new(TransferFunction::Color(one_d))),
        "phong",
        0.5,
        &[],
    );
    let worst = two_d
        .iter()
        .zip(&one_d)
        .flat_map(|(a, b)| (0..4).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0f32, f32::max);
    eprintln!("full-height rect vs 1-D: worst channel difference {worst:.6}");
    assert!(worst <= 1.0 / 255.0, "worst {worst}");
    assert!(two_d.iter().any(|p| p[3] > 0.1));
}

/// A quadratic profile x²/8 (Laplacian 1/4 per voxel²) continued by its tangent line (Laplacian
/// 0): on the Laplacian axis a red widget over 0.1 … 1 selects the quadratic part, a blue one
/// over −0.05 … 0.05 the linear part; closed forms within 10⁻³; GPU = CPU reference.
#[test]
fn laplacian_axis_separates_the_quadratic_from_the_linear_part() {
    let (w, h, d) = (28u32, 2u32, 16u32);
    let f = |x: u32| {
        let x = x as f32;
        if x <= 16.0 {
            x * x / 8.0
        } else {
            32.0 + 4.0 * (x - 16.0)
        }
    };
    let mut scene = Scene::new(columns(w, h, d, f), on_columns(w, h));
    let widgets = "rect 0..80 x 0.1..1: 1 0 0 0.2; rect 0..80 x -0.05..0.05: 0 0 1 0.1";
    let tf = scene.tf2d("laplacian", [0.0, 80.0], [-1.0, 1.0], widgets);
    let gpu = scene.gpu(tf, "none", 1.0, &[]);
    let reference_tf = baked(SecondAxis::Laplacian, [0.0, 80.0], [-1.0, 1.0], widgets);
    assert_matches(
        "laplacian",
        &gpu,
        &scene.cpu(&reference_tf, Shading::None, 1.0),
        w,
    );
    let mut worst = 0.0f32;
    for (columns, rgb, o) in [
        (1..=15u32, [1.0, 0.0, 0.0], 0.2f32),
        (17..=26, [0.0, 0.0, 1.0], 0.1),
    ] {
        let a = column_alpha(o, d);
        for x in columns {
            let got = gpu[x as usize];
            let want = [rgb[0] * a, rgb[1] * a, rgb[2] * a, a];
            for k in 0..4 {
                worst = worst.max((got[k] - want[k]).abs());
            }
            assert!(
                (0..4).all(|k| (got[k] - want[k]).abs() <= 1e-3),
                "column {x}: GPU {got:?}, closed form {want:?}"
            );
        }
    }
    eprintln!("laplacian: worst difference from the closed form {worst:.6}");
}

/// A ball's shell seen obliquely (orthographic, Blinn–Phong, step 0.5) through a triangle
/// widget: GPU = CPU reference within 1/255, with and without empty-space skipping.
#[test]
fn shaded_ball_matches_the_reference() {
    let size = 48u32;
    let data = common::field_on_cube(33, |p| 0.8 - p.length());
    let camera = Camera::orbit(
        Vec3::ZERO,
        30.0,
        20.0,
        4.0,
        2.0 * (1.2f32 / 4.0).atan().to_degrees(),
        true,
        0.05,
        50.0,
        false,
        size,
        size,
    );
    let mut scene = Scene::new(data, camera);
    let widgets =
        "tri 0 x 0..1 width 0.3: 0.9 0.7 0.5 0.6; rect -0.6..-0.3 x 0..1: 0.3 0.4 0.9 0.05";
    let reference_tf = baked(
        SecondAxis::GradientMagnitude,
        [-1.0, 1.0],
        [0.0, 1.0],
        widgets,
    );
    let tf = scene.tf2d("gradient_magnitude", [-1.0, 1.0], [0.0, 1.0], widgets);
    let gpu = scene.gpu(tf.clone(), "phong", 0.5, &[]);
    let cpu = scene.cpu(
        &reference_tf,
        Shading::Phong {
            ambient: 0.15,
            diffuse: 0.85,
            specular: 0.4,
            exponent: 32.0,
        },
        0.5,
    );
    assert_matches("shaded ball", &gpu, &cpu, size);
    let unskipped = scene.gpu(tf, "phong", 0.5, &[("skip_empty", ParamValue::Bool(false))]);
    assert_eq!(gpu, unskipped, "empty-space skipping changed the picture");
}

/// Errors: a widget that does not parse is named; MIP refuses a 2-D function on port `tf`.
#[test]
fn errors_name_the_widget_and_the_port() {
    let e = parse_widgets("rect 0..1 x 0..1: 1 1 1 1; tri 3 x 0..1: 1 1 1 1")
        .unwrap_err()
        .to_string();
    assert!(e.contains("widget 2") && e.contains("tri 3"), "{e}");
    let mut scene = Scene::new(columns(8, 2, 2, |x| x as f32), on_columns(8, 2));
    let tf = scene.tf2d(
        "gradient_magnitude",
        [0.0, 8.0],
        [0.0, 1.0],
        "rect 0..8 x 0..1: 1 1 1 1",
    );
    let node = scene.session.registry.node("Raycast").unwrap();
    let schema = node.schema();
    let mut values: std::collections::BTreeMap<String, ParamValue> = schema
        .params
        .iter()
        .map(|p| (p.name.to_owned(), p.default.clone()))
        .collect();
    values.insert("mode".into(), ParamValue::Choice("mip".into()));
    let names: Vec<&'static str> = schema.inputs.iter().map(|p| p.name).collect();
    let inputs = names
        .iter()
        .map(|n| match *n {
            "volume" => Some(Value::Volume(scene.volume.clone())),
            "camera" => Some(Value::Camera(Arc::new(scene.camera.clone()))),
            "tf" => Some(tf.clone()),
            _ => None,
        })
        .collect();
    let e = node
        .execute(
            &mut scene.session.ctx,
            &hatchery_graph::NodeInputs::new(names, inputs),
            &hatchery_graph::Params::new(values, None),
        )
        .err()
        .expect("MIP with a 2-D function must fail")
        .to_string();
    assert!(e.contains("tf") && e.contains("2-D"), "{e}");
}
