//! Self-tests of the CPU reference ray caster against closed forms: with an orthographic,
//! axis-aligned camera whose pixel centres sit on voxel centres and a step of one voxel, every
//! sample is a voxel value, so MIP is the column maximum and DVR the front-to-back "over" of
//! the column.

mod common;

use common::raycast_reference::{
    Mode, RayParams, Shading, gbuffer_iso, intersect_box, pixel_ray, render,
};
use glam::{Mat4, Vec3};
use hatchery_data::VolumeData;
use hatchery_data::lighting::lighting_tf;
use hatchery_data::procedural;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};

/// Voxels per axis of the test volumes (grid over [-1, 1]^3).
const N: u32 = 32;
const EYE_DISTANCE: f32 = 3.0;
const NEAR: f32 = 1.0;
const FAR: f32 = 5.0;

fn spacing() -> f32 {
    2.0 / (N - 1) as f32
}

/// Looking down −z from (0, 0, 3), y up: view space = world shifted by −3 in z.
fn view() -> Mat4 {
    glam::camera::rh::view::look_at_mat4(Vec3::new(0.0, 0.0, EYE_DISTANCE), Vec3::ZERO, Vec3::Y)
}

/// An N×N orthographic image whose pixel centres are the voxel centres (x, N−1−y): the
/// half-extent is 1 + half a voxel, so each pixel is one voxel wide. `extra` widens it.
fn ortho(extra: f32, mode: Mode, shading: Shading, step_voxels: f32) -> RayParams {
    let half = 1.0 + spacing() / 2.0 + extra;
    let proj = glam::camera::rh::proj::directx::orthographic(-half, half, -half, half, NEAR, FAR);
    RayParams {
        view_proj: proj * view(),
        view: view(),
        width: N,
        height: N,
        orthographic: true,
        step_voxels,
        mode,
        shading,
        light_dir_view: Vec3::Z,
        early_termination: 1.0,
    }
}

fn perspective(mode: Mode, shading: Shading, size: u32) -> RayParams {
    let proj = glam::camera::rh::proj::directx::perspective(45f32.to_radians(), 1.0, NEAR, FAR);
    RayParams {
        view_proj: proj * view(),
        view: view(),
        width: size,
        height: size,
        orthographic: false,
        step_voxels: 0.5,
        mode,
        shading,
        light_dir_view: Vec3::new(-0.3, 0.4, 1.0).normalize(),
        early_termination: 0.99,
    }
}

/// Deterministic noise in [0, 1] on the standard grid over [-1, 1]^3.
fn noise() -> VolumeData {
    let values = (0..N * N * N)
        .map(|i| {
            let mut h = i.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
            h ^= h >> 15;
            h = h.wrapping_mul(0x2C1B_3C6D);
            h ^= h >> 12;
            (h % 10_000) as f32 / 9_999.0
        })
        .collect();
    VolumeData::new([N; 3], [spacing(); 3], [-1.0; 3], values).unwrap()
}

fn sphere() -> VolumeData {
    procedural::sphere(N, 0.6).unwrap()
}

/// Colour varying with the value (so the compositing order matters), opacity up to 0.5.
fn tf(range: [f32; 2]) -> TransferFunction1D {
    let at = |f: f32| range[0] + f * (range[1] - range[0]);
    TransferFunction1D::from_points(&[
        ControlPoint {
            value: at(0.0),
            rgba: [0.0, 0.2, 1.0, 0.0],
        },
        ControlPoint {
            value: at(0.5),
            rgba: [0.2, 1.0, 0.3, 0.15],
        },
        ControlPoint {
            value: at(1.0),
            rgba: [1.0, 0.3, 0.0, 0.5],
        },
    ])
    .unwrap()
}

/// The voxel values seen by pixel (x, y), front (z = N−1) to back.
fn column(v: &VolumeData, x: u32, y: u32) -> Vec<f32> {
    (0..N).rev().map(|z| v.value(x, N - 1 - y, z)).collect()
}

fn premultiplied(rgba: [f32; 4]) -> [f32; 4] {
    [
        rgba[0] * rgba[3],
        rgba[1] * rgba[3],
        rgba[2] * rgba[3],
        rgba[3],
    ]
}

