//! Axis-aligned scenes for the ray caster's tests of per-sample opacity (tests/enhancement.rs,
//! tests/tf2d.rs): volumes constant along y and z seen orthographically along −z with one pixel
//! per voxel column, the closed form of a column's compositing, and the GPU-vs-reference check.

#![allow(dead_code)]

use glam::Vec3;
use hatchery_data::VolumeData;
use hatchery_nodes::camera::Camera;

/// Largest channel difference GPU − CPU reference allowed per pixel (premultiplied RGBA in
/// [0, 1]; the image is half floats, whose steps near 1 are 1/2048), and the RMS over the frame.
pub const WORST: f32 = 1.0 / 255.0;
pub const RMS: f64 = 0.25 / 255.0;

/// An orthographic camera looking along −z whose w × h pixel centres sit on the voxel columns
/// (x, h − 1 − row) of a unit-spacing grid.
pub fn on_columns(w: u32, h: u32) -> Camera {
    let distance = 40.0f32;
    let fov = 2.0 * (h as f32 / 2.0 / distance).atan().to_degrees();
    let target = Vec3::new((w - 1) as f32 / 2.0, (h - 1) as f32 / 2.0, 0.5);
    Camera::orbit(
        target, 0.0, 0.0, distance, fov, true, 0.05, 100.0, false, w, h,
    )
}

/// Values constant along y and z: `f(x)` on a w × h × d unit-spacing grid.
pub fn columns(w: u32, h: u32, d: u32, f: impl Fn(u32) -> f32) -> VolumeData {
    let values = (0..w * h * d).map(|i| f(i % w)).collect();
    VolumeData::new([w, h, d], [1.0; 3], [0.0; 3], values).unwrap()
}

/// Front-to-back compositing of `samples` equal samples of opacity `o` (step 1 voxel).
pub fn column_alpha(o: f32, samples: u32) -> f32 {
    1.0 - (1.0 - o).powi(samples as i32)
}

/// Fails unless GPU and CPU agree within [`WORST`] per channel and [`RMS`]; prints both figures.
pub fn assert_matches(name: &str, gpu: &[[f32; 4]], cpu: &[[f32; 4]], width: u32) {
    let diff = super::diff_images(gpu, cpu, width, |_| true, WORST);
    let squares: f64 = gpu
        .iter()
        .zip(cpu)
        .flat_map(|(g, c)| (0..4).map(move |k| f64::from(g[k] - c[k]).powi(2)))
        .sum();
    let rms = (squares / (gpu.len() * 4) as f64).sqrt();
    eprintln!(
        "{name}: worst channel difference {:.5} at ({}, {}) (GPU {:?}, CPU {:?}), RMS {rms:.6}",
        diff.worst, diff.x, diff.y, gpu[diff.index], cpu[diff.index]
    );
    if !diff.over.is_empty() || rms > RMS {
        diff.fail(
            name,
            gpu,
            cpu,
            format!(
                "{} pixels beyond {WORST}, RMS {rms} (at most {RMS})",
                diff.over.len()
            ),
        );
    }
    assert!(gpu.iter().any(|p| p[3] > 0.1), "{name}: the image is empty");
}

/// A session sized for `camera`'s frame, for running nodes directly.
pub fn session_for(camera: &Camera) -> hatchery_nodes::Session {
    let mut session = super::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        camera.width,
        camera.height,
    );
    session.ctx.set_size(camera.width, camera.height).unwrap();
    session
}

/// The Raycast node's image (premultiplied RGBA, row 0 at the top) of `volume` through `tf`:
/// no jitter, no early termination, `step` voxels, then `extra` parameters.
pub fn raycast_image(
    session: &mut hatchery_nodes::Session,
    volume: &std::sync::Arc<hatchery_nodes::value::Volume>,
    camera: &Camera,
    tf: hatchery_nodes::Value,
    shading: &str,
    step: f32,
    extra: &[(&str, hatchery_graph::ParamValue)],
) -> Vec<[f32; 4]> {
    let inputs = vec![("tf", tf)];
    raycast_with(session, volume, camera, inputs, shading, step, extra)
        .unwrap_or_else(|e| panic!("Raycast: {e}"))
}

/// [`raycast_image`] with more `inputs` (`tf` among them), returning the node's error.
pub fn raycast_with(
    session: &mut hatchery_nodes::Session,
    volume: &std::sync::Arc<hatchery_nodes::value::Volume>,
    camera: &Camera,
    mut inputs: Vec<(&'static str, hatchery_nodes::Value)>,
    shading: &str,
    step: f32,
    extra: &[(&str, hatchery_graph::ParamValue)],
) -> Result<Vec<[f32; 4]>, hatchery_graph::NodeError> {
    use hatchery_graph::ParamValue;
    use hatchery_nodes::Value;
    let mut params = vec![
        ("shading", ParamValue::Choice(shading.into())),
        ("step", ParamValue::Float(step.into())),
        ("jitter", ParamValue::Bool(false)),
        ("early_termination", ParamValue::Float(1.0)),
    ];
    params.extend(extra.iter().cloned());
    inputs.push(("volume", Value::Volume(volume.clone())));
    inputs.push(("camera", Value::Camera(std::sync::Arc::new(camera.clone()))));
    let outputs = super::try_run_node(session, "Raycast", inputs, &params)?;
    let a = hatchery_nodes::export::to_array(&outputs[0], &session.ctx.gpu).unwrap();
    Ok(a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect())
}

/// The CPU reference's parameters for the same rays as [`raycast_image`] (DVR, the node's
/// default headlight).
pub fn reference_params(
    camera: &Camera,
    shading: super::raycast_reference::Shading,
    step: f32,
) -> super::raycast_reference::RayParams {
    super::raycast_reference::RayParams {
        view_proj: camera.view_proj(),
        view: camera.view,
        width: camera.width,
        height: camera.height,
        orthographic: camera.orthographic,
        step_voxels: step,
        mode: super::raycast_reference::Mode::Dvr,
        shading,
        light_dir_view: Vec3::new(0.3, 0.4, 1.0).normalize(),
        early_termination: 1.0,
    }
}
