//! HatchStrokes (Nagy et al. 2002; Yuan & Chen 2005 §4.4) on analytic surfaces: on a cylinder
//! seen orthographically across its axis the strokes run around it (the larger-|κ| direction
//! projects to the screen's x axis), stroke density rises with darkness (nested seed sets), the
//! same surface seeds survive a 1° orbit, the mask covers the polylines, and SaveSvg writes one
//! polyline per stroke.

mod common;

use glam::{Vec2, Vec3};
use hatchery_data::VolumeData;
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::hatch_strokes::StrokeLine;
use hatchery_nodes::value::{Mask, Volume};
use hatchery_nodes::{Session, Value, export};
use std::collections::BTreeSet;
use std::sync::Arc;

const N: u32 = 96;
const SIZE: u32 = 128;
/// Cylinder radius (world units; the volume spans [-1, 1]³).
const R: f32 = 0.6;

/// `f` sampled on an N³ grid over world [-1, 1]³.
fn field(f: impl Fn(Vec3) -> f32) -> VolumeData {
    common::field_on_cube(N, f)
}

/// A cylinder of radius R around the y axis (positive inside).
fn cylinder() -> Value {
    let volume = field(|p| R - (p.x * p.x + p.z * p.z).sqrt());
    Value::Volume(Arc::new(Volume::new(volume)))
}

/// A camera looking at the origin from 5 units away, `azimuth` degrees around y, showing about
/// [-1.1, 1.1]².
fn camera(azimuth: f32, orthographic: bool) -> Value {
    let fov = 2.0 * (1.1f32 / 5.0).atan().to_degrees();
    Value::Camera(Arc::new(Camera::orbit(
        Vec3::ZERO,
        azimuth,
        0.0,
        5.0,
        fov,
        orthographic,
        0.1,
        20.0,
        false,
        SIZE,
        SIZE,
    )))
}

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// A constant-brightness tone mask.
fn tone(session: &Session, brightness: f32) -> Value {
    let data = vec![brightness; (SIZE * SIZE) as usize];
    let texture = session.ctx.gpu.texture_2d_init(
        "tone",
        SIZE,
        SIZE,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&data),
    );
    Value::Mask(Arc::new(Mask { texture }))
}

/// The surface's G-buffer, curvature and seed mesh.
struct Surface {
    gbuffer: Value,
    curvature: Value,
    seeds: Value,
}

fn surface(session: &mut Session, volume: &Value, camera: Value) -> Surface {
    let gbuffer = common::run_node(
        session,
        "IsoSurfaceRaycast",
        vec![("volume", volume.clone()), ("camera", camera)],
        &[
            ("iso", ParamValue::Float(0.0)),
            ("step", ParamValue::Float(0.25)),
        ],
    )
    .remove(0);
    let curvature = common::run_node(
        session,
        "Curvature",
        vec![("gbuffer", gbuffer.clone()), ("volume", volume.clone())],
        &[],
    )
    .remove(0);
    let seeds = common::run_node(
        session,
        "MarchingCubes",
        vec![("volume", volume.clone())],
        &[("iso", ParamValue::Float(0.0))],
    )
    .remove(0);
    Surface {
        gbuffer,
        curvature,
        seeds,
    }
}

/// HatchStrokes on `surface`: (mask values row-major, strokes).
fn hatch(
    session: &mut Session,
    surface: &Surface,
    tone: Option<Value>,
    params: &[(&str, ParamValue)],
) -> (Vec<f32>, Vec<StrokeLine>) {
    let mut inputs = vec![
        ("curvature", surface.curvature.clone()),
        ("gbuffer", surface.gbuffer.clone()),
        ("seeds", surface.seeds.clone()),
    ];
    if let Some(t) = tone {
        inputs.push(("tone", t));
    }
    let out = common::run_node(session, "HatchStrokes", inputs, params);
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let mask = export::to_array(&out[0], &session.ctx.gpu).unwrap().data;
    let strokes = match &out[1] {
        Value::Strokes(s) => s.lines(&session.ctx.gpu).unwrap().to_vec(),
        other => panic!("strokes output is a {}", other.port_type()),
    };
    (mask, strokes)
}

