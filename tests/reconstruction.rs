//! Higher-order reconstruction (issue 36; Hadwiger et al., tutorial §1.2–1.3): the tricubic
//! B-spline's values and gradients in the ray caster against the CPU reference of the filter
//! (tests/common/bspline_reference.rs), that reference against polynomials it must reproduce,
//! and the coarse sphere that the trilinear filter draws with rings.

mod common;

use common::bspline_reference as bspline;
use common::raycast_reference::{self as reference, Filter, Mode, RayParams, Shading};
use glam::{DMat3, Mat3, Vec3};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_data::voxels::Voxels;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{TransferFunction, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

fn session(w: u32, h: u32) -> Session {
    common::session_from_text(r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#, w, h)
}

/// `f(i, j, k)` on an `n`³ grid with `geometry`.
fn grid(n: u32, geometry: Geometry, f: impl Fn(Vec3) -> f32) -> VolumeData {
    let mut values = Vec::with_capacity((n * n * n) as usize);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(f(Vec3::new(i as f32, j as f32, k as f32)));
            }
        }
    }
    VolumeData::with_geometry([n; 3], geometry, values).unwrap()
}

/// The cubic B-spline reproduces linear functions exactly and turns x² into x² + 1/3 (its
/// variance): values, gradients and Hessians of the reference against those closed forms.
#[test]
fn the_bspline_reference_reproduces_polynomials() {
    let geometry = Geometry::default();
    let linear = grid(10, geometry, |p| 2.0 * p.x - 3.0 * p.y + 0.5 * p.z + 1.0);
    let quadratic = grid(10, geometry, |p| p.x * p.x + p.y * p.z);
    for q in [
        Vec3::new(4.0, 4.0, 4.0),
        Vec3::new(3.3, 5.7, 4.49),
        Vec3::new(6.9, 2.01, 5.5),
    ] {
        let d = bspline::derivatives(&linear, q).unwrap();
        let want = 2.0 * q.x - 3.0 * q.y + 0.5 * q.z + 1.0;
        assert!(
            (d.value - want).abs() < 1e-4,
            "linear value at {q}: {} vs {want}",
            d.value
        );
        assert!(
            (d.gradient - Vec3::new(2.0, -3.0, 0.5)).length() < 1e-4,
            "linear gradient at {q}: {}",
            d.gradient
        );
        assert!(
            d.hessian.abs_diff_eq(Mat3::ZERO, 1e-4),
            "linear Hessian at {q}"
        );

        let d = bspline::derivatives(&quadratic, q).unwrap();
        let want = q.x * q.x + 1.0 / 3.0 + q.y * q.z;
        assert!(
            (d.value - want).abs() < 1e-3,
            "x² + yz at {q}: {} vs {want}",
            d.value
        );
        let gradient = Vec3::new(2.0 * q.x, q.z, q.y);
        assert!(
            (d.gradient - gradient).length() < 1e-3,
            "gradient at {q}: {}",
            d.gradient
        );
        let hessian = Mat3::from_cols(Vec3::new(2.0, 0.0, 0.0), Vec3::Z, Vec3::Y);
        assert!(
            d.hessian.abs_diff_eq(hessian, 1e-3),
            "Hessian at {q}: {}",
            d.hessian
        );
    }
}

/// A ball of 1 in 0 on a coarse oblique grid (rotated, anisotropic voxels): the voxel lattice
/// is as visible as it can be, and the two filters draw it very differently.
fn blocky_ball() -> VolumeData {
    let n = 18;
    let direction = DMat3::from_rotation_z(0.4) * DMat3::from_rotation_x(-0.3);
    let spacing = [1.0, 1.2, 0.9];
    let centre = direction * (glam::DVec3::from_array(spacing) * 8.5);
    let geometry = Geometry {
        spacing: glam::DVec3::from_array(spacing),
        direction,
        origin: -centre,
    };
    let to_world = geometry;
    grid(n, geometry, move |p| {
        let r = to_world.voxel_to_world(p).length();
        if r < 6.5 { 1.0 } else { 0.0 }
    })
}

fn orbit(azimuth: f32, orthographic: bool, w: u32, h: u32, half_extent: f32) -> Camera {
    let distance = 40.0;
    let fov = 2.0 * (half_extent / distance).atan().to_degrees();
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        20.0,
        distance,
        fov,
        orthographic,
        1.0,
        200.0,
        false,
        w,
        h,
    )
}

