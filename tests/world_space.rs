//! Volumes land where they are in the world, on the GPU too: the ray caster marches in voxel
//! space through the voxel → world transform, so a radiological (LAS) and a neurological (RAS)
//! copy of one object look the same, and "no data" voxels are transparent.

mod common;

use glam::Vec3;
use hatchery_data::load_volume;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};
use hatchery_graph::ParamValue;
use hatchery_nodes::camera::Camera;
use hatchery_nodes::value::{TransferFunction, Volume};
use hatchery_nodes::{Session, Value, export};
use std::sync::Arc;

const SIZE: u32 = 96;

fn session() -> Session {
    common::session_from_text(
        r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#,
        SIZE,
        SIZE,
    )
}

/// An orthographic camera around `target`, `half` world units from the centre to the top.
fn ortho(target: Vec3, azimuth: f32, elevation: f32, half: f32) -> Camera {
    let distance = 200.0;
    let fov = 2.0 * (half / distance).atan().to_degrees();
    Camera::orbit(
        target, azimuth, elevation, distance, fov, true, 1.0, 400.0, true, SIZE, SIZE,
    )
}

/// Shaded DVR of `volume` seen by `cam`: premultiplied RGBA per pixel.
fn render(
    session: &mut Session,
    volume: &Arc<Volume>,
    cam: &Camera,
    tf: TransferFunction1D,
) -> Vec<[f32; 4]> {
    let light = hatchery_nodes::light::Light {
        direction: Vec3::new(0.3, 0.5, 1.0).normalize(),
        view_space: true,
        color: [1.0; 3],
        intensity: 1.0,
        ambient: 0.15,
    };
    let out = common::run_node(
        session,
        "Raycast",
        vec![
            ("volume", Value::Volume(volume.clone())),
            ("camera", Value::Camera(Arc::new(cam.clone()))),
            (
                "tf",
                Value::TransferFunction(Arc::new(TransferFunction::Color(tf))),
            ),
            ("light", Value::Light(Arc::new(light))),
        ],
        &[
            ("mode", ParamValue::Choice("dvr".into())),
            ("shading", ParamValue::Choice("phong".into())),
            ("step", ParamValue::Float(0.5)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    let a = export::to_array(&out[0], &session.ctx.gpu).unwrap();
    a.data
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

fn tf(points: &[(f32, [f32; 4])]) -> TransferFunction1D {
    let points: Vec<ControlPoint> = points
        .iter()
        .map(|&(value, rgba)| ControlPoint { value, rgba })
        .collect();
    TransferFunction1D::from_points(&points).unwrap()
}

fn fixture(name: &str) -> Arc<Volume> {
    let path = common::repo_root().join("tests/fixtures/world").join(name);
    Arc::new(Volume::new(load_volume(&path).unwrap()))
}

#[test]
fn las_and_ras_copies_of_one_object_ray_cast_alike() {
    let mut s = session();
    let ras = fixture("nifti_ras.nii");
    let las = fixture("nifti_las.nii.gz");
    // Stored mirrored, placed the same: the transforms differ, the worlds do not.
    assert_ne!(ras.data.geometry, las.data.geometry);
    assert!((ras.data.world_min() - las.data.world_min()).length() < 1e-4);
    let f = tf(&[
        (0.0, [0.2, 0.3, 0.9, 0.0]),
        (90.0, [0.9, 0.6, 0.2, 0.0]),
        (110.0, [0.95, 0.9, 0.8, 0.6]),
        (200.0, [1.0, 0.3, 0.2, 0.9]),
    ]);
    let centre = (ras.data.world_min() + ras.data.world_max()) / 2.0;
    for (azimuth, elevation) in [(0.0, 0.0), (90.0, 0.0), (30.0, 40.0), (200.0, -60.0)] {
        let cam = ortho(centre, azimuth, elevation, 18.0);
        let a = render(&mut s, &ras, &cam, f.clone());
        let b = render(&mut s, &las, &cam, f.clone());
        let covered = a.iter().filter(|p| p[3] > 0.1).count();
        assert!(covered > 100, "az {azimuth}: the object is not in view");
        let name = format!("az {azimuth} el {elevation}: LAS vs RAS");
        common::assert_images_close(&name, &a, &b, SIZE, 1.0 / 255.0);
    }
}

/// One anatomy written by ome-zarr-py in micrometres (OME-Zarr 0.4, Zarr v2, Blosc) and in
/// millimetres (0.5, Zarr v3, zstd): the same world, so the same pictures.
#[test]
fn ome_zarr_in_micrometres_and_millimetres_ray_cast_alike() {
    let mut s = session();
    let um = fixture("ome_v04.zarr");
    let mm = fixture("ome_v05.zarr");
    assert!((um.data.world_min() - mm.data.world_min()).length() < 1e-4);
    assert!((um.data.world_max() - mm.data.world_max()).length() < 1e-4);
    let f = tf(&[
        (0.0, [0.2, 0.3, 0.9, 0.0]),
        (90.0, [0.9, 0.6, 0.2, 0.0]),
        (200.0, [1.0, 0.3, 0.2, 0.9]),
    ]);
    let centre = (mm.data.world_min() + mm.data.world_max()) / 2.0;
    for (azimuth, elevation) in [(0.0, 0.0), (30.0, 40.0)] {
        let cam = ortho(centre, azimuth, elevation, 20.0);
        let a = render(&mut s, &um, &cam, f.clone());
        let b = render(&mut s, &mm, &cam, f.clone());
        assert!(
            a.iter().filter(|p| p[3] > 0.1).count() > 100,
            "the object is in view"
        );
        let name = format!("az {azimuth} el {elevation}: µm vs mm");
        common::assert_images_close(&name, &a, &b, SIZE, 1.0 / 255.0);
    }
}

#[test]
fn no_data_voxels_are_transparent_to_the_ray_caster() {
    let mut s = session();
    let path = common::repo_root().join("../shared/cases/nan_outside.nii.gz");
    let volume = Arc::new(Volume::new(load_volume(&path).unwrap()));
    let data = &volume.data;
    // Every finite value opaque: without no-data handling the whole box would show.
    let f = tf(&[(-1.0, [0.8, 0.8, 0.8, 1.0]), (1.0, [0.8, 0.8, 0.8, 1.0])]);
    let centre = data.voxel_to_world(Vec3::splat(9.5));
    let voxel = data.spacing()[0];
    let half = 12.0 * voxel;
    for (azimuth, elevation) in [(0.0, 0.0), (45.0, 30.0)] {
        let cam = ortho(centre, azimuth, elevation, half);
        let image = render(&mut s, &volume, &cam, f.clone());
        let pixel = 2.0 * half / SIZE as f32;
        for (i, p) in image.iter().enumerate() {
            let (x, y) = (
                (i as u32 % SIZE) as f32 + 0.5,
                (i as u32 / SIZE) as f32 + 0.5,
            );
            let r = ((x - SIZE as f32 / 2.0).hypot(y - SIZE as f32 / 2.0)) * pixel / voxel;
            if r > 9.0 {
                assert_eq!(p[3], 0.0, "pixel ({x}, {y}) {r} voxels out shows {p:?}");
            }
            if r < 6.0 {
                assert!(p[3] > 0.9, "pixel ({x}, {y}) inside the ball is {p:?}");
            }
        }
    }
}

/// A volume wider than the adapter's 3-D textures (once refused, issue 9 item 2) is bricked
/// (issue 30) and renders.
#[test]
fn a_volume_beyond_the_adapter_limit_is_bricked_and_renders() {
    let probe = session();
    let limit = probe.ctx.gpu.device.limits().max_texture_dimension_3d;
    let nx = limit + 1;
    let dir = tempfile::tempdir().unwrap();
    let mut values = vec!["0"; nx as usize * 4];
    values[0] = "1";
    let vti = format!(
        r#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">
  <ImageData WholeExtent="0 {last} 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
    <Piece Extent="0 {last} 0 1 0 1">
      <PointData Scalars="v">
        <DataArray type="UInt8" Name="v" format="ascii">{data}</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
"#,
        last = nx - 1,
        data = values.join(" ")
    );
    let path = dir.path().join("wide.vti");
    std::fs::write(&path, vti).unwrap();
    let graph = format!(
        r#"(version: 1, nodes: [
            (id: "volume", kind: "VolumeFile", params: {{"path": "{}"}}),
            (id: "camera", kind: "Camera"),
            (id: "tf", kind: "TransferFunction1D"),
            (id: "ray", kind: "Raycast"),
        ], edges: [
            (from: ("volume", "volume"), to: ("ray", "volume")),
            (from: ("camera", "camera"), to: ("ray", "camera")),
            (from: ("tf", "tf"), to: ("ray", "tf")),
        ])"#,
        path.display()
    );
    let mut s = common::session_from_text(&graph, 32, 32);
    s.run(&["ray"]).unwrap();
    let Some(hatchery_nodes::Value::Volume(v)) = s.executor.output("volume", 0) else {
        panic!("no volume");
    };
    let layout = v.bricked().expect("bricked");
    assert_eq!(layout.pages[1..], [1, 1], "{}", layout.describe());
    assert!(layout.atlas_dims().iter().all(|&d| d <= limit));
}

/// Next to "no data" the gradient is one-sided (the ray caster keeps that fallback for volumes
/// with NaN voxels: RAY_NO_DATA). A ramp f = x cut off by NaN for z ≥ 12, its iso-surface
/// x = 7.5 seen head-on with pixel centres on voxel centres: the plane shades uniformly up to
/// the row next to the NaN (there ∂f/∂z is one-sided, 0; across the NaN it would not be).
#[test]
fn a_plane_shades_uniformly_up_to_no_data() {
    use hatchery_data::VolumeData;
    use hatchery_data::geometry::Geometry;
    let n = 16u32;
    let mut values = Vec::new();
    for z in 0..n {
        for _y in 0..n {
            for x in 0..n {
                values.push(if z >= 12 { f32::NAN } else { x as f32 });
            }
        }
    }
    let geometry = Geometry::axis_aligned([1.0; 3], [0.0; 3]);
    let data = VolumeData::with_geometry([n; 3], geometry, values).unwrap();
    assert!(data.has_no_data());
    let volume = Arc::new(Volume::new(data));
    let mut s =
        common::session_from_text(r#"(version: 1, nodes: [(id: "c", kind: "Camera")])"#, n, n);
    let half = n as f32 / 2.0;
    let fov = 2.0 * (half / 200.0).atan().to_degrees();
    let cam = Camera::orbit(
        Vec3::splat(7.5),
        -90.0,
        0.0,
        200.0,
        fov,
        true,
        1.0,
        400.0,
        true,
        n,
        n,
    );
    let f = tf(&[(0.0, [0.8, 0.6, 0.4, 1.0]), (15.0, [0.8, 0.6, 0.4, 1.0])]);
    let out = common::run_node(
        &mut s,
        "Raycast",
        vec![
            ("volume", Value::Volume(volume)),
            ("camera", Value::Camera(Arc::new(cam))),
            (
                "tf",
                Value::TransferFunction(Arc::new(TransferFunction::Color(f))),
            ),
        ],
        &[
            ("mode", ParamValue::Choice("iso".into())),
            ("iso", ParamValue::Float(7.5)),
            ("shading", ParamValue::Choice("phong".into())),
            ("step", ParamValue::Float(0.5)),
            ("jitter", ParamValue::Bool(false)),
        ],
    );
    let a = export::to_array(&out[0], &s.ctx.gpu).unwrap();
    let hits: Vec<&[f32]> = a.data.chunks_exact(4).filter(|p| p[3] > 0.5).collect();
    // 16 columns × the 12 rows z = 0 … 11, the last one next to the NaN included.
    assert_eq!(hits.len(), 192, "pixels showing the plane");
    let first = hits[0];
    for p in &hits {
        let off = (0..3)
            .map(|c| (p[c] - first[c]).abs())
            .fold(0.0f32, f32::max);
        assert!(
            p.iter().all(|c| c.is_finite()) && off <= 1.0 / 255.0,
            "the plane's shade varies: {p:?} against {first:?}"
        );
    }
}
