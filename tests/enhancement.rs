//! Svakhine, Jang, Ebert & Gaither 2005, Table 1, as `Raycast` options: boundary enhancement
//! `o_o·|∇P|^n`, silhouette enhancement `o_o·(1 − |∇P̂·V|)^n` and the banding widget
//! `((1 + sin(o_o·π·m)) / 2)^n`, checked against the CPU reference ray caster
//! (tests/common/raycast_reference.rs, `render_enhanced`) and, on axis-aligned columns of
//! constant value and gradient, against closed forms.

mod common;

use common::ray_columns::{
    assert_matches, column_alpha, columns, on_columns, raycast_image, reference_params,
};
use common::raycast_reference::{self as reference, Enhancement, Shading};
use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{TransferFunction, Volume};
use hatchery_nodes::{Session, Value};
use std::sync::Arc;

struct Scene {
    session: Session,
    volume: Arc<Volume>,
    data: VolumeData,
    tf: TransferFunction1D,
    camera: Camera,
}

impl Scene {
    fn new(data: VolumeData, tf: &[(f32, [f32; 4])], camera: Camera) -> Self {
        let points: Vec<ControlPoint> = tf
            .iter()
            .map(|&(value, rgba)| ControlPoint { value, rgba })
            .collect();
        let session = common::ray_columns::session_for(&camera);
        Self {
            session,
            volume: Arc::new(Volume::new(data.clone())),
            data,
            tf: TransferFunction1D::from_points(&points).unwrap(),
            camera,
        }
    }

    /// The Raycast node's image through the scene's function (see `raycast_image`).
    fn gpu(&mut self, shading: &str, step: f32, extra: &[(&str, ParamValue)]) -> Vec<[f32; 4]> {
        let tf = Value::TransferFunction(Arc::new(TransferFunction::Color(self.tf.clone())));
        let (volume, camera) = (&self.volume, &self.camera);
        raycast_image(&mut self.session, volume, camera, tf, shading, step, extra)
    }

    /// The CPU reference with the same rays (the node's default headlight).
    fn cpu(&self, shading: Shading, step: f32, e: Enhancement) -> Vec<[f32; 4]> {
        let p = reference_params(&self.camera, shading, step);
        reference::render_enhanced(&self.data, &self.tf, &p, e)
    }
}

/// The node's parameters for `e`.
fn params(e: Enhancement) -> Vec<(&'static str, ParamValue)> {
    let f = |x: f32| ParamValue::Float(x.into());
    vec![
        ("boundary_enhancement", f(e.boundary)),
        ("silhouette_enhancement", f(e.silhouette)),
        ("banding", f(e.banding_period)),
        ("banding_power", f(e.banding_power)),
    ]
}

/// A square `size`-pixel view of the origin (degrees; near 0.05, far 50).
fn orbit(azimuth: f32, elevation: f32, distance: f32, fov: f32, ortho: bool, size: u32) -> Camera {
    let (near, far) = (0.05, 50.0);
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        elevation,
        distance,
        fov,
        ortho,
        near,
        far,
        false,
        size,
        size,
    )
}

/// The node's default Blinn–Phong coefficients.
const PHONG: Shading = Shading::Phong {
    ambient: 0.15,
    diffuse: 0.85,
    specular: 0.4,
    exponent: 32.0,
};