fn tf(points: &[(f32, [f32; 4])]) -> TransferFunction1D {
    let points: Vec<ControlPoint> = points
        .iter()
        .map(|&(value, rgba)| ControlPoint { value, rgba })
        .collect();
    TransferFunction1D::from_points(&points).unwrap()
}

/// Raycast of `volume` with `params` (and no jitter), premultiplied RGBA per pixel.
fn raycast(
    session: &mut Session,
    volume: &Value,
    cam: &Camera,
    tf: &TransferFunction1D,
    params: &[(&str, ParamValue)],
) -> Vec<[f32; 4]> {
    session.ctx.set_size(cam.width, cam.height).unwrap();
    let light = hatchery_nodes::light::Light {
        direction: Vec3::new(0.3, 0.5, 1.0).normalize(),
        view_space: true,
        color: [1.0; 3],
        intensity: 1.0,
        ambient: 0.15,
    };
    let mut all = vec![
        ("jitter", ParamValue::Bool(false)),
        ("early_termination", ParamValue::Float(0.99)),
    ];
    all.extend(params.iter().cloned());
    let out = common::run_node(
        session,
        "Raycast",
        vec![
            ("volume", volume.clone()),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
            (
                "tf",
                Value::TransferFunction(Arc::new(TransferFunction::Color(tf.clone()))),
            ),
            ("light", Value::Light(Arc::new(light))),
        ],
        &all,
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let a = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// Root mean square of the channel differences of two premultiplied images.
fn rms(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    let sum: f32 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..4).map(move |c| (p[c] - q[c]).powi(2)))
        .sum();
    (sum / (a.len() * 4) as f32).sqrt()
}

/// Raycast with `reconstruction: bspline` renders what the CPU reference of the B-spline filter
/// renders — DVR unshaded and Phong-shaded, MIP and the first iso hit, perspective and
/// orthographic — on a volume whose lattice the trilinear filter shows (the trilinear
/// reference is far from both, so the check tells the filters apart).
#[test]
fn raycast_with_the_bspline_matches_its_cpu_reference() {
    let data = blocky_ball();
    let colour = tf(&[
        (0.2, [0.9, 0.6, 0.2, 0.0]),
        (0.45, [0.95, 0.9, 0.8, 0.5]),
        (0.8, [1.0, 0.3, 0.2, 0.9]),
    ]);
    let phong = phong();
    let cases = [
        ("dvr_none_ortho", Mode::Dvr, Shading::None, "none", true),
        ("dvr_phong_persp", Mode::Dvr, phong.clone(), "phong", false),
        ("mip_persp", Mode::Mip, Shading::None, "none", false),
        (
            "iso_phong_ortho",
            Mode::Iso(0.5),
            phong.clone(),
            "phong",
            true,
        ),
    ];
    // Both ways of reading the 64 voxels: x-quads (CPU adapters) and the filtered fetches.
    for quads in [true, false] {
        let mut s = session(48, 40);
        if !quads {
            s.ctx.gpu.set_volume_limits(hatchery_gpu::VolumeLimits {
                quads_bytes: 0,
                ..hatchery_gpu::VolumeLimits::default()
            });
        }
        let v = Arc::new(Volume::new(data.clone()));
        let volume = Value::Volume(v.clone());
        let cpu_adapter = s.ctx.gpu.adapter_info.device_type == wgpu::DeviceType::Cpu;
        let read = v.bspline_quads(&s.ctx.gpu).unwrap().is_some();
        assert_eq!(
            read,
            quads && cpu_adapter,
            "x-quads made (quads allowed: {quads})"
        );
        bspline_cases_match_the_reference(
            &mut s,
            &data,
            &volume,
            &colour,
            &cases,
            read,
            24.0 / 255.0,
        );
    }
}

