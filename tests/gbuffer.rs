//! The G-buffer of a sphere against analytic depth and normals, for both projections.

mod common;

use common::Sample;
use glam::{Mat4, Vec3, Vec4};
use hatchery_nodes::export;

const RADIUS: f32 = 0.7;
const W: u32 = 160;
const H: u32 = 120;

fn graph(projection: &str, azimuth: f32, elevation: f32) -> String {
    format!(
        r#"(
    version: 1,
    nodes: [
        (id: "sphere", kind: "ProceduralVolume", params: {{"shape": "sphere", "radius": {RADIUS}, "resolution": 128}}),
        (id: "surface", kind: "MarchingCubes", params: {{"iso": 0.0}}),
        (id: "camera", kind: "Camera", params: {{"projection": "{projection}", "azimuth": {azimuth}, "elevation": {elevation}, "distance": 3.0, "fov": 35.0, "near": 0.5, "far": 10.0}}),
        (id: "gbuffer", kind: "GBuffer", params: {{}}),
    ],
    edges: [
        (from: ("sphere", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("gbuffer", "mesh")),
        (from: ("camera", "camera"), to: ("gbuffer", "camera")),
    ],
)"#
    )
}

/// Analytic first hit of the pixel's ray with the sphere at the origin: (window depth, view normal).
fn analytic(view: Mat4, proj: Mat4, x: u32, y: u32) -> Option<(f32, Vec3)> {
    let ndc_x = (x as f32 + 0.5) / W as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - (y as f32 + 0.5) / H as f32 * 2.0;
    let inverse = (proj * view).inverse();
    let unproject = |z: f32| {
        let p = inverse * Vec4::new(ndc_x, ndc_y, z, 1.0);
        p.truncate() / p.w
    };
    let (near, far) = (unproject(0.0), unproject(1.0));
    let dir = (far - near).normalize();
    // |near + t·dir|² = r²
    let b = near.dot(dir);
    let c = near.length_squared() - RADIUS * RADIUS;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    let hit = near + dir * t;
    let clip = proj * view * hit.extend(1.0);
    let normal = view.transform_vector3(hit.normalize());
    Some((clip.z / clip.w, normal))
}

fn check(projection: &str, azimuth: f32, elevation: f32) {
    let mut session = common::session_from_text(&graph(projection, azimuth, elevation), W, H);
    let value = session.evaluate("gbuffer", "gbuffer").unwrap();
    let hatchery_nodes::Value::GBuffer(gbuffer) = &value else {
        panic!("not a GBuffer")
    };
    let (view, proj) = (gbuffer.camera.view, gbuffer.camera.proj);
    let array = export::to_array(&value, &session.ctx.gpu).unwrap();
    assert_eq!(array.shape, vec![H as usize, W as usize, 4]);
    let picture = export::to_rgba8(&value, &session.ctx.gpu).unwrap();
    let texel = |x: u32, y: u32| {
        let i = ((y * W + x) * 4) as usize;
        (
            array.data[i],
            Vec3::new(array.data[i + 1], array.data[i + 2], array.data[i + 3]),
        )
    };

    let (mut depth_samples, mut normal_samples, mut empty_samples) = (vec![], vec![], vec![]);
    let inverse_proj = proj.inverse();
    let view_z = |depth: f32, x: u32, y: u32| {
        let ndc = Vec4::new(
            (x as f32 + 0.5) / W as f32 * 2.0 - 1.0,
            1.0 - (y as f32 + 0.5) / H as f32 * 2.0,
            depth,
            1.0,
        );
        let p = inverse_proj * ndc;
        p.z / p.w
    };
    for y in (1..H).step_by(3) {
        for x in (1..W).step_by(3) {
            let (depth, normal) = texel(x, y);
            match analytic(view, proj, x, y) {
                // Skip the outline, where the polygonal outline and the true circle differ by a pixel.
                Some((expected_depth, expected_normal)) if expected_normal.z > 0.2 => {
                    // Compare depths as view-space distances (world units), which is what a
                    // tessellation error is measured in.
                    let error = (view_z(depth, x, y) - view_z(expected_depth, x, y)).abs() as f64;
                    depth_samples.push(Sample {
                        x,
                        y,
                        what: format!("depth {depth} vs {expected_depth}"),
                        error,
                    });
                    let angle = normal
                        .normalize()
                        .dot(expected_normal)
                        .clamp(-1.0, 1.0)
                        .acos()
                        .to_degrees() as f64;
                    normal_samples.push(Sample {
                        x,
                        y,
                        what: format!("normal {normal} vs {expected_normal}"),
                        error: angle,
                    });
                }
                Some(_) => {}
                None => {
                    // Well outside the outline: empty.
                    let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
                    let outside = [(-2.0f32, 0.0f32), (2.0, 0.0), (0.0, -2.0), (0.0, 2.0)]
                        .iter()
                        .all(|(dx, dy)| {
                            analytic(
                                view,
                                proj,
                                (cx + dx).max(0.0) as u32,
                                (cy + dy).max(0.0) as u32,
                            )
                            .is_none()
                        });
                    if outside {
                        let error = ((depth - 1.0).abs() + normal.length()) as f64;
                        empty_samples.push(Sample {
                            x,
                            y,
                            what: format!("background depth {depth}, normal {normal}"),
                            error,
                        });
                    }
                }
            }
        }
    }
    let name = format!("gbuffer_{projection}_{azimuth}_{elevation}");
    // Half a voxel of the 128³ grid over [-1, 1] is 0.008 world units.
    common::assert_samples(
        &format!("{name}_depth"),
        &depth_samples,
        0.008,
        Some(&picture),
    );
    common::assert_samples(
        &format!("{name}_normal"),
        &normal_samples,
        2.0,
        Some(&picture),
    );
    common::assert_samples(
        &format!("{name}_empty"),
        &empty_samples,
        1e-6,
        Some(&picture),
    );
    assert!(
        depth_samples.len() > 200 && empty_samples.len() > 200,
        "too few samples"
    );
}

#[test]
fn orthographic_axis_aligned_sphere_matches_analytic_depth_and_normals() {
    check("orthographic", 0.0, 0.0);
}

#[test]
fn orthographic_oblique_sphere_matches_analytic_depth_and_normals() {
    check("orthographic", 35.0, 25.0);
}

#[test]
fn perspective_sphere_matches_analytic_depth_and_normals() {
    check("perspective", 0.0, 0.0);
    check("perspective", -50.0, 40.0);
}