/// A ramp along x with two slopes (0.02 and 0.06 per voxel), so |∇P| (divided by the volume's
/// largest gradient magnitude, 0.06) is 1/3 on the left and 1 on the right; constant along each
/// z ray. With a constant transfer-function opacity o_o = 0.2 a ray of 16 samples composites
/// α = 1 − (1 − o_o·|∇P|^n)^16.
#[test]
fn boundary_enhancement_of_a_two_slope_ramp_scales_opacity_by_the_gradient_power() {
    let (w, h, d) = (16u32, 2u32, 16u32);
    let f = |x: u32| {
        let x = x as f32;
        if x <= 8.0 {
            0.02 * x
        } else {
            0.16 + 0.06 * (x - 8.0)
        }
    };
    let colour = [1.0, 0.5, 0.25, 0.2];
    let mut scene = Scene::new(
        columns(w, h, d, f),
        &[(0.0, colour), (0.6, colour)],
        on_columns(w, h),
    );
    for n in [1.0f32, 2.0, 0.5] {
        let e = Enhancement {
            boundary: n,
            ..Enhancement::default()
        };
        let gpu = scene.gpu("none", 1.0, &params(e));
        let cpu = scene.cpu(Shading::None, 1.0, e);
        assert_matches(&format!("boundary n = {n}"), &gpu, &cpu, w);
        // Closed form on the columns whose central differences lie inside one slope.
        let mut worst = 0.0f32;
        for x in (1..7).chain(10..w) {
            let g: f32 = if x < 8 { 1.0 / 3.0 } else { 1.0 };
            let alpha = column_alpha(0.2 * g.powf(n), d);
            for row in 0..h {
                let got = gpu[(row * w + x) as usize];
                let want = [alpha, alpha * 0.5, alpha * 0.25, alpha];
                for k in 0..4 {
                    worst = worst.max((got[k] - want[k]).abs());
                }
                assert!(
                    (0..4).all(|k| (got[k] - want[k]).abs() <= 1e-3),
                    "boundary n = {n}, column {x}: GPU {got:?}, closed form {want:?}"
                );
            }
        }
        eprintln!("boundary n = {n}: worst difference from the closed form {worst:.6}");
    }
}

/// A ramp along x (value x / 31) under a transfer function whose opacity is the value: the
/// banding widget gives column x the opacity b = ((1 + sin(π·m·x/31)) / 2)^n, opaque bands
/// centred on o = (0.5 + 2k) / m and clear ones on o = (1.5 + 2k) / m.
#[test]
fn banding_of_a_ramp_puts_bands_where_the_sine_peaks() {
    let (w, h, d) = (32u32, 2u32, 2u32);
    let mut scene = Scene::new(
        columns(w, h, d, |x| x as f32 / 31.0),
        &[(0.0, [0.2, 0.4, 0.8, 0.0]), (1.0, [0.2, 0.4, 0.8, 1.0])],
        on_columns(w, h),
    );
    let (m, n) = (4.0f32, 2.0f32);
    let e = Enhancement {
        banding_period: m,
        banding_power: n,
        ..Enhancement::default()
    };
    let gpu = scene.gpu("none", 1.0, &params(e));
    let cpu = scene.cpu(Shading::None, 1.0, e);
    assert_matches("banding", &gpu, &cpu, w);
    let alpha: Vec<f32> = (0..w).map(|x| gpu[x as usize][3]).collect();
    let mut worst = 0.0f32;
    for (x, &got) in alpha.iter().enumerate() {
        let o = scene.tf.lookup(x as f32 / 31.0)[3];
        let want = if o > 0.0 {
            column_alpha(
                ((1.0 + (o * std::f32::consts::PI * m).sin()) / 2.0).powf(n),
                d,
            )
        } else {
            0.0
        };
        worst = worst.max((got - want).abs());
        assert!(
            (got - want).abs() <= 1e-3,
            "banding column {x}: GPU α {got}, closed form {want}"
        );
    }
    eprintln!(
        "banding: worst α difference from the closed form {worst:.6}; α per column {alpha:?}"
    );
    // Bands: the interior local maxima and minima of α along the ramp.
    let extrema = |better: fn(f32, f32) -> bool| -> Vec<u32> {
        (1..w - 1)
            .filter(|&x| {
                let x = x as usize;
                better(alpha[x], alpha[x - 1]) && better(alpha[x], alpha[x + 1])
            })
            .collect()
    };
    let nearest = |o: f32| (o * 31.0).round() as u32;
    assert_eq!(
        extrema(|a, b| a > b),
        vec![nearest(0.5 / m), nearest(2.5 / m)],
        "opaque bands"
    );
    assert_eq!(
        extrema(|a, b| a < b),
        vec![nearest(1.5 / m), nearest(3.5 / m)],
        "clear bands"
    );
}