/// The x-quads at the grid's faces: two balls cut by the faces x = 0 and x = n − 1 (where a row
/// of the 4×4×4 neighbourhood starts before the grid or runs past it, clamped) against the CPU
/// reference, which extends the data by clamping.
#[test]
fn the_bspline_at_the_grid_faces_matches_its_reference() {
    let n = 18;
    let centre = (n - 1) as f32 / 2.0;
    let geometry = Geometry::axis_aligned([1.0; 3], [-f64::from(centre); 3]);
    let data = grid(n, geometry, |p| {
        let near = Vec3::new(0.5, centre, centre);
        let far = Vec3::new((n - 1) as f32 - 0.5, centre + 2.0, centre - 1.0);
        if p.distance(near) < 6.0 || p.distance(far) < 5.0 {
            0.2 + p.y / 40.0
        } else {
            0.0
        }
    });
    let colour = tf(&[(0.05, [0.9, 0.6, 0.2, 0.0]), (0.3, [0.95, 0.9, 0.8, 0.7])]);
    let phong = phong();
    let cases = [
        (
            "faces_dvr_phong_ortho",
            Mode::Dvr,
            phong.clone(),
            "phong",
            true,
        ),
        ("faces_dvr_phong_persp", Mode::Dvr, phong, "phong", false),
        ("faces_mip_ortho", Mode::Mip, Shading::None, "none", true),
    ];
    let mut s = session(48, 40);
    let v = Arc::new(Volume::new(data.clone()));
    let read = v.bspline_quads(&s.ctx.gpu).unwrap().is_some();
    // The filtered fetches (real GPUs) round their weights: the sibling test's tolerance.
    let worst = if read { 1.0 } else { 24.0 } / 255.0;
    bspline_cases_match_the_reference(
        &mut s,
        &data,
        &Value::Volume(v),
        &colour,
        &cases,
        read,
        worst,
    );
}

/// Blinn–Phong as the tests here shade it.
fn phong() -> Shading {
    Shading::Phong {
        ambient: 0.15,
        diffuse: 0.85,
        specular: 0.4,
        exponent: 32.0,
    }
}

fn bspline_cases_match_the_reference(
    s: &mut Session,
    data: &VolumeData,
    volume: &Value,
    colour: &TransferFunction1D,
    cases: &[(&str, Mode, Shading, &str, bool)],
    quads: bool,
    worst: f32,
) {
    for (name, mode, shading, shading_name, ortho) in cases.iter().cloned() {
        let name = format!("{name} (x-quads: {quads})");
        let cam = orbit(35.0, ortho, 48, 40, 9.5);
        let (mode_name, iso) = match mode {
            Mode::Dvr => ("dvr", 0.0),
            Mode::Mip => ("mip", 0.0),
            Mode::Iso(v) => ("iso", v),
        };
        let step = 0.4;
        let gpu = raycast(
            s,
            volume,
            &cam,
            colour,
            &[
                ("mode", ParamValue::Choice(mode_name.into())),
                ("shading", ParamValue::Choice(shading_name.into())),
                ("iso", ParamValue::Float(iso.into())),
                ("step", ParamValue::Float(step)),
                ("reconstruction", ParamValue::Choice("bspline".into())),
            ],
        );
        let params = RayParams {
            view_proj: cam.view_proj(),
            view: cam.view,
            width: cam.width,
            height: cam.height,
            orthographic: cam.orthographic,
            step_voxels: step as f32,
            mode,
            shading,
            light_dir_view: Vec3::new(0.3, 0.5, 1.0).normalize(),
            early_termination: 0.99,
        };
        let cpu = reference::render_with(data, colour, &params, Filter::Bspline);
        let trilinear = reference::render_with(data, colour, &params, Filter::Trilinear);
        let (ours, other) = (rms(&gpu, &cpu), rms(&gpu, &trilinear));
        eprintln!("{name}: RMS vs the B-spline reference {ours}, vs the trilinear one {other}");
        assert!(
            gpu.iter().filter(|p| p[3] > 0.1).count() > 100,
            "{name}: empty picture"
        );
        assert!(
            ours <= 2.0 / 255.0,
            "{name}: RMS {ours} against the B-spline reference"
        );
        assert!(
            other > 4.0 * ours.max(1.0 / 255.0),
            "{name}: the trilinear reference is as close ({other}) as the B-spline one ({ours})"
        );
        common::assert_images_close(&name, &gpu, &cpu, cam.width, worst);
    }
}