/// Front-to-back over of straight-alpha samples, stopping after A >= `stop`.
fn over(samples: impl IntoIterator<Item = [f32; 4]>, stop: f32) -> [f32; 4] {
    let mut out = [0.0f32; 4];
    for [r, g, b, a] in samples {
        let w = (1.0 - out[3]) * a;
        out[0] += w * r;
        out[1] += w * g;
        out[2] += w * b;
        out[3] += w;
        if out[3] >= stop {
            break;
        }
    }
    out
}

/// The N × N picture of `want` (x, y).
fn picture(want: impl Fn(u32, u32) -> [f32; 4]) -> Vec<[f32; 4]> {
    (0..N * N).map(|i| want(i % N, i / N)).collect()
}

/// Pixels off the border columns and rows.
fn interior(i: usize) -> bool {
    let (x, y) = (i as u32 % N, i as u32 / N);
    (1..N - 1).contains(&x) && (1..N - 1).contains(&y)
}

#[test]
fn pixel_centres_hit_voxel_centres() {
    let p = ortho(0.0, Mode::Mip, Shading::None, 1.0);
    for (x, y) in [(0, 0), (5, 17), (31, 31), (16, 15)] {
        let (p0, dir) = pixel_ray(&p, x, y);
        let want = Vec3::new(-1.0 + x as f32 * spacing(), 1.0 - y as f32 * spacing(), 2.0);
        assert!((p0 - want).abs().max_element() < 1e-5, "{p0} vs {want}");
        assert!((dir - Vec3::NEG_Z).abs().max_element() < 1e-6, "{dir}");
    }
}

#[test]
fn slab_intersection() {
    let (lo, hi) = (Vec3::splat(-1.0), Vec3::splat(1.0));
    // Axis-aligned, zero components inside and outside the slabs (bounds inclusive).
    assert_eq!(
        intersect_box(lo, hi, Vec3::new(0.5, 1.0, 3.0), Vec3::NEG_Z),
        Some((2.0, 4.0))
    );
    assert_eq!(
        intersect_box(lo, hi, Vec3::new(1.5, 0.0, 3.0), Vec3::NEG_Z),
        None
    );
    // Starting inside: t_in = 0.
    assert_eq!(intersect_box(lo, hi, Vec3::ZERO, Vec3::X), Some((0.0, 1.0)));
    // Box behind the ray.
    assert_eq!(
        intersect_box(lo, hi, Vec3::new(0.0, 0.0, 3.0), Vec3::Z),
        None
    );
    // Diagonal.
    let d = Vec3::ONE.normalize();
    let (t0, t1) = intersect_box(lo, hi, Vec3::splat(-2.0), d).unwrap();
    assert!((t0 - 3f32.sqrt()).abs() < 1e-5 && (t1 - 3.0 * 3f32.sqrt()).abs() < 1e-5);
    // Missing diagonally.
    assert_eq!(
        intersect_box(
            lo,
            hi,
            Vec3::new(-2.0, 3.5, 0.0),
            Vec3::new(1.0, 1.0, 0.0).normalize()
        ),
        None
    );
}

#[test]
fn first_and_last_voxel_layers_are_sampled() {
    // Only the front (z = N − 1) or only the back (z = 0) layer is 1: with one-voxel steps
    // from t_in to t_out both end samples fall exactly on the box faces and must be taken.
    for layer in [N - 1, 0] {
        let values = (0..N * N * N)
            .map(|i| if i / (N * N) == layer { 1.0 } else { 0.0 })
            .collect();
        let v = VolumeData::new([N; 3], [spacing(); 3], [-1.0; 3], values).unwrap();
        let tf = tf([0.0, 1.0]);
        let img = render(&v, &tf, &ortho(0.0, Mode::Mip, Shading::None, 1.0));
        common::assert_images_close_where(
            &format!("MIP with only layer {layer} set"),
            &img,
            &picture(|_, _| premultiplied(tf.lookup(1.0))),
            N,
            1e-3,
            interior,
        );
    }
}