/// A ball's shell (value 0.8 − r on [−1, 1]³, opaque around r = 0.8) seen orthographically
/// along z: silhouette enhancement leaves its rim, where the shell is seen edge-on, and clears
/// its centre, where it faces the viewer.
#[test]
fn silhouette_enhancement_of_a_ball_keeps_the_rim_and_clears_the_centre() {
    let size = 48u32;
    let data = common::field_on_cube(33, |p| 0.8 - p.length());
    let mut scene = Scene::new(
        data,
        &[
            (-0.1, [0.9, 0.8, 0.7, 0.0]),
            (0.0, [0.9, 0.8, 0.7, 0.6]),
            (0.1, [0.9, 0.8, 0.7, 0.0]),
        ],
        orbit(
            0.0,
            0.0,
            4.0,
            2.0 * (1.0f32 / 4.0).atan().to_degrees(),
            true,
            size,
        ),
    );
    let e = Enhancement {
        silhouette: 2.0,
        ..Enhancement::default()
    };
    let gpu = scene.gpu("phong", 0.5, &params(e));
    let cpu = scene.cpu(PHONG, 0.5, e);
    assert_matches("silhouette", &gpu, &cpu, size);
    let plain = scene.gpu("phong", 0.5, &[]);
    // The centre row: α at the centre and the largest α (the rim).
    let row = |image: &[[f32; 4]]| -> Vec<f32> {
        let y = size / 2;
        (0..size)
            .map(|x| image[(y * size + x) as usize][3])
            .collect()
    };
    let (enhanced, plain) = (row(&gpu), row(&plain));
    let centre = size as usize / 2;
    let rim = enhanced.iter().copied().fold(0.0f32, f32::max);
    eprintln!(
        "silhouette: centre α {} (plain {}), rim α {rim}",
        enhanced[centre], plain[centre]
    );
    assert!(
        plain[centre] > 0.5,
        "the plain shell is dense at its centre"
    );
    assert!(
        enhanced[centre] < 0.1 && rim > 0.5,
        "silhouette enhancement: centre α {} should be faint, the rim's {rim} strong",
        enhanced[centre]
    );
}

/// All three together, perspective, Blinn–Phong: the order of application (banding on the
/// transfer function's opacity, then boundary × silhouette after shading, then the step
/// correction) and V per sample are the reference's.
#[test]
fn all_enhancements_together_match_the_reference_in_perspective() {
    let size = 48u32;
    let data = hatchery_data::procedural::torus(32, 0.55, 0.25).unwrap();
    let mut scene = Scene::new(
        data,
        &[
            (-0.3, [0.2, 0.3, 0.9, 0.0]),
            (-0.02, [0.9, 0.6, 0.2, 0.0]),
            (0.05, [0.95, 0.9, 0.8, 0.4]),
            (0.6, [1.0, 0.3, 0.2, 0.9]),
        ],
        orbit(25.0, 35.0, 3.0, 45.0, false, size),
    );
    let e = Enhancement {
        boundary: 0.7,
        silhouette: 1.5,
        banding_period: 6.0,
        banding_power: 0.5,
    };
    let gpu = scene.gpu("phong", 0.5, &params(e));
    let cpu = scene.cpu(PHONG, 0.5, e);
    assert_matches("all three, perspective", &gpu, &cpu, size);
}

/// Off is off: with the period 0 the banding power changes nothing, and MIP ignores the
/// enhancements — both bit for bit. (tests/presets_unchanged.rs checks that every preset's
/// picture is what it was before the enhancements existed.)
#[test]
fn enhancements_off_or_outside_dvr_leave_the_picture_bit_identical() {
    let size = 32u32;
    let data = hatchery_data::procedural::sphere(24, 0.6).unwrap();
    let mut scene = Scene::new(
        data,
        &[(-0.1, [0.9, 0.8, 0.7, 0.0]), (0.6, [0.9, 0.5, 0.3, 0.8])],
        orbit(30.0, 20.0, 3.0, 40.0, false, size),
    );
    let flat = |image: Vec<[f32; 4]>| image.into_iter().flatten().collect::<Vec<f32>>();
    let plain = flat(scene.gpu("phong", 0.5, &[]));
    let power_only = flat(scene.gpu("phong", 0.5, &[("banding_power", ParamValue::Float(3.0))]));
    common::assert_images_identical(
        "banding power without a period",
        &power_only,
        &plain,
        size * 4,
    );
    let on = params(Enhancement {
        boundary: 2.0,
        silhouette: 1.0,
        banding_period: 3.0,
        banding_power: 1.0,
    });
    let mip = [("mode", ParamValue::Choice("mip".into()))];
    let mip_plain = flat(scene.gpu("phong", 0.5, &mip));
    let mip_on = flat(scene.gpu("phong", 0.5, &[&mip[..], &on[..]].concat()));
    common::assert_images_identical("mip with enhancements", &mip_on, &mip_plain, size * 4);
    assert_ne!(
        flat(scene.gpu("phong", 0.5, &on)),
        plain,
        "DVR with the enhancements on differs"
    );
}