/// A bricked volume (limits forced down) samples the B-spline across brick borders as one
/// texture does: every fetch goes through the page table.
#[test]
fn the_bspline_reads_a_bricked_volume_as_one_texture() {
    let data = blocky_ball();
    let colour = tf(&[(0.2, [0.9, 0.6, 0.2, 0.0]), (0.6, [0.95, 0.9, 0.8, 0.8])]);
    let cam = orbit(-50.0, false, 48, 40, 9.5);
    let params = [
        ("shading", ParamValue::Choice("phong".into())),
        ("step", ParamValue::Float(0.4)),
        ("reconstruction", ParamValue::Choice("bspline".into())),
    ];
    // Both through the filtered fetches (a bricked volume never reads x-quads).
    let mut whole = session(48, 40);
    whole.ctx.gpu.set_volume_limits(hatchery_gpu::VolumeLimits {
        quads_bytes: 0,
        ..hatchery_gpu::VolumeLimits::default()
    });
    let one = raycast(
        &mut whole,
        &Value::Volume(Arc::new(Volume::new(data.clone()))),
        &cam,
        &colour,
        &params,
    );
    let mut small = session(48, 40);
    small.ctx.gpu.set_volume_limits(hatchery_gpu::VolumeLimits {
        max_texture_3d: Some(8),
        brick: 8,
        ..hatchery_gpu::VolumeLimits::default()
    });
    let volume = Arc::new(Volume::new(data));
    let bricked = raycast(
        &mut small,
        &Value::Volume(volume.clone()),
        &cam,
        &colour,
        &params,
    );
    assert!(volume.bricked().is_some(), "the volume was not bricked");
    common::assert_images_close("bricked bspline", &bricked, &one, 48, 2.0 / 255.0);
}

/// The exact blur of a ball of radius `r` by an isotropic Gaussian of deviation `sigma`, at
/// distance `d` from its centre: the probability that a normal variate around the point lies in
/// the ball (the non-central χ₃ distribution).
fn blurred_ball(d: f64, r: f64, sigma: f64) -> f64 {
    let s2 = sigma * std::f64::consts::SQRT_2;
    let d = d.max(1e-9);
    let gauss = |x: f64| (-(x * x) / (2.0 * sigma * sigma)).exp();
    0.5 * (libm::erf((r - d) / s2) + libm::erf((r + d) / s2))
        - sigma / (d * (2.0 * std::f64::consts::PI).sqrt()) * (gauss(r - d) - gauss(r + d))
}

/// The issue's sphere: radius 30 mm, Gaussian edge σ 1 mm, values 0…255, on a grid of `n`³
/// voxels of `spacing` mm centred at the origin; uint8 (rounded) or float32.
fn sphere_volume(n: u32, spacing: f64, uint8: bool) -> VolumeData {
    let origin = -f64::from(n - 1) * spacing / 2.0;
    let geometry = Geometry::axis_aligned([spacing; 3], [origin; 3]);
    let mut values = Vec::with_capacity((n * n * n) as usize);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let p = glam::DVec3::new(i as f64, j as f64, k as f64) * spacing + origin;
                values.push(255.0 * blurred_ball(p.length(), 30.0, 1.0));
            }
        }
    }
    let voxels = if uint8 {
        Voxels::U8(values.iter().map(|v| v.round() as u8).collect())
    } else {
        Voxels::F32(values.iter().map(|&v| v as f32).collect())
    };
    VolumeData::from_voxels([n; 3], geometry, voxels).unwrap()
}

/// `(RMS, p99)` in 1/255 of the RGB difference between two renders over the pixels at least
/// `inset` pixels inside both silhouettes (alpha > 0.5): RMS over the channels, p99 of each
/// pixel's largest channel difference.
fn inside_difference(a: &[[f32; 4]], b: &[[f32; 4]], size: u32, inset: i32) -> (f32, f32, usize) {
    let n = size as i32;
    let covered = |x: i32, y: i32| {
        (0..n).contains(&x) && (0..n).contains(&y) && {
            let i = (y * n + x) as usize;
            a[i][3] > 0.5 && b[i][3] > 0.5
        }
    };
    let (mut sum, mut worst) = (0.0f64, Vec::new());
    for y in 0..n {
        for x in 0..n {
            let inside = (-inset..=inset).all(|dy| {
                (-inset..=inset)
                    .all(|dx| dx * dx + dy * dy > inset * inset || covered(x + dx, y + dy))
            });
            if !inside {
                continue;
            }
            let i = (y * n + x) as usize;
            let d: Vec<f32> = (0..3).map(|c| (a[i][c] - b[i][c]).abs() * 255.0).collect();
            sum += d.iter().map(|d| f64::from(d * d)).sum::<f64>();
            worst.push(d.iter().copied().fold(0.0, f32::max));
        }
    }
    assert!(!worst.is_empty(), "no pixel inside the silhouette");
    worst.sort_by(f32::total_cmp);
    let p99 = worst[(worst.len() - 1) * 99 / 100];
    (
        (sum / (worst.len() * 3) as f64).sqrt() as f32,
        p99,
        worst.len(),
    )
}