#[test]
fn mip_is_the_column_maximum() {
    for (name, v) in [("sphere", sphere()), ("noise", noise())] {
        let tf = tf(v.value_range);
        let img = render(&v, &tf, &ortho(0.0, Mode::Mip, Shading::None, 1.0));
        let want = |x, y| {
            let m = column(&v, x, y)
                .into_iter()
                .fold(f32::NEG_INFINITY, f32::max);
            premultiplied(tf.lookup(m))
        };
        let name = format!("MIP of {name}");
        common::assert_images_close_where(&name, &img, &picture(want), N, 1e-3, interior);
    }
}

#[test]
fn dvr_is_front_to_back_over_of_the_column() {
    for (name, v) in [("sphere", sphere()), ("noise", noise())] {
        let tf = tf(v.value_range);
        for stop in [1.0, 0.9] {
            let mut p = ortho(0.0, Mode::Dvr, Shading::None, 1.0);
            p.early_termination = stop;
            let img = render(&v, &tf, &p);
            let want = |x, y| over(column(&v, x, y).into_iter().map(|s| tf.lookup(s)), stop);
            common::assert_images_close_where(
                &format!("DVR of {name}, termination {stop}"),
                &img,
                &picture(want),
                N,
                1e-3,
                interior,
            );
        }
    }
}

#[test]
fn dvr_half_step_corrects_opacity() {
    // Step 0.5 voxel: samples at the voxel centres and half-way between (the mean of the two
    // neighbours along z), each with opacity 1 − (1 − a)^0.5.
    let v = noise();
    let tf = tf(v.value_range);
    let img = render(&v, &tf, &ortho(0.0, Mode::Dvr, Shading::None, 0.5));
    let want = |x, y| {
        let col = column(&v, x, y);
        let mut values = vec![col[0]];
        for pair in col.windows(2) {
            values.push(0.5 * (pair[0] + pair[1]));
            values.push(pair[1]);
        }
        over(
            values.into_iter().map(|s| {
                let [r, g, b, a] = tf.lookup(s);
                [r, g, b, 1.0 - (1.0 - a).sqrt()]
            }),
            1.0,
        )
    };
    let want = picture(want);
    common::assert_images_close_where("DVR at half steps", &img, &want, N, 2e-4, interior);
}

#[test]
fn iso_depth_and_normal_of_a_sphere() {
    let v = sphere();
    let p = ortho(0.0, Mode::Iso(0.0), Shading::None, 1.0);
    let g = gbuffer_iso(&v, &p, 0.0);
    let tf = tf(v.value_range);
    let img = render(&v, &tf, &p);
    let colour = tf.lookup(0.0);
    let (mut hits, mut misses) = (0, 0);
    for y in 0..N {
        for x in 0..N {
            let i = (y * N + x) as usize;
            let (wx, wy) = (-1.0 + x as f32 * spacing(), 1.0 - y as f32 * spacing());
            let r2 = wx * wx + wy * wy;
            let (depth, normal) = g[i];
            if r2 < 0.5 * 0.5 {
                // Front surface z = sqrt(0.6² − r²); window depth (distance − near) / (far − near).
                let z = (0.36 - r2).sqrt();
                let want = (EYE_DISTANCE - z - NEAR) / (FAR - NEAR);
                let tolerance = 0.5 * spacing() / (FAR - NEAR);
                assert!(
                    (depth - want).abs() <= tolerance,
                    "pixel ({x}, {y}): depth {depth}, want {want} ± {tolerance}"
                );
                // Outward normal (towards lower values) = world = view direction here.
                let n = Vec3::new(wx, wy, z) / 0.6;
                assert!(
                    normal.dot(n) > 0.99,
                    "pixel ({x}, {y}): normal {normal} vs {n}"
                );
                assert!((normal.length() - 1.0).abs() < 1e-5);
                assert_eq!(img[i], [colour[0], colour[1], colour[2], 1.0]);
                hits += 1;
            } else if r2 > (0.6 + spacing()).powi(2) {
                assert_eq!((depth, normal), (1.0, Vec3::ZERO), "pixel ({x}, {y})");
                assert_eq!(img[i], [0.0; 4]);
                misses += 1;
            }
        }
    }
    assert!(hits > 100 && misses > 100, "{hits} hits, {misses} misses");
}

