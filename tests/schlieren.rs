//! Schlieren photographs and shadowgraphs (Svakhine, Ebert et al. 2005, §4, eq. 1–5) against a
//! CPU reference of the paper's equations on a Gaussian blob ρ = exp(−|p − c|²/2σ²) seen by an
//! orthographic camera along −z, where the integrals are closed-form: with
//! P = ∫ρ dz = σ√(2π)·exp(−s²/2σ²) (s the distance from c across the rays),
//! ε = (∂P/∂x, ∂P/∂y) = −(x, y)/σ²·P (eq. 1) and L = ∇²P = (s²/σ⁴ − 2/σ²)·P (eq. 2).

mod common;

use common::Sample;
use glam::{DMat3, DVec3, Vec2, Vec3};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::Volume;
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

/// Voxels per side (odd: a voxel centre at the blob's centre).
const N: u32 = 65;
/// Pixels per side (odd: a pixel centre on the blob's centre).
const SIZE: u32 = 65;
/// Half the width of the world square the frame shows.
const HALF: f32 = 1.1;
/// The blob's σ, world units (7.9 voxels of the axis-aligned grid).
const SIGMA: f32 = 0.25;

/// The CPU reference: eq. 1 and 2 integrated along the ray (midpoint rule, exact derivatives of
/// the analytic field), eq. 3–5 turning them into intensity.
mod reference {
    use glam::{Vec2, Vec3};

    /// ∇ρ and the Laplacian across z of the Gaussian blob at `p`.
    fn derivatives(p: Vec3, centre: Vec3, sigma: f32) -> (Vec2, f32) {
        let d = p - centre;
        let s2 = sigma * sigma;
        let rho = (-d.length_squared() / (2.0 * s2)).exp();
        let gradient = Vec2::new(d.x, d.y) * (-rho / s2);
        let laplacian = ((d.x * d.x + d.y * d.y) / (s2 * s2) - 2.0 / s2) * rho;
        (gradient, laplacian)
    }

    /// (ε_x, ε_y) = ∫ ∂ρ/∂x, ∂ρ/∂y dz (eq. 1) and L = ∫ ∂²ρ/∂x² + ∂²ρ/∂y² dz (eq. 2) along the
    /// line through (x, y) parallel to z, over z ∈ [centre.z − 6σ, centre.z + 6σ].
    pub fn integrals(x: f32, y: f32, centre: Vec3, sigma: f32) -> (Vec2, f32) {
        let steps = 2000;
        let (z0, z1) = (centre.z - 6.0 * sigma, centre.z + 6.0 * sigma);
        let dz = (z1 - z0) / steps as f32;
        let (mut eps, mut l) = (Vec2::ZERO, 0.0);
        for k in 0..steps {
            let z = z0 + (k as f32 + 0.5) * dz;
            let (g, lap) = derivatives(Vec3::new(x, y, z), centre, sigma);
            eps += g * dz;
            l += lap * dz;
        }
        (eps, l)
    }

    /// Eq. 3: the knife edge with normal `k`, clamped.
    pub fn knife_edge(eps: Vec2, k: Vec2, gain: f32, s: f32) -> f32 {
        (s * (1.0 + gain * eps.dot(k)) / 2.0).clamp(0.0, 1.0)
    }

    /// Eq. 4: the circular cutoff, clamped.
    pub fn circular(eps: Vec2, gain: f32, s: f32) -> f32 {
        (s * gain * eps.length()).clamp(0.0, 1.0)
    }

    /// Eq. 5: the shadowgraph, clamped.
    pub fn shadowgraph(l: f32, gain: f32, s: f32) -> f32 {
        (s * (1.0 + gain * l) / 2.0).clamp(0.0, 1.0)
    }
}

/// The closed forms of eq. 1 and 2 for the blob (module doc).
fn closed_form(x: f32, y: f32, centre: Vec3, sigma: f32) -> (Vec2, f32) {
    let d = Vec2::new(x - centre.x, y - centre.y);
    let s2 = sigma * sigma;
    let p = sigma * (2.0 * std::f32::consts::PI).sqrt() * (-d.length_squared() / (2.0 * s2)).exp();
    (
        d * (-p / s2),
        (d.length_squared() / (s2 * s2) - 2.0 / s2) * p,
    )
}

/// The blob centred at `centre` sampled at the voxel centres of an N³ grid placed by `geometry`.
fn blob(geometry: Geometry, centre: Vec3) -> VolumeData {
    let mut values = Vec::with_capacity((N * N * N) as usize);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let p = geometry.voxel_to_world(Vec3::new(i as f32, j as f32, k as f32));
                values.push((-(p - centre).length_squared() / (2.0 * SIGMA * SIGMA)).exp());
            }
        }
    }
    VolumeData::with_geometry([N; 3], geometry, values).unwrap()
}