/// Issue 36's measurement: the sphere stored as uint8 on a 48³ grid of 2 mm and as float32 on a
/// 192³ grid of 0.5 mm, one Raycast (shaded DVR, opacity ramp 118 → 124, orthographic, no
/// jitter, step 0.25 voxel, 384×384). With the B-spline (the presets' reconstruction) the
/// coarse picture is within RMS 4/255 and p99 12/255 of the fine one over the pixels 6 px
/// inside the silhouette; the trilinear figures are printed beside it (its rings: ~8/255 RMS).
#[test]
fn a_coarse_sphere_renders_like_a_fine_one_with_the_bspline() {
    const SIZE: u32 = 384;
    let coarse = Value::Volume(Arc::new(Volume::new(sphere_volume(48, 2.0, true))));
    let fine = Value::Volume(Arc::new(Volume::new(sphere_volume(192, 0.5, false))));
    let ramp = tf(&[
        (118.0, [0.9, 0.85, 0.8, 0.0]),
        (124.0, [0.9, 0.85, 0.8, 1.0]),
        (255.0, [0.9, 0.85, 0.8, 1.0]),
    ]);
    let cam = orbit(30.0, true, SIZE, SIZE, 36.0);
    let mut s = session(SIZE, SIZE);
    let mut figures = Vec::new();
    for reconstruction in ["trilinear", "bspline"] {
        let params = [
            ("shading", ParamValue::Choice("phong".into())),
            ("step", ParamValue::Float(0.25)),
            ("reconstruction", ParamValue::Choice(reconstruction.into())),
        ];
        let a = raycast(&mut s, &coarse, &cam, &ramp, &params);
        let b = raycast(&mut s, &fine, &cam, &ramp, &params);
        let (rms, p99, pixels) = inside_difference(&a, &b, SIZE, 6);
        eprintln!(
            "{reconstruction}: coarse vs fine RMS {rms:.2}/255, p99 {p99:.1}/255 over {pixels} pixels"
        );
        assert!(
            pixels > 40_000,
            "{reconstruction}: only {pixels} pixels inside the sphere"
        );
        figures.push((reconstruction, rms, p99));
    }
    let (_, rms, p99) = figures[1];
    assert!(
        rms <= 4.0 && p99 <= 12.0,
        "B-spline: coarse vs fine RMS {rms}/255, p99 {p99}/255 (want ≤ 4 and ≤ 12); trilinear: {:?}",
        figures[0]
    );
}

