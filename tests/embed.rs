//! Strokes embedded in a volume rendering (Yuan & Chen 2005 §5) through Raycast's `strokes`
//! inputs: a line drawn on a plane behind an opaque slab is hidden exactly where the slab lies
//! in front of it, shown elsewhere, and shown everywhere when its plane is in front of the slab;
//! the global alpha ρ lets it show through.

mod common;

use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Mask, TransferFunction, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 40;
const SIZE: u32 = 48;
/// The stroke's row.
const ROW: u32 = 24;

/// An opaque slab (value 100) over the left half of the grid (voxels x 0..=19), voxels z
/// 28..=34 (world z 8.5..14.5, in front of the origin); grid centred at the origin.
fn slab() -> VolumeData {
    let half = (N - 1) as f64 / 2.0;
    let mut values = Vec::new();
    for z in 0..N {
        for _y in 0..N {
            for x in 0..N {
                values.push(if x <= 19 && (28..=34).contains(&z) {
                    100.0
                } else {
                    0.0
                });
            }
        }
    }
    VolumeData::with_geometry([N; 3], Geometry::axis_aligned([1.0; 3], [-half; 3]), values).unwrap()
}

/// The plane z = `z` as a field (larger behind it), for the strokes' depth.
fn plane(z: f32) -> VolumeData {
    let half = (N - 1) as f64 / 2.0;
    let mut values = Vec::new();
    for k in 0..N {
        for _ in 0..N * N {
            values.push(z - (k as f32 - half as f32));
        }
    }
    VolumeData::with_geometry([N; 3], Geometry::axis_aligned([1.0; 3], [-half; 3]), values).unwrap()
}

fn camera(session: &mut Session) -> Camera {
    session.ctx.set_size(SIZE, SIZE).unwrap();
    let fov = 2.0 * (22.0f32 / 60.0).atan().to_degrees();
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

/// Raycast of the slab (grey, opaque), with a red line along row `ROW` on the plane z =
/// `plane_z` embedded when `plane_z` is given; premultiplied RGBA per pixel.
fn render(session: &mut Session, plane_z: Option<f32>, rho: f32, coverage: f32) -> Vec<[f32; 4]> {
    let cam = camera(session);
    let camera = Value::Camera(Arc::new(cam.clone()));
    let tf = TransferFunction1D::from_points(&[
        ControlPoint {
            value: 0.0,
            rgba: [0.5, 0.5, 0.5, 0.0],
        },
        ControlPoint {
            value: 50.0,
            rgba: [0.5, 0.5, 0.5, 1.0],
        },
        ControlPoint {
            value: 100.0,
            rgba: [0.5, 0.5, 0.5, 1.0],
        },
    ])
    .unwrap();
    let mut inputs = vec![
        ("volume", Value::Volume(Arc::new(Volume::new(slab())))),
        ("camera", camera.clone()),
        (
            "tf",
            Value::TransferFunction(Arc::new(TransferFunction::Color(tf))),
        ),
    ];
    if let Some(z) = plane_z {
        let depth = common::run_node(
            session,
            "IsoSurfaceRaycast",
            vec![
                ("volume", Value::Volume(Arc::new(Volume::new(plane(z))))),
                ("camera", camera),
            ],
            &[("iso", ParamValue::Float(0.0))],
        )
        .remove(0);
        let mut line = vec![0.0f32; (SIZE * SIZE) as usize];
        for x in 0..SIZE {
            line[(ROW * SIZE + x) as usize] = coverage;
        }
        let texture = session.ctx.gpu.texture_2d_init(
            "line",
            SIZE,
            SIZE,
            wgpu::TextureFormat::R32Float,
            bytemuck::cast_slice(&line),
        );
        inputs.push(("strokes", Value::Mask(Arc::new(Mask { texture }))));
        inputs.push(("strokes_depth", depth));
    }
    let out = common::run_node(
        session,
        "Raycast",
        inputs,
        &[
            ("shading", ParamValue::Choice("none".into())),
            ("jitter", ParamValue::Bool(false)),
            ("step", ParamValue::Float(0.37)),
            ("rho", ParamValue::Float(rho as f64)),
            ("stroke_color", ParamValue::Color([1.0, 0.0, 0.0, 1.0])),
        ],
    );
    let a = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

#[test]
fn a_stroke_behind_an_opaque_slab_is_hidden_exactly_where_the_slab_is_nearer() {
    let mut session = common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    );
    let plain = render(&mut session, None, 1.0, 1.0);
    let behind = render(&mut session, Some(0.0), 1.0, 1.0);
    let in_front = render(&mut session, Some(18.0), 1.0, 1.0);
    let red = [1.0, 0.0, 0.0, 1.0];
    let (mut hidden, mut shown) = (0, 0);
    // Columns whose rays cross the volume's box (the plane exists there): world |x| < 19.
    for x in 4..SIZE - 4 {
        let i = (ROW * SIZE + x) as usize;
        // The plane in front of the slab: the stroke everywhere on its row.
        assert!(
            common::channel_difference(&in_front[i], &red) <= 1.0 / 255.0,
            "x {x}: {:?}",
            in_front[i]
        );
        if plain[i][3] >= 0.99 {
            // The slab is opaque in front of the stroke here: exactly the plain rendering.
            assert!(
                common::channel_difference(&behind[i], &plain[i]) <= 1.0 / 255.0,
                "x {x}: {:?} vs {:?}",
                behind[i],
                plain[i]
            );
            hidden += 1;
        } else if plain[i][3] == 0.0 {
            assert!(
                common::channel_difference(&behind[i], &red) <= 1.0 / 255.0,
                "x {x}: {:?}",
                behind[i]
            );
            shown += 1;
        }
    }
    assert!(
        hidden >= 18 && shown >= 18,
        "hidden {hidden}, shown {shown}"
    );
    // Off the stroke's row nothing changes.
    common::assert_images_close_where("off the row", &behind, &plain, SIZE, 1.0 / 255.0, |i| {
        i / SIZE as usize != ROW as usize
    });
    // A global alpha ρ < 1 lets the stroke show through the slab.
    let thin = render(&mut session, Some(0.0), 0.02, 1.0);
    let i = (ROW * SIZE + 8) as usize;
    assert!(
        plain[i][3] >= 0.99 && thin[i][0] > thin[i][1] + 0.05,
        "{:?}",
        thin[i]
    );
}
