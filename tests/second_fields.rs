//! Svakhine, Jang, Ebert & Gaither 2005, Table 1 with fields besides the rendered one:
//! boundary and silhouette enhancement measuring a second scalar field's gradient or a vector
//! field U (`Raycast`'s `second` and `vector` inputs, `enhancement_field`), and a 2-D transfer
//! function over value × a second field (§3.3). Checked on axis-aligned columns against closed
//! forms, against the CPU reference ray caster (tests/common/raycast_reference.rs,
//! `render_fields`), and the operators (|U|, ∇·U, |∇×U|) on the ABC flow, whose curl is π·U.

mod common;

use common::ray_columns::{
    assert_matches, column_alpha, columns, on_columns, raycast_with, reference_params,
};
use common::raycast_reference::{self as reference, Enhancement, Fields, Measure, Shading};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_data::transfer_function_2d::{SecondAxis, TransferFunction2D, parse_widgets};
use hatchery_data::vector_field::VectorFieldData;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::vector_field::VectorField;
use hatchery_nodes::value::{TransferFunction, Volume};
use hatchery_nodes::{Session, Value};
use std::sync::Arc;

/// A constant colour of opacity `alpha` per voxel over every value.
fn flat_tf(alpha: f32) -> TransferFunction1D {
    let rgba = [1.0, 0.5, 0.25, alpha];
    TransferFunction1D::from_points(&[
        ControlPoint { value: -1e3, rgba },
        ControlPoint { value: 1e3, rgba },
    ])
    .unwrap()
}

fn tf_value(tf: &TransferFunction1D) -> Value {
    Value::TransferFunction(Arc::new(TransferFunction::Color(tf.clone())))
}

fn volume(data: &VolumeData) -> Value {
    Value::Volume(Arc::new(Volume::new(data.clone())))
}

fn field(data: &VectorFieldData) -> Value {
    Value::VectorField(Arc::new(VectorField::new(data.clone())))
}

/// U = `f(x)` on the unit-spacing grid of [`columns`].
fn vector_columns(w: u32, h: u32, d: u32, f: impl Fn(u32) -> [f32; 3]) -> VectorFieldData {
    let vectors = (0..w * h * d).map(|i| f(i % w)).collect();
    VectorFieldData::new(
        [w, h, d],
        Geometry::axis_aligned([1.0; 3], [0.0; 3]),
        vectors,
    )
    .unwrap()
}

fn enhancement_params(e: Enhancement, field: &str) -> Vec<(&'static str, ParamValue)> {
    let f = |x: f32| ParamValue::Float(x.into());
    vec![
        ("boundary_enhancement", f(e.boundary)),
        ("silhouette_enhancement", f(e.silhouette)),
        ("enhancement_field", ParamValue::Choice(field.into())),
    ]
}

/// Fails unless every pixel of `columns` (all rows) has opacity `want` within 10⁻³.
fn assert_columns(
    name: &str,
    gpu: &[[f32; 4]],
    w: u32,
    cols: impl Iterator<Item = u32>,
    want: f32,
) {
    for x in cols {
        for (row, px) in gpu.chunks_exact(w as usize).enumerate() {
            let got = px[x as usize][3];
            assert!(
                (got - want).abs() <= 1e-3,
                "{name}: column {x} row {row}: α {got}, closed form {want}"
            );
        }
    }
}

/// A volume seen by one camera in one session: Raycast's picture and the CPU reference's.
struct Scene {
    session: Session,
    data: VolumeData,
    volume: Arc<Volume>,
    camera: Camera,
}

/// What the CPU reference classifies and enhances with (the node gets the same as inputs).
struct Reference<'a> {
    tf: &'a TransferFunction1D,
    tf2d: Option<&'a TransferFunction2D>,
    step: f32,
    enhancement: Enhancement,
    fields: Fields<'a>,
}

impl Scene {
    fn new(data: VolumeData, camera: Camera) -> Self {
        Self {
            session: common::ray_columns::session_for(&camera),
            volume: Arc::new(Volume::new(data.clone())),
            data,
            camera,
        }
    }