#[test]
fn strokes_on_a_cylinder_run_around_it() {
    let mut session = session();
    let volume = cylinder();
    let surface = surface(&mut session, &volume, camera(0.0, true));
    let dark = tone(&session, 0.0);
    let (mask, strokes) = hatch(
        &mut session,
        &surface,
        Some(dark),
        &[
            ("density", ParamValue::Float(0.3)),
            ("cross_hatching", ParamValue::Float(1.0)),
        ],
    );
    // Segment directions against the circumferential direction, which projects onto the screen's
    // x axis everywhere on the cylinder (seen along −z across its axis y). Length-weighted.
    let (mut total, mut within, mut worst) = (0.0f32, 0.0f32, 0.0f32);
    let mut drawn = 0;
    for line in &strokes {
        if line.points.len() < 2 {
            continue;
        }
        drawn += 1;
        for pair in line.points.windows(2) {
            let d = pair[1] - pair[0];
            let length = d.length();
            let angle = (d.y.abs() / length.max(1e-9)).asin().to_degrees();
            total += length;
            if angle <= 5.0 {
                within += length;
            }
            worst = worst.max(angle);
        }
    }
    eprintln!(
        "cylinder: {} strokes ({drawn} with a segment), {:.1} % of their length within 5° of \
         the circumferential direction, worst segment {worst:.1}°",
        strokes.len(),
        100.0 * within / total
    );
    assert!(drawn >= 30, "only {drawn} strokes drawn");
    assert!(
        within >= 0.95 * total,
        "{:.1} % of the stroke length within 5°",
        100.0 * within / total
    );
    assert!(strokes.iter().all(|l| !l.cross), "cross-hatching was off");

    // The mask covers the strokes: near every stroke point (3×3 pixels) the coverage is > 0.5.
    let mut uncovered = 0;
    let mut points = 0;
    for line in strokes.iter().filter(|l| l.points.len() >= 5) {
        // The tapered ends thin out: check the middle half of each stroke.
        let n = line.points.len();
        for q in &line.points[n / 4..n - n / 4] {
            points += 1;
            let (x, y) = (q.x.floor() as i32, q.y.floor() as i32);
            let covered = (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (u, v) = (x + dx, y + dy);
                    (0..SIZE as i32).contains(&u)
                        && (0..SIZE as i32).contains(&v)
                        && mask[(v * SIZE as i32 + u) as usize] > 0.5
                })
            });
            uncovered += usize::from(!covered);
        }
    }
    assert!(points > 100, "{points} stroke points checked");
    assert_eq!(
        uncovered, 0,
        "{uncovered} of {points} stroke points not in the mask"
    );
    // And nothing is drawn off the surface (outside the cylinder's silhouette |x| > R).
    let pixel_of_r = R / 1.1 * SIZE as f32 / 2.0;
    for (i, &m) in mask.iter().enumerate() {
        let x = (i as u32 % SIZE) as f32 + 0.5 - SIZE as f32 / 2.0;
        if x.abs() > pixel_of_r + 3.0 {
            assert!(m == 0.0, "stroke ink at pixel {i} outside the cylinder");
        }
    }
}