/// Energy of `image` (luminance, `n`×`n`, Hann-windowed, mean removed) at the frequencies of a
/// lattice of period `period` pixels along both image axes: |DFT|² summed over the lattice's
/// first and second harmonics (±1 bin around each, for leakage), and, for comparison, over the
/// same bins at 0.75 of those frequencies (detail below the voxel period, not the lattice).
fn lattice_energy(luminance: &[f32], n: usize, period: usize) -> (f64, f64) {
    let mean = luminance.iter().map(|&l| f64::from(l)).sum::<f64>() / luminance.len() as f64;
    let hann = |i: usize| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / n as f64).cos();
    let base = (n / period) as i64;
    let energy_at = |fundamental: i64| -> f64 {
        let mut bins = Vec::new();
        for a in -2i64..=2 {
            for b in -2i64..=2 {
                if (a, b) == (0, 0) {
                    continue;
                }
                for da in -1..=1 {
                    for db in -1..=1 {
                        bins.push((a * fundamental + da, b * fundamental + db));
                    }
                }
            }
        }
        let us: std::collections::BTreeSet<i64> = bins.iter().map(|b| b.0).collect();
        // Row transforms at the needed horizontal frequencies, then the columns.
        let mut rows = std::collections::BTreeMap::new();
        for &u in &us {
            let row: Vec<(f64, f64)> = (0..n)
                .map(|y| {
                    (0..n).fold((0.0, 0.0), |(re, im), x| {
                        let v = (f64::from(luminance[y * n + x]) - mean) * hann(x) * hann(y);
                        let phase = -2.0 * std::f64::consts::PI * (u * x as i64) as f64 / n as f64;
                        (re + v * phase.cos(), im + v * phase.sin())
                    })
                })
                .collect();
            rows.insert(u, row);
        }
        bins.iter()
            .map(|&(u, v)| {
                let (re, im) =
                    rows[&u]
                        .iter()
                        .enumerate()
                        .fold((0.0, 0.0), |(re, im), (y, &(a, b))| {
                            let phase =
                                -2.0 * std::f64::consts::PI * (v * y as i64) as f64 / n as f64;
                            let (c, s) = (phase.cos(), phase.sin());
                            (re + a * c - b * s, im + a * s + b * c)
                        });
                re * re + im * im
            })
            .sum()
    };
    (energy_at(base), energy_at(base * 3 / 4))
}

/// `preset` seen orthographically from the right, zoomed onto the cortex at 8 pixels per voxel
/// (the MNI152's 1 mm grid is axis-aligned, so its lattice has a period of 8 pixels along both
/// image axes), with `reconstruction` set on its Raycast: the luminance of the picture on paper.
fn zoomed_cortex(preset: &str, reconstruction: Option<&str>) -> Vec<f32> {
    const SIZE: u32 = 256;
    let path = common::repo_root().join("graphs").join(preset);
    let mut session = Session::open(&path, SIZE, SIZE).unwrap();
    // 32 mm across: 2·distance·tan(fov/2) = 32 at distance 200.
    let fov = 2.0 * (16.0f64 / 200.0).atan().to_degrees();
    for (param, value) in [
        ("framing", "fixed".to_string()),
        ("projection", "orthographic".into()),
        ("azimuth", "90".into()),
        ("elevation", "0".into()),
        ("distance", "200".into()),
        ("fov", fov.to_string()),
        ("target", "0,-18,20".into()),
        ("near", "10".into()),
        ("far", "1000".into()),
    ] {
        session.set_param_text("camera", param, &value).unwrap();
    }
    if let Some(r) = reconstruction {
        session.set_param_text("ray", "reconstruction", r).unwrap();
    }
    let alpha =
        export::to_array(&session.evaluate("ray", "image").unwrap(), &session.ctx.gpu).unwrap();
    assert!(
        alpha.data.chunks_exact(4).all(|p| p[3] > 0.9),
        "{preset}: the zoomed view is not all cortex"
    );
    let image = export::to_array(
        &session.evaluate("over", "image").unwrap(),
        &session.ctx.gpu,
    )
    .unwrap();
    image
        .data
        .chunks_exact(4)
        .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
        .collect()
}

/// Issue 36: zoomed in, `tf1d_phong_brain` and `style_tf_brain` (on their own reconstruction)
/// show no lattice — the energy at the voxel period over the cortex is at most a quarter of the
/// trilinear filter's. The energy at 0.75 of that frequency (detail, not lattice) is printed.
#[test]
fn zoomed_brain_presets_show_no_voxel_lattice() {
    let data = common::shared_data("volumes/mni152_t1.nii.gz");
    if !data.exists() {
        eprintln!("skipped: {} is missing", data.display());
        return;
    }
    for preset in ["tf1d_phong_brain.ron", "style_tf_brain.ron"] {
        let (lattice_t, detail_t) =
            lattice_energy(&zoomed_cortex(preset, Some("trilinear")), 256, 8);
        let (lattice_p, detail_p) = lattice_energy(&zoomed_cortex(preset, None), 256, 8);
        eprintln!(
            "{preset}: energy at the voxel period {lattice_p:.3e} (preset) vs {lattice_t:.3e} \
             (trilinear): {:.3}; at 0.75 of it {detail_p:.3e} vs {detail_t:.3e}",
            lattice_p / lattice_t
        );
        assert!(
            lattice_p <= lattice_t / 4.0,
            "{preset}: the lattice energy is {lattice_p:.3e}, trilinear {lattice_t:.3e} (want ≤ a quarter)"
        );
    }
}

