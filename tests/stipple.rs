//! Stipple (Preim & Tietjen in Viola et al.'s 2005 tutorial, §2.1 and §6; "Efficient
//! Texture-based Stippling"): dots whose density gives the tone and that stick to the surface.
//!
//! - Tone: on a plane facing an orthographic camera, and on one tilted 60° away from it, under a
//!   constant intensity I, the ink fraction of the frame's middle is the darkness 1 − I (the
//!   rule the node implements: coverage = darkness, up to 1 − exp(−π·radius²/spacing²)), at two
//!   zooms (different levels of detail). Tolerance 0.03 absolute.
//! - Stability: a sphere seen orthographically, then orbited by 5°: the centres of the dots of the
//!   first frame, carried through the known camera motion onto the second, find a dot there within
//!   1 px (at least 85 %); the same check against an unmoved, screen-fixed pattern (the first
//!   frame's dots) finds at most 20 %.
//! - `--scale 2` (the executor's pixel scale): the same dots (count within 5 %) with four times the
//!   ink each (dot radius doubled in pixels), the same tone within 0.01.

mod common;

use glam::{Vec2, Vec3, Vec4};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{Mask, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const N: u32 = 96;
const SIZE: u32 = 160;

fn volume(f: impl Fn(Vec3) -> f32) -> Value {
    Value::Volume(Arc::new(Volume::new(common::field_on_cube(N, f))))
}

/// An orthographic camera looking at the origin from 5 units away, `azimuth` degrees around y,
/// showing [−extent, extent]².
fn camera(azimuth: f32, extent: f32) -> Camera {
    let fov = 2.0 * (extent / 5.0).atan().to_degrees();
    let (near, far) = (0.1, 20.0);
    Camera::orbit(
        Vec3::ZERO,
        azimuth,
        0.0,
        5.0,
        fov,
        true,
        near,
        far,
        false,
        SIZE,
        SIZE,
    )
}

/// A session for single nodes at SIZE².
fn session() -> Session {
    let graph = r#"(version: 1, nodes: [])"#;
    common::session_from_text(graph, SIZE, SIZE)
}

/// The ink (1 − mask) of Stipple on the iso-surface 0 of `volume` seen by `camera`.
fn stipple(
    session: &mut Session,
    volume: &Value,
    camera: &Camera,
    intensity: f32,
    params: &[(&str, ParamValue)],
) -> Vec<f32> {
    let gbuffer = common::run_node(
        session,
        "IsoSurfaceRaycast",
        vec![
            ("volume", volume.clone()),
            ("camera", Value::Camera(Arc::new(camera.clone()))),
        ],
        &[
            ("iso", ParamValue::Float(0.0)),
            ("step", ParamValue::Float(0.25)),
        ],
    )
    .remove(0);
    // A constant intensity.
    let data = vec![intensity; (SIZE * SIZE) as usize];
    let format = wgpu::TextureFormat::R32Float;
    let bytes = bytemuck::cast_slice(&data);
    let texture = (session.ctx.gpu).texture_2d_init("tone", SIZE, SIZE, format, bytes);
    let intensity = Value::Mask(Arc::new(Mask { texture }));
    let out = common::run_node(
        session,
        "Stipple",
        vec![("intensity", intensity), ("gbuffer", gbuffer)],
        params,
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let mask = export::to_array(&out[0], &session.ctx.gpu).unwrap().data;
    mask.iter().map(|m| 1.0 - m).collect()
}

/// Mean ink over the pixels (x, y) with x in `xs`, y in `ys`.
fn ink_fraction(
    ink: &[f32],
    width: u32,
    xs: std::ops::Range<u32>,
    ys: std::ops::Range<u32>,
) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for y in ys {
        for x in xs.clone() {
            sum += ink[(y * width + x) as usize] as f64;
            n += 1;
        }
    }
    sum / n as f64
}

/// Connected (4-neighbour) components of ink > 0.5: (centroid in pixel coordinates, pixel
/// centres at +0.5; summed ink, with the anti-aliased rim of a dot of `radius` pixels).
fn dots(ink: &[f32], width: u32, height: u32, radius: f32) -> Vec<(Vec2, f32)> {
    let mut seen = vec![false; ink.len()];
    let mut found = Vec::new();
    for start in 0..ink.len() {
        if seen[start] || ink[start] <= 0.5 {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let (mut sum, mut weighted, mut total) = (Vec2::ZERO, 0.0f32, 0.0f32);
        while let Some(i) = stack.pop() {
            let (x, y) = ((i as u32 % width) as i32, (i as u32 / width) as i32);
            let w = ink[i];
            sum += Vec2::new(x as f32 + 0.5, y as f32 + 0.5) * w;
            weighted += w;
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                let (u, v) = (x + dx, y + dy);
                if u < 0 || v < 0 || u >= width as i32 || v >= height as i32 {
                    continue;
                }
                let j = (v as u32 * width + u as u32) as usize;
                if !seen[j] && ink[j] > 0.5 {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        // The dot's whole ink: its core plus the anti-aliased rim (ink ≤ 0.5) around it.
        let c = sum / weighted;
        let rim = radius + 1.0;
        for y in (c.y - rim).floor() as i32..=(c.y + rim).ceil() as i32 {
            for x in (c.x - rim).floor() as i32..=(c.x + rim).ceil() as i32 {
                if x < 0 || y < 0 || x >= width as i32 || y >= height as i32 {
                    continue;
                }
                let w = ink[(y as u32 * width + x as u32) as usize];
                if w <= 0.5 && (Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - c).length() < rim {
                    total += w;
                }
            }
        }
        found.push((c, weighted + total));
    }
    found
}

#[test]
fn ink_coverage_is_the_darkness() {
    let mut session = session();
    // A plane through the origin facing the camera (normal +z), and one tilted 60° about y.
    let facing = volume(|p| -p.z);
    let (s, c) = 60f32.to_radians().sin_cos();
    let tilted = volume(move |p| -(p.x * s + p.z * c));
    let params = [
        ("spacing", ParamValue::Float(3.0)),
        ("radius", ParamValue::Float(1.5)),
    ];
    let ceiling = 1.0 - (-std::f64::consts::PI * 1.5 * 1.5 / 9.0).exp();
    let mut worst = 0.0f64;
    for extent in [1.1f32, 0.8] {
        let cam = camera(0.0, extent);
        // Pixels per world unit, and the plane's middle in pixels (the tilted plane leaves the
        // volume at |x| = cot 60° ≈ 0.577).
        let scale = SIZE as f32 / (2.0 * extent);
        let half_tilted = (0.5 * scale) as u32;
        for (name, surface, xs) in [
            ("facing", &facing, 20..SIZE - 20),
            (
                "tilted 60°",
                &tilted,
                SIZE / 2 - half_tilted..SIZE / 2 + half_tilted,
            ),
        ] {
            for intensity in [0.95f32, 0.85, 0.75, 0.65, 0.55] {
                let darkness = 1.0 - intensity as f64;
                assert!(darkness < ceiling);
                // Four dot patterns (seeds), to average the pattern's own noise.
                let mut fraction = 0.0;
                for seed in 0..4 {
                    let mut params = params.to_vec();
                    params.push(("seed", ParamValue::Int(seed)));
                    let ink = stipple(&mut session, surface, &cam, intensity, &params);
                    fraction += ink_fraction(&ink, SIZE, xs.clone(), 20..SIZE - 20) / 4.0;
                }
                eprintln!(
                    "{name}, extent {extent}: darkness {darkness:.2}, ink fraction {fraction:.4} \
                     (error {:+.4})",
                    fraction - darkness
                );
                worst = worst.max((fraction - darkness).abs());
            }
        }
    }
    eprintln!("worst |ink fraction − darkness| {worst:.4}");
    assert!(worst <= 0.03, "ink fraction off the darkness by {worst:.4}");
}

/// The world point of the sphere of radius `r` (centre 0) seen at pixel position `at` by the
/// orthographic `camera`, if the ray meets it.
fn on_sphere(camera: &Camera, at: Vec2, r: f32) -> Option<Vec3> {
    let ndc = Vec2::new(
        at.x / camera.width as f32 * 2.0 - 1.0,
        1.0 - at.y / camera.height as f32 * 2.0,
    );
    let inverse = camera.view_proj().inverse();
    let unproject = |z: f32| {
        let p = inverse * Vec4::new(ndc.x, ndc.y, z, 1.0);
        p.truncate() / p.w
    };
    let (near, far) = (unproject(0.0), unproject(1.0));
    let d = (far - near).normalize();
    // |near + t d|² = r²
    let b = near.dot(d);
    let disc = b * b - (near.length_squared() - r * r);
    (disc >= 0.0).then(|| near + d * (-b - disc.sqrt()))
}

/// Pixel position of world point `p` for `camera`.
fn project(camera: &Camera, p: Vec3) -> Vec2 {
    let c = camera.view_proj() * p.extend(1.0);
    let ndc = c.truncate() / c.w;
    Vec2::new(
        (ndc.x + 1.0) * 0.5 * camera.width as f32,
        (1.0 - ndc.y) * 0.5 * camera.height as f32,
    )
}

#[test]
fn dots_stick_to_the_surface_when_the_camera_orbits() {
    const R: f32 = 0.8;
    let mut session = session();
    let sphere = volume(|p| R - p.length());
    let (first, second) = (camera(0.0, 1.1), camera(5.0, 1.1));
    let eye2 = second.eye.normalize();
    let near = |set: &[(Vec2, f32)], at: Vec2| set.iter().any(|(c, _)| (*c - at).length() <= 1.0);
    let (mut checked, mut moved_with_surface, mut screen_fixed, mut motion) = (0, 0, 0, 0.0);
    let (mut all1, mut all2) = (0, 0);
    // Three dot patterns (seeds), for enough single dots.
    for seed in 0..3 {
        let params = [
            ("spacing", ParamValue::Float(4.0)),
            ("radius", ParamValue::Float(1.2)),
            ("seed", ParamValue::Int(seed)),
        ];
        let ink1 = stipple(&mut session, &sphere, &first, 0.92, &params);
        let ink2 = stipple(&mut session, &sphere, &second, 0.92, &params);
        let dots1 = dots(&ink1, SIZE, SIZE, 1.2);
        let dots2 = dots(&ink2, SIZE, SIZE, 1.2);
        all1 += dots1.len();
        all2 += dots2.len();
        // Each first-frame dot well inside the sphere's disc in both frames (the rim is where the
        // foreshortening thins dots and the iso-surface's sampling matters), carried to the second.
        for (c, ink) in &dots1 {
            // Single dots, at least 4 px from any other: near ones merge or part on the pixel grid.
            let single = std::f32::consts::PI * 1.7 * 1.7;
            let alone = dots1
                .iter()
                .all(|(d, _)| d == c || (*d - *c).length() > 4.0);
            if *ink > single || !alone {
                continue;
            }
            let Some(p) = on_sphere(&first, *c, R) else {
                continue;
            };
            if p.normalize().dot(first.eye.normalize()) < 0.5 || p.normalize().dot(eye2) < 0.5 {
                continue;
            }
            let to = project(&second, p);
            checked += 1;
            motion += (to - *c).length();
            if near(&dots2, to) {
                moved_with_surface += 1;
            }
            // A pattern fixed on the screen would show the first frame's dots again.
            if near(&dots1, to) {
                screen_fixed += 1;
            }
        }
    }
    let rate = moved_with_surface as f64 / checked as f64;
    let fixed_rate = screen_fixed as f64 / checked as f64;
    eprintln!(
        "{checked} dots checked (of {} and {} in the frames), mean motion {:.2} px: {:.1} % found \
         where the surface carried them, {:.1} % where a screen-fixed pattern would be",
        all1,
        all2,
        motion / checked as f32,
        100.0 * rate,
        100.0 * fixed_rate
    );
    assert!(checked >= 150, "only {checked} dots checked");
    assert!(
        rate >= 0.95,
        "only {:.1} % of the dots moved with the surface",
        100.0 * rate
    );
    assert!(
        fixed_rate <= 0.2,
        "the check does not tell a screen-fixed pattern apart ({:.1} %)",
        100.0 * fixed_rate
    );
}

#[test]
fn scale_two_doubles_the_dots_in_pixels() {
    const BASE: u32 = 256;
    // A lit sphere through the executor, whose pixel scale multiplies `unit(pixels)` parameters.
    let text = r#"(version: 1, nodes: [
        (id: "volume", kind: "ProceduralVolume", params: {"shape": "sphere", "resolution": 96}),
        (id: "camera", kind: "Camera", params: {"projection": "orthographic", "framing": "fit"}),
        (id: "surface", kind: "IsoSurfaceRaycast", params: {"iso": 0.0}),
        (id: "light", kind: "Light", params: {"direction": [-0.4, 0.6, 1.0]}),
        (id: "tone", kind: "DiffuseIntensity"),
        (id: "stipple", kind: "Stipple", params: {"spacing": 8.0, "radius": 1.5}),
    ], edges: [
        (from: ("volume", "volume"), to: ("camera", "volume")),
        (from: ("volume", "volume"), to: ("surface", "volume")),
        (from: ("camera", "camera"), to: ("surface", "camera")),
        (from: ("surface", "gbuffer"), to: ("tone", "gbuffer")),
        (from: ("light", "light"), to: ("tone", "light")),
        (from: ("surface", "gbuffer"), to: ("stipple", "gbuffer")),
        (from: ("tone", "intensity"), to: ("stipple", "intensity")),
    ])"#;
    let mut session = common::session_from_text(text, BASE, BASE);
    let mut render = |scale: u32| {
        session.ctx.set_size(BASE * scale, BASE * scale).unwrap();
        session.ctx.set_pixel_scale(scale as f64);
        let value = session.evaluate("stipple", "mask").unwrap();
        let mask = export::to_array(&value, &session.ctx.gpu).unwrap().data;
        let ink: Vec<f32> = mask.iter().map(|m| 1.0 - m).collect();
        let size = BASE * scale;
        let fraction = ink_fraction(&ink, size, 0..size, 0..size);
        (fraction, dots(&ink, size, size, 1.5 * scale as f32))
    };
    let (tone1, dots1) = render(1);
    let (tone2, dots2) = render(2);
    // Each single dot of the 1× picture (no other within 6 px) found at twice its position in
    // the 2× picture (within 2 px), and the ink of the two.
    let (mut singles, mut matched, mut ratio) = (0, 0, 0.0);
    for (c, ink) in &dots1 {
        // One whole dot (ink about π·1.5²): not a fragment (the sphere's rim, seen edge-on, cuts
        // dots) nor overlapping dots, which part at 2× where the anti-aliased rim is thinner.
        let area = std::f32::consts::PI * 1.5 * 1.5;
        let whole = (0.6 * area..=1.4 * area).contains(ink);
        if !whole
            || dots1
                .iter()
                .any(|(d, _)| d != c && (*d - *c).length() <= 6.0)
        {
            continue;
        }
        singles += 1;
        if let Some((_, ink2)) = dots2.iter().find(|(d, _)| (*d - 2.0 * *c).length() <= 2.0) {
            matched += 1;
            ratio += ink2 / ink;
        }
    }
    let ratio = ratio / matched as f32;
    eprintln!(
        "scale 1: {} dots, {singles} single, tone {tone1:.4}; scale 2: {} dots, tone {tone2:.4}; \
         {matched} singles found at twice their position, {ratio:.3}× the ink",
        dots1.len(),
        dots2.len(),
    );
    assert!(singles >= 30, "only {singles} single dots");
    assert!(
        matched as f64 >= 0.95 * singles as f64,
        "{matched} of {singles} dots found at scale 2"
    );
    assert!(
        (ratio - 4.0).abs() <= 0.3,
        "a dot's ink grew {ratio:.2}× at scale 2 (4× expected)"
    );
    assert!(
        (tone2 - tone1).abs() <= 0.01,
        "tone {tone1:.4} vs {tone2:.4}"
    );
}