#[test]
fn stroke_density_rises_with_darkness() {
    let mut session = session();
    let volume = cylinder();
    let surface = surface(&mut session, &volume, camera(0.0, true));
    let mut previous: Option<BTreeSet<u32>> = None;
    let mut counts = Vec::new();
    for brightness in [0.9, 0.7, 0.5, 0.3, 0.1] {
        let t = tone(&session, brightness);
        let (mask, strokes) = hatch(
            &mut session,
            &surface,
            Some(t),
            &[("cross_hatching", ParamValue::Float(1.0))],
        );
        let seeds: BTreeSet<u32> = strokes.iter().map(|l| l.seed).collect();
        let ink: f32 = mask.iter().sum();
        counts.push((1.0 - brightness, seeds.len(), ink));
        if let Some(lighter) = &previous {
            assert!(
                seeds.len() > lighter.len(),
                "darkness {}: {} strokes, not more than the lighter tone's {}",
                1.0 - brightness,
                seeds.len(),
                lighter.len()
            );
            // Yuan–Chen's test u < density · darkness: a darker tone keeps the lighter's seeds.
            assert!(lighter.is_subset(&seeds), "a lighter tone's seed vanished");
        }
        previous = Some(seeds);
    }
    eprintln!("darkness → strokes, ink: {counts:?}");
    for pair in counts.windows(2) {
        assert!(pair[1].2 > pair[0].2, "ink did not rise: {counts:?}");
    }
    // Proportional in expectation: strokes / darkness varies by less than a factor 1.5.
    let rates: Vec<f32> = counts.iter().map(|(d, n, _)| *n as f32 / d).collect();
    let (lo, hi) = rates
        .iter()
        .fold((f32::MAX, 0.0f32), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    assert!(hi < 1.5 * lo, "strokes per darkness {rates:?}");
}

#[test]
fn dark_tones_cross_hatch_along_the_other_direction() {
    let mut session = session();
    let volume = cylinder();
    let surface = surface(&mut session, &volume, camera(0.0, true));
    let dark = tone(&session, 0.1);
    let (_, strokes) = hatch(
        &mut session,
        &surface,
        Some(dark),
        &[
            ("density", ParamValue::Float(0.2)),
            ("cross_hatching", ParamValue::Float(0.6)),
        ],
    );
    let cross: Vec<&StrokeLine> = strokes.iter().filter(|l| l.cross).collect();
    let main = strokes.len() - cross.len();
    // Every seed of a tone this dark draws both strokes (a seed on the silhouette may stop at once
    // in one direction: such strokes are left out).
    let seeds = |cross: bool| -> BTreeSet<u32> {
        strokes
            .iter()
            .filter(|l| l.cross == cross)
            .map(|l| l.seed)
            .collect()
    };
    let (main_seeds, cross_seeds) = (seeds(false), seeds(true));
    let both = main_seeds.intersection(&cross_seeds).count();
    eprintln!(
        "cross-hatching: {main} strokes, {} cross, {both} seeds with both",
        cross.len()
    );
    assert!(main > 20 && both as f32 >= 0.9 * main as f32);
    // The second direction on a cylinder is its axis: the screen's y axis.
    let (mut total, mut within) = (0.0f32, 0.0f32);
    for line in &cross {
        for pair in line.points.windows(2) {
            let d = pair[1] - pair[0];
            total += d.length();
            if (d.x.abs() / d.length().max(1e-9)).asin().to_degrees() <= 5.0 {
                within += d.length();
            }
        }
    }
    assert!(total > 0.0);
    assert!(
        within >= 0.95 * total,
        "{:.1} % within 5°",
        100.0 * within / total
    );
}

#[test]
fn seeds_stay_on_the_surface_through_a_small_orbit() {
    let mut session = session();
    let volume = cylinder();
    let dark = tone(&session, 0.0);
    let mut seed_sets = Vec::new();
    for azimuth in [0.0, 1.0] {
        let surface = surface(&mut session, &volume, camera(azimuth, false));
        let (_, strokes) = hatch(
            &mut session,
            &surface,
            Some(dark.clone()),
            &[("cross_hatching", ParamValue::Float(1.0))],
        );
        seed_sets.push(strokes.iter().map(|l| l.seed).collect::<BTreeSet<u32>>());
    }
    let survived = seed_sets[0].intersection(&seed_sets[1]).count();
    eprintln!(
        "1° orbit: {survived} of {} seeds survive ({} after)",
        seed_sets[0].len(),
        seed_sets[1].len()
    );
    assert!(seed_sets[0].len() > 50);
    assert!(
        survived as f32 >= 0.95 * seed_sets[0].len() as f32,
        "only {survived} of {} seeds survive a 1° orbit",
        seed_sets[0].len()
    );
}

#[test]
fn save_svg_writes_one_polyline_per_stroke() {
    let mut session = session();
    let volume = cylinder();
    let surface = surface(&mut session, &volume, camera(0.0, true));
    let dark = tone(&session, 0.2);
    let out = common::run_node(
        &mut session,
        "HatchStrokes",
        vec![
            ("curvature", surface.curvature.clone()),
            ("gbuffer", surface.gbuffer.clone()),
            ("seeds", surface.seeds.clone()),
            ("tone", dark),
        ],
        &[],
    );
    let Value::Strokes(strokes) = &out[1] else {
        panic!("no strokes")
    };
    let lines = strokes.lines(&session.ctx.gpu).unwrap().to_vec();
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let dir = std::env::temp_dir().join(format!("hatchery-hatching-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("strokes.svg");
    common::run_node(
        &mut session,
        "SaveSvg",
        vec![("strokes", out[1].clone())],
        &[(
            "path",
            ParamValue::Path(path.to_string_lossy().into_owned()),
        )],
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let layer = doc
        .descendants()
        .find(|n| n.has_tag_name("g") && n.attribute("id") == Some("strokes"))
        .expect("a strokes layer");
    let paths: Vec<_> = layer
        .descendants()
        .filter(|n| n.has_tag_name("path"))
        .collect();
    // `lines` holds the strokes with at least one segment: one path each.
    assert!(lines.len() > 10);
    assert!(lines.iter().all(|l| l.points.len() >= 2));
    assert_eq!(paths.len(), lines.len(), "one path per stroke");
    // The first stroke's first point is where the SVG's first path starts.
    let first = lines.iter().find(|l| l.points.len() >= 2).unwrap();
    let d = paths[0].attribute("d").unwrap();
    let numbers: Vec<f32> = d
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    assert!(
        (Vec2::new(numbers[0], numbers[1]) - first.points[0]).length() < 0.01,
        "path starts at {:?}, stroke at {:?}",
        &numbers[..2],
        first.points[0]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// CurvatureFlow on the cylinder: (mean |∂x|, mean |∂y|, standard deviation) of the flow over
/// the middle of the cylinder's face.
fn flow_gradients(direction: &str) -> (f32, f32, f32) {
    let mut session = session();
    let volume = cylinder();
    let surface = surface(&mut session, &volume, camera(0.0, true));
    let out = common::run_node(
        &mut session,
        "CurvatureFlow",
        vec![
            ("curvature", surface.curvature.clone()),
            ("gbuffer", surface.gbuffer.clone()),
        ],
        &[
            ("grain", ParamValue::Float(0.02)),
            ("direction", ParamValue::Choice(direction.into())),
        ],
    );
    let errors = session.ctx.gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:?}");
    let v = export::to_array(&out[0], &session.ctx.gpu).unwrap().data;
    let at = |x: u32, y: u32| v[(y * SIZE + x) as usize];
    // The middle: |x| < R/2 and |y| < 0.8 (world), away from the silhouette and the ends.
    let px = |w: f32| (w / 1.1 * SIZE as f32 / 2.0) as u32;
    let (c, hx, hy) = (SIZE / 2, px(R / 2.0), px(0.8));
    let (mut dx, mut dy, mut n) = (0.0f32, 0.0f32, 0.0f32);
    let mut values = Vec::new();
    for y in c - hy..c + hy {
        for x in c - hx..c + hx {
            dx += (at(x + 1, y) - at(x, y)).abs();
            dy += (at(x, y + 1) - at(x, y)).abs();
            n += 1.0;
            values.push(at(x, y));
        }
    }
    let mean = values.iter().sum::<f32>() / n;
    let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / n).sqrt();
    (dx / n, dy / n, sd)
}

#[test]
fn curvature_flow_streaks_follow_the_principal_direction() {
    // Around the cylinder (larger |κ|): streaks along x, so the flow varies little along x.
    let (dx, dy, sd) = flow_gradients("max_curvature");
    eprintln!("flow around: mean |∂x| {dx:.4}, |∂y| {dy:.4}, sd {sd:.3}");
    assert!(sd > 0.05, "the flow is flat (sd {sd})");
    assert!(dx < 0.4 * dy, "not streaked along x: |∂x| {dx}, |∂y| {dy}");
    // Along the axis (smaller |κ|): streaks along y.
    let (dx, dy, sd) = flow_gradients("min_curvature");
    eprintln!("flow along the axis: mean |∂x| {dx:.4}, |∂y| {dy:.4}, sd {sd:.3}");
    assert!(sd > 0.05, "the flow is flat (sd {sd})");
    assert!(dy < 0.4 * dx, "not streaked along y: |∂x| {dx}, |∂y| {dy}");
}

#[test]
fn strokes_follow_the_projected_circumferential_direction_in_perspective() {
    // Seen in perspective the circles around the cylinder project to curves (ellipse arcs above
    // and below the eye level): the expected screen direction at a stroke point is the
    // projection of the circumferential tangent at its surface point.
    let mut session = session();
    let volume = cylinder();
    let camera_value = camera(20.0, false);
    let Value::Camera(cam) = &camera_value else {
        unreachable!()
    };
    let cam = cam.as_ref().clone();
    let surface = surface(&mut session, &volume, camera_value);
    let dark = tone(&session, 0.0);
    let (_, strokes) = hatch(
        &mut session,
        &surface,
        Some(dark),
        &[
            ("density", ParamValue::Float(0.3)),
            ("cross_hatching", ParamValue::Float(1.0)),
        ],
    );
    let depth = export::to_array(&surface.gbuffer, &session.ctx.gpu)
        .unwrap()
        .data;
    let view_proj = cam.view_proj();
    let inverse = view_proj.inverse();
    let to_screen = |p: Vec3| {
        let n = view_proj.project_point3(p);
        Vec2::new(
            (n.x + 1.0) * 0.5 * SIZE as f32,
            (1.0 - n.y) * 0.5 * SIZE as f32,
        )
    };
    let (mut total, mut within, mut tilted) = (0.0f32, 0.0f32, 0.0f32);
    for line in &strokes {
        for pair in line.points.windows(2) {
            let mid = 0.5 * (pair[0] + pair[1]);
            let (x, y) = (mid.x as u32, mid.y as u32);
            let d = depth[((y * SIZE + x) * 4) as usize];
            if d >= 1.0 {
                continue;
            }
            let ndc = Vec2::new(
                mid.x / SIZE as f32 * 2.0 - 1.0,
                1.0 - mid.y / SIZE as f32 * 2.0,
            );
            let p = inverse.project_point3(ndc.extend(d));
            let t = Vec3::new(-p.z, 0.0, p.x).normalize();
            let expected = (to_screen(p + 0.01 * t) - to_screen(p)).normalize();
            let got = pair[1] - pair[0];
            let length = got.length();
            let sin = (expected.perp_dot(got) / length.max(1e-9)).abs().min(1.0);
            total += length;
            if sin.asin().to_degrees() <= 5.0 {
                within += length;
            }
            // How far from horizontal the expected direction is (perspective at work).
            tilted = tilted.max(expected.y.abs().asin().to_degrees());
        }
    }
    eprintln!(
        "perspective: {} strokes, {:.1} % of their length within 5° of the projected \
         circumferential direction (which tilts up to {tilted:.1}° from horizontal)",
        strokes.len(),
        100.0 * within / total
    );
    assert!(
        tilted > 3.0,
        "the view shows no perspective tilt ({tilted:.1}°)"
    );
    assert!(
        within >= 0.95 * total,
        "{:.1} % within 5°",
        100.0 * within / total
    );
}