/// A thin opacity band (values 0.45…0.5 of a smooth ball's range), the transfer function a
/// step of 2 voxels misses or rings with post-classification.
fn thin_band() -> TransferFunction1D {
    tf(&[
        (0.0, [0.2, 0.4, 0.9, 0.0]),
        (0.45, [0.2, 0.4, 0.9, 0.0]),
        (0.47, [1.0, 0.8, 0.3, 0.8]),
        (0.5, [0.9, 0.3, 0.2, 0.0]),
        (1.0, [0.9, 0.3, 0.2, 0.0]),
    ])
}

/// A ball whose value falls linearly from 1 at the centre to 0 at radius 9 (voxels of 1).
fn graded_ball() -> VolumeData {
    let n = 24;
    let half = (n - 1) as f32 / 2.0;
    let geometry = Geometry::axis_aligned([1.0; 3], [-f64::from(half); 3]);
    grid(n, geometry, move |p| {
        (1.0 - (p - Vec3::splat(half)).length() / 9.0).max(0.0)
    })
}

fn dvr(shading: &Shading, cam: &Camera, step: f32) -> RayParams {
    RayParams {
        view_proj: cam.view_proj(),
        view: cam.view,
        width: cam.width,
        height: cam.height,
        orthographic: cam.orthographic,
        step_voxels: step,
        mode: Mode::Dvr,
        shading: shading.clone(),
        light_dir_view: Vec3::new(0.3, 0.5, 1.0).normalize(),
        early_termination: 0.99,
    }
}

/// `preintegrated: true` (Engel et al. 2001) renders what the CPU reference of pre-integration
/// renders, unshaded and Phong-shaded, with and without empty-space skipping; and at a step of
/// 2 voxels it is over 3× closer to a converged render (step 1/8, post-classified) than
/// post-classification at that step (what is left: the value is not linear between samples).
#[test]
fn preintegrated_dvr_matches_its_reference_and_converges_at_coarse_steps() {
    let data = graded_ball();
    let volume = Value::Volume(Arc::new(Volume::new(data.clone())));
    let band = thin_band();
    let phong = phong();
    let mut s = session(48, 48);
    for (name, shading, shading_name, ortho) in [
        ("none_ortho", Shading::None, "none", true),
        ("phong_persp", phong, "phong", false),
    ] {
        let cam = orbit(25.0, ortho, 48, 48, 12.0);
        let run = |s: &mut Session, step: f64, pre: bool, skip: bool| {
            raycast(
                s,
                &volume,
                &cam,
                &band,
                &[
                    ("shading", ParamValue::Choice(shading_name.into())),
                    ("step", ParamValue::Float(step)),
                    ("preintegrated", ParamValue::Bool(pre)),
                    ("skip_empty", ParamValue::Bool(skip)),
                ],
            )
        };
        let pre = run(&mut s, 2.0, true, true);
        let reference = reference::render_preintegrated(&data, &band, &dvr(&shading, &cam, 2.0));
        // The GPU interpolates the table between entries; the reference integrates the exact
        // positions: a few pixels differ by up to 8/255.
        common::assert_images_close(
            &format!("{name} vs reference"),
            &pre,
            &reference,
            48,
            8.0 / 255.0,
        );
        let worst = rms(&pre, &reference);
        assert!(
            worst <= 2.0 / 255.0,
            "{name}: RMS {worst} against the reference"
        );
        // The node keeps its table between runs (Ctx::keep): a new step makes a new one.
        let again = run(&mut s, 1.0, true, true);
        let reference_1 = reference::render_preintegrated(&data, &band, &dvr(&shading, &cam, 1.0));
        let off = rms(&again, &reference_1);
        assert!(off <= 2.0 / 255.0, "{name}: step 1 after step 2: RMS {off}");
        let unskipped = run(&mut s, 2.0, true, false);
        common::assert_images_close(
            &format!("{name} skipping"),
            &pre,
            &unskipped,
            48,
            1.0 / 255.0,
        );

        let post = run(&mut s, 2.0, false, true);
        let converged = run(&mut s, 0.125, false, true);
        let (pre_error, post_error) = (rms(&pre, &converged), rms(&post, &converged));
        eprintln!(
            "{name}: step 2 vs step 1/8 (post-classified): pre-integrated RMS {:.2}/255, \
             post-classified {:.2}/255",
            pre_error * 255.0,
            post_error * 255.0
        );
        assert!(
            pre.iter().filter(|p| p[3] > 0.1).count() > 200,
            "{name}: empty picture"
        );
        assert!(
            pre_error * 3.0 < post_error,
            "{name}: pre-integrated {pre_error}, post-classified {post_error} from converged"
        );
    }
}