#[test]
fn iso_phong_shading_follows_the_analytic_normal() {
    let v = sphere();
    let (ambient, diffuse, specular, exponent) = (0.1, 0.6, 0.3, 8.0);
    let p = ortho(
        0.0,
        Mode::Iso(0.0),
        Shading::Phong {
            ambient,
            diffuse,
            specular,
            exponent,
        },
        1.0,
    );
    let tf = tf(v.value_range);
    let img = render(&v, &tf, &p);
    let base = tf.lookup(0.0);
    for y in 0..N {
        for x in 0..N {
            let (wx, wy) = (-1.0 + x as f32 * spacing(), 1.0 - y as f32 * spacing());
            let r2 = wx * wx + wy * wy;
            if r2 >= 0.45 * 0.45 {
                continue;
            }
            // Headlight: L = V = H = +z in view space, so s = c_a + c_d n_z + c_s n_z^e.
            let nz = (0.36 - r2).sqrt() / 0.6;
            let s = ambient + diffuse * nz + specular * nz.powf(exponent);
            let got = img[(y * N + x) as usize];
            for c in 0..3 {
                let want = (base[c] * s).clamp(0.0, 1.0);
                assert!(
                    (got[c] - want).abs() < 0.02,
                    "pixel ({x}, {y}) channel {c}: {} vs {want}",
                    got[c]
                );
            }
            assert_eq!(got[3], 1.0);
        }
    }
}

#[test]
fn shading_variants_are_consistent() {
    let v = sphere();
    let tf = tf(v.value_range);
    let phong = Shading::Phong {
        ambient: 0.2,
        diffuse: 0.6,
        specular: 0.3,
        exponent: 16.0,
    };
    let context = |kappa_t: f32| Shading::ContextPreserving {
        fast_exponent: false,
        kappa_t,
        kappa_s: 0.5,
        ambient: 0.2,
        diffuse: 0.6,
        specular: 0.3,
        exponent: 16.0,
    };
    let unshaded = render(&v, &tf, &ortho(0.0, Mode::Dvr, Shading::None, 1.0));
    let shaded = render(&v, &tf, &ortho(0.0, Mode::Dvr, phong, 1.0));
    // κt = 0 is plain (Phong-shaded) DVR, bit for bit.
    let cp0 = render(&v, &tf, &ortho(0.0, Mode::Dvr, context(0.0), 1.0));
    assert_eq!(cp0, shaded);
    // Shading changes colour only.
    for (a, b) in unshaded.iter().zip(&shaded) {
        assert_eq!(a[3], b[3]);
    }
    // The "phong" lighting transfer function has s_alpha = 1: opacity unchanged too.
    let lit = render(
        &v,
        &tf,
        &ortho(
            0.0,
            Mode::Dvr,
            Shading::Lighting(lighting_tf("phong").unwrap()),
            1.0,
        ),
    );
    for (a, b) in unshaded.iter().zip(&lit) {
        assert_eq!(a[3], b[3]);
    }
    // Contour enhancement (s_alpha < 1) only adds opacity.
    let contour = render(
        &v,
        &tf,
        &ortho(
            0.0,
            Mode::Dvr,
            Shading::Lighting(lighting_tf("phong_contour").unwrap()),
            1.0,
        ),
    );
    assert!(unshaded.iter().zip(&contour).all(|(a, b)| b[3] >= a[3]));
    assert!(
        unshaded
            .iter()
            .zip(&contour)
            .any(|(a, b)| b[3] > a[3] + 1e-3)
    );
    // Context preservation only removes opacity, more for larger κt.
    let cp1 = render(&v, &tf, &ortho(0.0, Mode::Dvr, context(1.0), 1.0));
    let cp4 = render(&v, &tf, &ortho(0.0, Mode::Dvr, context(4.0), 1.0));
    for ((a, b), c) in shaded.iter().zip(&cp1).zip(&cp4) {
        assert!(b[3] <= a[3] && c[3] <= b[3] + 1e-6, "{a:?} {b:?} {c:?}");
    }
    let sum = |img: &[[f32; 4]]| img.iter().map(|p| p[3]).sum::<f32>();
    assert!(sum(&cp4) < sum(&cp1) && sum(&cp1) < sum(&shaded));
}