    /// Raycast (shading none) with `inputs` besides the volume and camera, and `extra`
    /// parameters; the node's error if it fails.
    fn gpu(
        &mut self,
        inputs: Vec<(&'static str, Value)>,
        step: f32,
        extra: &[(&str, ParamValue)],
    ) -> Result<Vec<[f32; 4]>, hatchery_graph::NodeError> {
        let (volume, camera) = (&self.volume, &self.camera);
        raycast_with(
            &mut self.session,
            volume,
            camera,
            inputs,
            "none",
            step,
            extra,
        )
    }

    /// [`Self::gpu`] with the enhancement and field of `r`, checked against the CPU reference
    /// (`assert_matches`); returns the GPU picture.
    fn compare(
        &mut self,
        name: &str,
        inputs: Vec<(&'static str, Value)>,
        r: Reference,
    ) -> Vec<[f32; 4]> {
        let field = match r.fields.measure {
            Measure::Rendered => "rendered",
            Measure::Second => "second",
            Measure::Vector => "vector",
        };
        let gpu = self
            .gpu(inputs, r.step, &enhancement_params(r.enhancement, field))
            .unwrap();
        let params = reference_params(&self.camera, Shading::None, r.step);
        let cpu =
            reference::render_fields(&self.data, r.tf, r.tf2d, &params, r.enhancement, r.fields);
        assert_matches(name, &gpu, &cpu, self.camera.width);
        gpu
    }
}

/// The rendered field is constant (so its own |∇P| is 0 everywhere); the second field S is a
/// ramp with slopes 0.02 and 0.06 per voxel along x. Boundary enhancement measuring S gives each
/// column o_o·(|∇S| / max |∇S|)^n: 1/3^n on the left, 1 on the right, α = 1 − (1 − o)^16;
/// measuring the rendered field it clears the picture.
#[test]
fn boundary_enhancement_measures_the_second_fields_gradient() {
    let (w, h, d) = (16u32, 2u32, 16u32);
    let s = columns(w, h, d, |x| {
        let x = x as f32;
        if x <= 8.0 {
            0.02 * x
        } else {
            0.16 + 0.06 * (x - 8.0)
        }
    });
    let mut scene = Scene::new(columns(w, h, d, |_| 0.5), on_columns(w, h));
    let tf = flat_tf(0.2);
    let fields = Fields {
        second: Some(&s),
        vector: None,
        measure: Measure::Second,
    };
    for n in [1.0f32, 2.0] {
        let enhancement = Enhancement {
            boundary: n,
            ..Enhancement::default()
        };
        let inputs = vec![("tf", tf_value(&tf)), ("second", volume(&s))];
        let r = Reference {
            tf: &tf,
            tf2d: None,
            step: 1.0,
            enhancement,
            fields,
        };
        let gpu = scene.compare(&format!("second-field boundary n = {n}"), inputs, r);
        let shallow = column_alpha(0.2 * (1.0f32 / 3.0).powf(n), d);
        assert_columns("shallow slope", &gpu, w, 1..7, shallow);
        assert_columns("steep slope", &gpu, w, 10..w, column_alpha(0.2, d));
    }
    let e = Enhancement {
        boundary: 1.0,
        ..Enhancement::default()
    };
    let inputs = vec![("tf", tf_value(&tf)), ("second", volume(&s))];
    let own = scene
        .gpu(inputs, 1.0, &enhancement_params(e, "rendered"))
        .unwrap();
    assert!(
        own.iter().all(|px| px[3] == 0.0),
        "the rendered field has no boundaries"
    );
}

/// U lies across the view (x) with |U| = 1/2 on the left half and along it (z) with |U| = 1 on
/// the right. Silhouette enhancement (1 − |Û·V|)^n keeps the left at o_o and clears the right;
/// boundary enhancement (|U| / max |U|)^n halves the left's opacity and keeps the right's.
#[test]
fn vector_enhancement_keeps_flow_seen_side_on_and_scales_by_speed() {
    let (w, h, d) = (16u32, 2u32, 16u32);
    let u = vector_columns(w, h, d, |x| {
        if x < 8 {
            [0.5, 0.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        }
    });
    let mut scene = Scene::new(columns(w, h, d, |_| 0.5), on_columns(w, h));
    let tf = flat_tf(0.2);
    let silhouette = Enhancement {
        silhouette: 1.0,
        ..Enhancement::default()
    };
    let boundary = Enhancement {
        boundary: 1.0,
        ..Enhancement::default()
    };
    let cases = [
        (silhouette, column_alpha(0.2, d), 0.0),
        (boundary, column_alpha(0.1, d), column_alpha(0.2, d)),
    ];
    let fields = Fields {
        second: None,
        vector: Some(&u),
        measure: Measure::Vector,
    };
    for (enhancement, left, right) in cases {
        let inputs = vec![("tf", tf_value(&tf)), ("vector", field(&u))];
        let r = Reference {
            tf: &tf,
            tf2d: None,
            step: 1.0,
            enhancement,
            fields,
        };
        let gpu = scene.compare(&format!("vector {enhancement:?}"), inputs, r);
        assert_columns("across the view", &gpu, w, 0..7, left);
        assert_columns("along the view", &gpu, w, 9..w, right);
    }
}

/// The ABC flow through a perspective view at an angle, silhouette and boundary enhancement
/// together measuring U: GPU = CPU reference (the tolerance of `assert_matches`).
#[test]
fn vector_enhancement_of_the_abc_flow_matches_the_reference_in_perspective() {
    let n = 24u32;
    let u = hatchery_data::vector_field::abc_flow(n, 1.0, 0.8, 0.6).unwrap();
    let size = 48u32;
    let camera = Camera::orbit(
        Vec3::ZERO,
        30.0,
        20.0,
        4.0,
        40.0,
        false,
        0.05,
        50.0,
        false,
        size,
        size,
    );
    let mut scene = Scene::new(common::field_on_cube(n, |q| 1.0 - q.length()), camera);
    let tf = TransferFunction1D::from_points(&[
        ControlPoint {
            value: 0.0,
            rgba: [0.2, 0.5, 0.9, 0.0],
        },
        ControlPoint {
            value: 1.0,
            rgba: [0.9, 0.6, 0.2, 0.6],
        },
    ])
    .unwrap();
    let enhancement = Enhancement {
        silhouette: 2.0,
        boundary: 1.0,
        ..Enhancement::default()
    };
    let fields = Fields {
        second: None,
        vector: Some(&u),
        measure: Measure::Vector,
    };
    let inputs = vec![("tf", tf_value(&tf)), ("vector", field(&u))];
    let r = Reference {
        tf: &tf,
        tf2d: None,
        step: 0.5,
        enhancement,
        fields,
    };
    scene.compare("ABC flow, perspective", inputs, r);
}

/// A 2-D transfer function over value × a second field S = x (data units): a box over S in
/// [8, 16] shows exactly the columns whose S lies inside it, each α = 1 − (1 − 0.3)^4, and no
/// others. GPU = CPU reference.
#[test]
fn second_field_axis_classifies_by_the_second_fields_value() {
    let (w, h, d) = (32u32, 2u32, 4u32);
    let s = columns(w, h, d, |x| x as f32);
    let mut scene = Scene::new(columns(w, h, d, |_| 100.0), on_columns(w, h));
    let widgets = "rect 0..255 x 8..16: 1 0.5 0.25 0.3";
    let f = |x: f32| ParamValue::Float(x.into());
    let tf = common::run_node(
        &mut scene.session,
        "TransferFunction2D",
        vec![],
        &[
            ("axis", ParamValue::Choice("second_field".into())),
            ("value_min", f(0.0)),
            ("value_max", f(255.0)),
            ("second_min", f(0.0)),
            ("second_max", f(32.0)),
            ("widgets", ParamValue::Text(widgets.into())),
        ],
    )
    .remove(0);
    let baked = TransferFunction2D::new(
        SecondAxis::SecondField,
        [0.0, 255.0],
        [0.0, 32.0],
        &parse_widgets(widgets).unwrap(),
    )
    .unwrap();
    let unused = flat_tf(0.0);
    let r = Reference {
        tf: &unused,
        tf2d: Some(&baked),
        step: 1.0,
        enhancement: Enhancement::default(),
        fields: Fields {
            second: Some(&s),
            vector: None,
            measure: Measure::Rendered,
        },
    };
    let gpu = scene.compare(
        "second-field axis",
        vec![("tf", tf.clone()), ("second", volume(&s))],
        r,
    );
    assert_columns("inside the box", &gpu, w, 9..16, column_alpha(0.3, d));
    assert_columns("below the box", &gpu, w, 0..7, 0.0);
    assert_columns("above the box", &gpu, w, 18..w, 0.0);

    // Without the second field the node names the port it needs.
    let e = scene.gpu(vec![("tf", tf.clone())], 1.0, &[]).unwrap_err();
    assert_eq!(e.port.as_deref(), Some("second"), "{e}");
    assert!(e.message.contains("second_field"), "{e}");
    // A second field on another grid is refused, naming the port.
    let elsewhere = columns(w, h, d + 1, |x| x as f32);
    let e = scene
        .gpu(vec![("tf", tf), ("second", volume(&elsewhere))], 1.0, &[])
        .unwrap_err();
    assert_eq!(e.port.as_deref(), Some("second"), "{e}");
    assert!(e.message.contains("share the grid"), "{e}");
}

/// Enhancement measuring a field that is not connected names the port it needs.
#[test]
fn missing_fields_name_their_port() {
    let (w, h, d) = (8u32, 2u32, 2u32);
    let mut scene = Scene::new(columns(w, h, d, |x| x as f32), on_columns(w, h));
    let e = Enhancement {
        silhouette: 1.0,
        ..Enhancement::default()
    };
    for port in ["second", "vector"] {
        let inputs = vec![("tf", tf_value(&flat_tf(0.2)))];
        let err = scene
            .gpu(inputs, 1.0, &enhancement_params(e, port))
            .unwrap_err();
        assert_eq!(err.port.as_deref(), Some(port), "{err}");
    }
}

/// The operators through the nodes a user connects: ProceduralVectorField (abc) → VectorOperator.
/// |∇×U| = π·|U| within the central differences' error (0.5 % of the peak), ∇·U = 0; and a
/// VectorField of three component volumes equals its components.
#[test]
fn vector_operators_of_the_abc_flow_and_a_field_from_components() {
    let mut session = common::session_from_text(r#"(version: 1, nodes: [])"#, 8, 8);
    let abc = common::run_node(
        &mut session,
        "ProceduralVectorField",
        vec![],
        &[
            ("shape", ParamValue::Choice("abc".into())),
            ("resolution", ParamValue::Int(40)),
        ],
    )
    .remove(0);
    let op = |session: &mut Session, name: &str| -> VolumeData {
        let out = common::run_node(
            session,
            "VectorOperator",
            vec![("field", abc.clone())],
            &[("operator", ParamValue::Choice(name.into()))],
        );
        let Value::Volume(v) = &out[0] else {
            panic!("not a volume")
        };
        (*v.data).clone()
    };
    let (m, c, dv) = (
        op(&mut session, "magnitude"),
        op(&mut session, "curl_magnitude"),
        op(&mut session, "divergence"),
    );
    let peak = m.value_range[1];
    let mut worst = 0.0f32;
    for z in 1..39 {
        for y in 1..39 {
            for x in 1..39 {
                worst =
                    worst.max((c.value(x, y, z) - std::f32::consts::PI * m.value(x, y, z)).abs());
                assert!(dv.value(x, y, z).abs() < 1e-4);
            }
        }
    }
    eprintln!(
        "|∇×U| − π|U|: worst {worst:.5} (π·peak |U| {:.3})",
        std::f32::consts::PI * peak
    );
    assert!(worst < 0.005 * std::f32::consts::PI * peak, "worst {worst}");

    let comp = |c: u32| columns(4, 3, 2, move |x| (x * 10 + c) as f32);
    let out = common::run_node(
        &mut session,
        "VectorField",
        vec![
            ("x", volume(&comp(0))),
            ("y", volume(&comp(1))),
            ("z", volume(&comp(2))),
        ],
        &[],
    );
    let Value::VectorField(f) = &out[0] else {
        panic!("not a vector field")
    };
    assert_eq!(f.data.vectors[3], [30.0, 31.0, 32.0]);
    let other = columns(4, 3, 3, |x| x as f32);
    let e = common::try_run_node(
        &mut session,
        "VectorField",
        vec![
            ("x", volume(&comp(0))),
            ("y", volume(&other)),
            ("z", volume(&comp(2))),
        ],
        &[],
    )
    .err()
    .expect("components on different grids must fail");
    assert_eq!(e.port.as_deref(), Some("y"), "{e}");
}

/// A volume the device's brick pool cannot hold whole renders at a coarser level; second and
/// vector fields are read on the full grid, so the node refuses them there, naming the port and
/// the level (rather than blaming the field's grid).
#[test]
fn fields_with_a_volume_at_a_coarser_level_are_refused_naming_the_port() {
    let n = 64u32;
    let mut scene = Scene::new(columns(n, n, n, |x| x as f32), on_columns(n, n));
    // A 1 MiB pool holds 64 bricks of 16³ (14³ voxels each): 64³ needs 125, 32³ 27.
    scene
        .session
        .ctx
        .gpu
        .set_volume_limits(hatchery_gpu::VolumeLimits {
            max_texture_3d: Some(16),
            brick: 16,
            pool_bytes: 1 << 20,
            ..hatchery_gpu::VolumeLimits::default()
        });
    let s = columns(n, n, n, |x| x as f32);
    let e = Enhancement {
        boundary: 1.0,
        ..Enhancement::default()
    };
    let inputs = vec![("tf", tf_value(&flat_tf(0.2))), ("second", volume(&s))];
    let err = scene
        .gpu(inputs, 1.0, &enhancement_params(e, "second"))
        .unwrap_err();
    assert_eq!(err.port.as_deref(), Some("second"), "{err}");
    assert!(err.message.contains("coarser level"), "{err}");
}