/// Pre-integration where it does not apply is one clear error naming the parameter.
#[test]
fn preintegration_outside_dvr_is_refused_by_name() {
    let mut s = session(16, 16);
    let volume = Value::Volume(Arc::new(Volume::new(graded_ball())));
    let cam = orbit(0.0, true, 16, 16, 12.0);
    let node = s.registry.node("Raycast").unwrap();
    let light = hatchery_nodes::light::Light {
        direction: Vec3::Z,
        view_space: true,
        color: [1.0; 3],
        intensity: 1.0,
        ambient: 0.15,
    };
    let mut values: std::collections::BTreeMap<String, ParamValue> = node
        .schema()
        .params
        .iter()
        .map(|p| (p.name.to_owned(), p.default.clone()))
        .collect();
    values.insert("preintegrated".into(), ParamValue::Bool(true));
    values.insert("mode".into(), ParamValue::Choice("mip".into()));
    let inputs = hatchery_graph::NodeInputs::new(
        node.schema().inputs.iter().map(|p| p.name).collect(),
        node.schema()
            .inputs
            .iter()
            .map(|p| match p.name {
                "volume" => Some(volume.clone()),
                "camera" => Some(Value::Camera(Arc::new(cam.clone()))),
                "tf" => Some(Value::TransferFunction(Arc::new(TransferFunction::Color(
                    thin_band(),
                )))),
                "light" => Some(Value::Light(Arc::new(light.clone()))),
                _ => None,
            })
            .collect(),
    );
    let error = node
        .execute(
            &mut s.ctx,
            &inputs,
            &hatchery_graph::Params::new(values, None),
        )
        .err()
        .expect("pre-integrated MIP is refused");
    assert!(error.to_string().contains("preintegrated"), "{error}");
}

/// A volume with "no data" (NaN) voxels is drawn with the trilinear filter under `bspline`,
/// with a warning: a NaN voxel that carries little weight in the B-spline's filtered fetches
/// cannot be told from data there (it would pull the value down).
#[test]
fn a_volume_with_no_data_is_drawn_trilinear_with_a_warning() {
    let half = 11.5f32;
    let geometry = Geometry::axis_aligned([1.0; 3], [-f64::from(half); 3]);
    let data = grid(24, geometry, move |p| {
        if p.x == 5.0 {
            f32::NAN
        } else {
            (1.0 - (p - Vec3::splat(half)).length() / 9.0).max(0.0)
        }
    });
    assert!(data.has_no_data());
    let volume = Value::Volume(Arc::new(Volume::new(data)));
    let cam = orbit(60.0, false, 32, 32, 12.0);
    let colour = tf(&[(0.2, [0.9, 0.6, 0.2, 0.0]), (0.8, [0.95, 0.9, 0.8, 0.6])]);
    let mut s = session(32, 32);
    let render = |s: &mut Session, reconstruction: &str| {
        raycast(
            s,
            &volume,
            &cam,
            &colour,
            &[
                ("shading", ParamValue::Choice("phong".into())),
                ("reconstruction", ParamValue::Choice(reconstruction.into())),
            ],
        )
    };
    let trilinear = render(&mut s, "trilinear");
    assert!(s.ctx.warnings().is_empty(), "{:?}", s.ctx.warnings());
    let bspline = render(&mut s, "bspline");
    let warned = s.ctx.warnings().values().any(|w| w.contains("no data"));
    assert!(warned, "no warning: {:?}", s.ctx.warnings());
    assert!(trilinear.iter().any(|p| p[3] > 0.1), "empty picture");
    assert_eq!(bspline, trilinear);
}