/// The blob at the origin on the axis-aligned grid over [-1, 1]³.
fn centred_blob() -> VolumeData {
    let spacing = 2.0 / (N - 1) as f64;
    blob(Geometry::axis_aligned([spacing; 3], [-1.0; 3]), Vec3::ZERO)
}

/// World (x, y) of pixel (i, j)'s centre (j from the top).
fn pixel_world(i: u32, j: u32) -> (f32, f32) {
    let f = |k: u32| (k as f32 + 0.5) / SIZE as f32 * 2.0 * HALF - HALF;
    (f(i), -f(j))
}

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// Orthographic along −z, x right and y up, showing [−HALF, HALF]².
fn camera() -> Camera {
    let fov = 2.0 * (HALF / 5.0).atan().to_degrees();
    Camera::orbit(
        Vec3::ZERO,
        0.0,
        0.0,
        5.0,
        fov,
        true,
        0.1,
        20.0,
        false,
        SIZE,
        SIZE,
    )
}

/// One Schlieren run: (picture, deflection) as RGBA per pixel.
struct Run {
    image: Vec<[f32; 4]>,
    deflection: Vec<[f32; 4]>,
}

fn schlieren(session: &mut Session, volume: &VolumeData, params: &[(&str, ParamValue)]) -> Run {
    let outputs = common::run_node(
        session,
        "Schlieren",
        vec![
            (
                "volume",
                Value::Volume(Arc::new(Volume::new(volume.clone()))),
            ),
            ("camera", Value::Camera(Arc::new(camera()))),
        ],
        params,
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let rgba = |v: &Value| -> Vec<[f32; 4]> {
        let a = export::to_array(v, &session.ctx.gpu).unwrap();
        a.data
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect()
    };
    Run {
        image: rgba(&outputs[0]),
        deflection: rgba(&outputs[1]),
    }
}

fn choice(name: &str) -> ParamValue {
    ParamValue::Choice(name.into())
}

/// Schlieren of `volume` in `mode` with `gain` and the knife at `angle` degrees.
fn photograph(s: &mut Session, volume: &VolumeData, mode: &str, gain: f32, angle: f32) -> Run {
    let params = [
        ("mode", choice(mode)),
        ("gain", ParamValue::Float(gain as f64)),
        ("knife_angle", ParamValue::Float(angle as f64)),
    ];
    schlieren(s, volume, &params)
}

/// The reference's (ε, L) of every pixel, normalised as the node's deflection output is: ε in
/// value ranges of `volume`, L in value ranges per voxel of its smallest spacing.
fn reference_integrals(volume: &VolumeData, centre: Vec3) -> Vec<(Vec2, f32)> {
    let range = volume.value_range[1] - volume.value_range[0];
    let spacing = volume
        .spacing()
        .iter()
        .copied()
        .fold(f32::INFINITY, f32::min);
    (0..SIZE * SIZE)
        .map(|p| {
            let (x, y) = pixel_world(p % SIZE, p / SIZE);
            let (eps, l) = reference::integrals(x, y, centre, SIGMA);
            (eps / range, l * spacing / range)
        })
        .collect()
}

/// Fails (naming the worst pixel) unless every pixel's `got` is within `tolerance` of `want`;
/// returns the worst error.
fn compare(
    name: &str,
    got: impl Fn(usize) -> f32,
    want: impl Fn(usize) -> f32,
    tolerance: f64,
) -> f64 {
    let samples: Vec<Sample> = (0..(SIZE * SIZE) as usize)
        .map(|i| {
            let (g, w) = (got(i), want(i));
            Sample {
                x: i as u32 % SIZE,
                y: i as u32 / SIZE,
                what: format!("GPU {g}, reference {w}"),
                error: (g - w).abs() as f64,
            }
        })
        .collect();
    common::assert_samples(name, &samples, tolerance, None);
    let worst = samples.iter().map(|s| s.error).fold(0.0, f64::max);
    eprintln!("{name}: worst error {worst:.5} (tolerance {tolerance})");
    worst
}

fn centre_pixel() -> usize {
    ((SIZE / 2) * SIZE + SIZE / 2) as usize
}

#[test]
fn the_reference_integrals_are_the_closed_forms() {
    for &(x, y) in &[
        (0.0, 0.0),
        (0.1, 0.0),
        (-0.2, 0.15),
        (0.3, -0.4),
        (0.6, 0.1),
    ] {
        let (eps, l) = reference::integrals(x, y, Vec3::new(0.0, 0.0, 0.05), SIGMA);
        let (e, le) = closed_form(x, y, Vec3::ZERO, SIGMA);
        assert!(
            (eps - e).length() < 1e-4 && (l - le).abs() < 1e-3,
            "at ({x}, {y}): numeric ε {eps} L {l}, closed form ε {e} L {le}"
        );
    }
}

/// Eq. 1 and 3: the deflection within 0.03 value ranges (2 % of its peak √(2π)/√e ≈ 1.52: the
/// central differences at ±1 voxel and the trilinear filter flatten the slopes by about 1 %),
/// the knife-edge picture within 0.01 of the reference's; darker where the density falls to
/// the right with k pointing right, and no deflection at the blob's centre.
#[test]
fn knife_edge_schlieren_of_a_gaussian_blob_follows_eq_1_and_3() {
    let mut s = session();
    let volume = centred_blob();
    let gain = 0.5;
    let run = photograph(&mut s, &volume, "schlieren", gain, 0.0);
    let want = reference_integrals(&volume, Vec3::ZERO);
    compare("ε_x", |i| run.deflection[i][0], |i| want[i].0.x, 0.03);
    compare("ε_y", |i| run.deflection[i][1], |i| want[i].0.y, 0.03);
    compare(
        "knife edge (eq. 3)",
        |i| run.image[i][0],
        |i| reference::knife_edge(want[i].0, Vec2::X, gain, 1.0),
        0.01,
    );
    assert!(
        run.image
            .iter()
            .all(|p| p[0] == p[1] && p[1] == p[2] && p[3] == 1.0),
        "grey, opaque"
    );
    // The centre deflects nothing: mid-grey.
    let c = centre_pixel();
    let [ex, ey, ..] = run.deflection[c];
    assert!(
        ex.abs() < 1e-3 && ey.abs() < 1e-3,
        "centre ε = ({ex}, {ey})"
    );
    assert!(
        (run.image[c][0] - 0.5).abs() < 2e-3,
        "centre grey {}",
        run.image[c][0]
    );
    // σ to the right the density falls towards +x: dark; σ to the left: bright.
    let at = |x: f32| {
        let i = ((x + HALF) / (2.0 * HALF) * SIZE as f32) as u32;
        run.image[(SIZE / 2 * SIZE + i) as usize][0]
    };
    assert!(
        at(SIGMA) < 0.3 && at(-SIGMA) > 0.7,
        "right {} left {}",
        at(SIGMA),
        at(-SIGMA)
    );
}

/// Turning the knife edge by 90° shows ε_y instead of ε_x: for the round blob, the picture
/// mirrored across the anti-diagonal (x ↔ y), within the f16 output's rounding.
#[test]
fn turning_the_knife_edge_by_90_degrees_swaps_x_and_y() {
    let mut s = session();
    let volume = centred_blob();
    let gain = 0.5;
    let across = photograph(&mut s, &volume, "schlieren", gain, 0.0);
    let up = photograph(&mut s, &volume, "schlieren", gain, 90.0);
    let want = reference_integrals(&volume, Vec3::ZERO);
    compare(
        "knife edge at 90°",
        |i| up.image[i][0],
        |i| reference::knife_edge(want[i].0, Vec2::Y, gain, 1.0),
        0.01,
    );
    // Pixel (i, j) at 90° is world (x_i, −x_j); at 0° that is pixel (n − j, n − i).
    let n = SIZE as usize - 1;
    compare(
        "90° vs 0° mirrored",
        |p| up.image[p][0],
        |p| {
            let (i, j) = (p % SIZE as usize, p / SIZE as usize);
            across.image[(n - i) * SIZE as usize + (n - j)][0]
        },
        2e-3,
    );
    // Upwards the density falls: dark above the centre, bright below.
    let above = up.image[(SIZE / 2 - 8) as usize * SIZE as usize + SIZE as usize / 2][0];
    let below = up.image[(SIZE / 2 + 8) as usize * SIZE as usize + SIZE as usize / 2][0];
    assert!(above < 0.3 && below > 0.7, "above {above} below {below}");
}

/// Eq. 2 and 5: L within 0.02 value ranges per voxel (its value at the centre is
/// −2√(2π)/σ · spacing ≈ −0.63), the shadowgraph within 0.01; dark at the centre (L < 0),
/// brighter than the background on the ring s > √2 σ.
#[test]
fn shadowgraph_of_a_gaussian_blob_follows_eq_2_and_5() {
    let mut s = session();
    let volume = centred_blob();
    let gain = 1.0;
    let run = photograph(&mut s, &volume, "shadowgraph", gain, 0.0);
    let want = reference_integrals(&volume, Vec3::ZERO);
    compare("L", |i| run.deflection[i][2], |i| want[i].1, 0.02);
    compare(
        "shadowgraph (eq. 5)",
        |i| run.image[i][0],
        |i| reference::shadowgraph(want[i].1, gain, 1.0),
        0.01,
    );
    let c = centre_pixel();
    assert!(run.image[c][0] < 0.25, "centre {}", run.image[c][0]);
    let ring = c + (2.0 * SIGMA / (2.0 * HALF) * SIZE as f32) as usize;
    assert!(run.image[ring][0] > 0.5, "ring {}", run.image[ring][0]);
    // The absolute value (Fig. 13e): never darker than the background.
    let abs = photograph(&mut s, &volume, "shadowgraph_abs", gain, 0.0);
    compare(
        "shadowgraph |L|",
        |i| abs.image[i][0],
        |i| reference::shadowgraph(want[i].1.abs(), gain, 1.0),
        0.01,
    );
}

/// Eq. 4 (the circular cutoff: |ε|, black where nothing deflects; within 0.015, the gain times
/// the deflection's tolerance) and the colour Schlieren (hue
/// the direction of ε: red where it points right, cyan left; white where it vanishes).
#[test]
fn circular_cutoff_and_colour_schlieren_show_the_deflections_length_and_direction() {
    let mut s = session();
    let volume = centred_blob();
    let gain = 0.5;
    let run = photograph(&mut s, &volume, "schlieren_circular", gain, 0.0);
    let want = reference_integrals(&volume, Vec3::ZERO);
    compare(
        "circular cutoff (eq. 4)",
        |i| run.image[i][0],
        |i| reference::circular(want[i].0, gain, 1.0),
        0.015,
    );
    assert!(run.image[centre_pixel()][0] < 2e-3);
    let colour = photograph(&mut s, &volume, "schlieren_color", 1.0, 0.0);
    let c = centre_pixel();
    assert!(
        colour.image[c].iter().all(|v| (v - 1.0).abs() < 2e-3),
        "centre {:?}",
        colour.image[c]
    );
    // Left of the centre the density grows to the right: ε points right (hue 0, red); right of
    // it, left (cyan).
    let [r, g, b, _] = colour.image[c - 8];
    assert!(
        r > 0.99 && g < 0.5 && b < 0.5,
        "left of centre {:?}",
        [r, g, b]
    );
    let [r, g, b, _] = colour.image[c + 8];
    assert!(
        r < 0.5 && g > 0.99 && b > 0.99,
        "right of centre {:?}",
        [r, g, b]
    );
}

/// The voxel → world transform is honoured: a grid rotated 30° about z, its k axis flipped,
/// spacing anisotropic, holding the blob at c = (0.2, −0.15, 0.1), shows the blob at c.
#[test]
fn the_blob_lands_where_the_voxel_to_world_transform_puts_it() {
    let mut s = session();
    let centre = Vec3::new(0.2, -0.15, 0.1);
    let angle = 30f64.to_radians();
    let direction =
        DMat3::from_rotation_z(angle) * DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
    let spacing = DVec3::new(1.9 / 64.0, 2.1 / 64.0, 2.0 / 64.0);
    let half = spacing * (N - 1) as f64 / 2.0;
    let geometry = Geometry {
        spacing,
        direction,
        origin: centre.as_dvec3() - direction * half,
    };
    let volume = blob(geometry, centre);
    let gain = 0.5;
    let run = photograph(&mut s, &volume, "schlieren", gain, 0.0);
    let want = reference_integrals(&volume, centre);
    // Only where the rotated box covers the whole blob column (inside 0.85 of the centre).
    let inside = |i: usize| {
        let (x, y) = pixel_world(i as u32 % SIZE, i as u32 / SIZE);
        Vec2::new(x - centre.x, y - centre.y).length() < 0.85
    };
    compare(
        "ε_x, transformed grid",
        |i| if inside(i) { run.deflection[i][0] } else { 0.0 },
        |i| if inside(i) { want[i].0.x } else { 0.0 },
        0.03,
    );
    compare(
        "knife edge, transformed grid",
        |i| if inside(i) { run.image[i][0] } else { 0.0 },
        |i| {
            if inside(i) {
                reference::knife_edge(want[i].0, Vec2::X, gain, 1.0)
            } else {
                0.0
            }
        },
        0.01,
    );
}

/// The fragment and compute paths cast the same rays: the same pictures.
#[test]
fn fragment_and_compute_paths_give_the_same_picture() {
    let mut s = session();
    let volume = centred_blob();
    let fragment = schlieren(&mut s, &volume, &[("kernel", choice("fragment"))]);
    let compute = schlieren(&mut s, &volume, &[("kernel", choice("compute"))]);
    compare(
        "compute vs fragment",
        |i| compute.image[i][0],
        |i| fragment.image[i][0],
        1e-3,
    );
    compare(
        "compute vs fragment ε_x",
        |i| compute.deflection[i][0],
        |i| fragment.deflection[i][0],
        1e-3,
    );
}
