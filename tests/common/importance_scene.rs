//! The scene helpers of the importance tests (tests/importance.rs, tests/importance_thinning.rs):
//! a session, an orthographic camera along −z, the objects' styles, and ImportanceCompositing
//! followed by TwoLevelRaycast on the GPU.

#![allow(dead_code)]

use super::importance_reference::{Method, Setup};
use super::raycast_reference::{Mode, RayParams, Shading};
use super::two_level_reference::{Local, Object};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Compositing, Labels, ObjectStyle, RenderMode, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

pub const N: u32 = 40;
pub const SIZE: u32 = 48;
pub const STEP: f32 = 0.37;
pub const HALF_WIDTH: f32 = 22.0;

pub fn session() -> Session {
    super::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

pub fn flat(rgba: [f32; 4]) -> TransferFunction1D {
    TransferFunction1D::from_points(&[
        ControlPoint { value: 0.0, rgba },
        ControlPoint { value: 400.0, rgba },
    ])
    .unwrap()
}

/// Orthographic along −z (the eye on +z), the volume filling most of the frame.
pub fn camera(session: &mut Session) -> Camera {
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let fov = 2.0 * (HALF_WIDTH / 60.0).atan().to_degrees();
    Camera::orbit(
        Vec3::ZERO,
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

pub fn ray_params(cam: &Camera) -> RayParams {
    RayParams {
        view_proj: cam.view_proj(),
        view: cam.view,
        width: cam.width,
        height: cam.height,
        orthographic: true,
        step_voxels: STEP,
        mode: Mode::Dvr,
        shading: Shading::None,
        light_dir_view: Vec3::Z,
        early_termination: 0.99,
    }
}

/// World size of a pixel of `cam` (orthographic), as ImportanceCompositing computes it.
pub fn pixel_world(cam: &Camera) -> f32 {
    2.0 / (cam.proj.y_axis.y * cam.height as f32)
}

pub fn style(o: &Object, importance: f32) -> ObjectStyle {
    ObjectStyle {
        id: o.id,
        name: format!("object {}", o.id),
        enabled: true,
        tf: o.tf.clone(),
        mode: RenderMode::Dvr,
        compositing: match o.local {
            Local::Mip => Compositing::Mip,
            Local::Sum => Compositing::Sum,
            _ => Compositing::Over,
        },
        iso: 0.0,
        importance,
    }
}

pub fn method_name(m: Method) -> &'static str {
    match m {
        Method::Mimp => "mimp",
        Method::Cutaway => "cutaway",
        Method::AimcImage => "aimc_image",
        Method::AimcObject => "aimc_object",
        Method::Vpimc => "vpimc",
    }
}

pub struct Scene {
    pub volume: VolumeData,
    pub labels: LabelData,
    pub objects: Vec<Object>,
}

impl Scene {
    pub fn styles(&self, setup: &Setup) -> Vec<ObjectStyle> {
        self.objects
            .iter()
            .map(|o| {
                let i = setup.importance.iter().find(|(id, _)| *id == o.id);
                style(o, i.map_or(1.0, |(_, v)| *v))
            })
            .collect()
    }
}

pub fn pixels(value: &Value, session: &Session) -> Vec<[f32; 4]> {
    let a = export::to_array(value, &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// ImportanceCompositing's buffer (E, Σ I, footprint, last hit) and TwoLevelRaycast's picture
/// with it (or, with `setup = None`, without importance).
pub fn render_gpu(
    session: &mut Session,
    cam: &Camera,
    scene: &Scene,
    setup: Option<&Setup>,
    extra: &[(&str, ParamValue)],
) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let labels = Value::Labels(Arc::new(Labels::new(scene.labels.clone())));
    let default_setup = Setup {
        method: Method::Mimp,
        focus: 0,
        importance: vec![],
        slope: 0.0,
    };
    let styles = Value::ObjectStyles(Arc::new(scene.styles(setup.unwrap_or(&default_setup))));
    let camera = Value::Camera(Arc::new(cam.clone()));
    let mut inputs = vec![
        (
            "volume",
            Value::Volume(Arc::new(Volume::new(scene.volume.clone()))),
        ),
        ("labels", labels.clone()),
        ("styles", styles.clone()),
        ("camera", camera.clone()),
    ];
    let mut buffer = Vec::new();
    if let Some(setup) = setup {
        let countersink = if setup.slope > 0.0 {
            "conical"
        } else {
            "cylindrical"
        };
        let out = super::run_node(
            session,
            "ImportanceCompositing",
            vec![("labels", labels), ("styles", styles), ("camera", camera)],
            &[
                (
                    "method",
                    ParamValue::Choice(method_name(setup.method).into()),
                ),
                ("focus", ParamValue::Int(i64::from(setup.focus))),
                ("countersink", ParamValue::Choice(countersink.into())),
                ("slope", ParamValue::Float(setup.slope.max(0.05) as f64)),
                ("step", ParamValue::Float(STEP as f64)),
            ],
        );
        buffer = pixels(&out[0], session);
        inputs.push(("importance", out[0].clone()));
    }
    let mut params = vec![
        ("step", ParamValue::Float(STEP as f64)),
        ("jitter", ParamValue::Bool(false)),
    ];
    params.extend(extra.iter().cloned());
    let out = super::run_node(session, "TwoLevelRaycast", inputs, &params);
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    (buffer, pixels(&out[0], session))
}