#[test]
fn rays_missing_the_box_are_empty() {
    let v = sphere();
    let tf = tf(v.value_range);
    // Twice as wide: the outer ring of pixels misses the box.
    let img = render(&v, &tf, &ortho(1.0, Mode::Dvr, Shading::None, 1.0));
    for (x, y) in [(0, 0), (N - 1, 0), (0, N - 1), (3, N / 2), (N / 2, N - 2)] {
        assert_eq!(img[(y * N + x) as usize], [0.0; 4], "pixel ({x}, {y})");
    }
    assert!(img[(N / 2 * N + N / 2) as usize][3] > 0.0);
}

#[test]
fn perspective_images_are_mirror_symmetric() {
    // The sphere grid is symmetric about x = 0 and the camera looks along −z, so every mode
    // gives a left-right symmetric image (the light is not symmetric, so only unshaded or
    // opacity-only checks).
    let v = sphere();
    let tf = tf(v.value_range);
    let size = 24;
    for (mode, shading) in [
        (Mode::Mip, Shading::None),
        (Mode::Dvr, Shading::None),
        (Mode::Iso(0.1), Shading::None),
    ] {
        let img = render(&v, &tf, &perspective(mode, shading.clone(), size));
        assert!(img.iter().any(|p| p[3] > 0.0));
        let mirrored: Vec<[f32; 4]> = (0..size * size)
            .map(|i| img[(i / size * size + size - 1 - i % size) as usize])
            .collect();
        // Every difference below 1e-3: none beyond the largest float under it.
        common::assert_images_close_where(
            &format!("{mode:?} vs mirrored"),
            &img,
            &mirrored,
            size,
            1e-3f32.next_down(),
            |i| (i as u32 % size) < size / 2,
        );
    }
    // Context-preserving with a perspective eye: finite and within [0, 1], and at most as
    // opaque as the same render without it.
    let cp = Shading::ContextPreserving {
        fast_exponent: false,
        kappa_t: 2.0,
        kappa_s: 0.5,
        ambient: 0.2,
        diffuse: 0.6,
        specular: 0.3,
        exponent: 16.0,
    };
    let phong = Shading::Phong {
        ambient: 0.2,
        diffuse: 0.6,
        specular: 0.3,
        exponent: 16.0,
    };
    // (Without early termination: the attenuated ray would otherwise run on past the point
    // where the other one stopped.)
    let mut with_cp = perspective(Mode::Dvr, cp, size);
    with_cp.early_termination = 1.0;
    let mut without = perspective(Mode::Dvr, phong, size);
    without.early_termination = 1.0;
    let a = render(&v, &tf, &with_cp);
    let b = render(&v, &tf, &without);
    for (a, b) in a.iter().zip(&b) {
        assert!(
            a.iter().all(|c| c.is_finite() && (0.0..=1.0).contains(c)),
            "{a:?}"
        );
        assert!(a[3] <= b[3] + 1e-6);
    }
    // Perspective iso depth at the centre pixel: sphere front at z = 0.6 - 0.1 (iso 0.1).
    let p = perspective(Mode::Iso(0.1), Shading::None, size);
    let g = gbuffer_iso(&v, &p, 0.1);
    // The image centre lies between four pixels; their rays are nearly axial.
    let (depth, normal) = g[(size / 2 * size + size / 2) as usize];
    let distance = {
        // Invert the directx perspective depth: depth = far (d − near) / (d (far − near)).
        let d = depth;
        FAR * NEAR / (FAR - d * (FAR - NEAR))
    };
    assert!(
        (distance - (EYE_DISTANCE - 0.5)).abs() < 0.5 * spacing() + 0.01,
        "distance {distance}"
    );
    assert!(normal.z > 0.95, "{normal}");
}
