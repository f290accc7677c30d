//! The volume inputs of `../shared/cases/` (README there): files other tools write that were
//! read wrongly, each with its right answer. (The STL cases are in meshes.rs, the VTK array case
//! in vti.rs.)

use glam::Vec3;
use hatchery_data::marching_cubes::marching_cubes;
use hatchery_data::{MeshData, VolumeData, load_volume};
use std::path::{Path, PathBuf};

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/cases")
        .join(name)
}

fn centroid(mesh: &MeshData) -> Vec3 {
    let sum: Vec3 = mesh.positions.iter().map(|p| Vec3::from_array(*p)).sum();
    sum / mesh.positions.len() as f32
}

#[test]
fn radiological_las_nifti_lands_where_its_sform_says() {
    let v = load_volume(&case("las_blob.nii")).unwrap();
    assert!(v.placement.starts_with("sform"), "{}", v.placement);
    // The blob (voxels x 2..7, y 4..11, z 4..11) is at world x 9..19, y −7..7, z −7..7.
    let mesh = marching_cubes(&v, 50.0);
    assert!(mesh.triangle_count() > 0);
    let c = centroid(&mesh);
    assert!(
        (c - Vec3::new(14.0, 0.0, 0.0)).length() < 1.0,
        "centroid {c}"
    );
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[0]), hi.max(p[0]))
        });
    assert!(lo >= 7.5 && hi <= 20.5, "x extent {lo}..{hi}");
    // Mirrored: the triangles must still face outward (normals point away from the centroid).
    let outward = mesh
        .indices
        .chunks_exact(3)
        .filter(|t| {
            let [a, b, c2] =
                [t[0], t[1], t[2]].map(|i| Vec3::from_array(mesh.positions[i as usize]));
            let n = (b - a).cross(c2 - a);
            n.dot((a + b + c2) / 3.0 - c) > 0.0
        })
        .count();
    assert!(
        outward * 10 >= mesh.triangle_count() * 9,
        "{outward} of {} triangles face outward",
        mesh.triangle_count()
    );
}

#[test]
fn no_data_border_grows_no_wall() {
    let v = load_volume(&case("ramp_half_nan.nii.gz")).unwrap();
    assert!(v.has_no_data());
    let mesh = marching_cubes(&v, 0.0);
    assert!(mesh.triangle_count() > 0);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        assert!((p[0] - 9.5).abs() <= 0.01, "vertex off the plane: {p:?}");
        assert!(n[0].abs() > 0.999, "normal not along x: {n:?} at {p:?}");
    }
}

#[test]
fn no_data_outside_a_ball_is_outside() {
    let v: VolumeData = load_volume(&case("nan_outside.nii.gz")).unwrap();
    let [lo, hi] = v.value_range;
    // cos(12 r) over the finite voxels: within [-1, 1], reaching near both ends.
    assert!(
        (-1.0..=-0.9).contains(&lo) && (0.8..=1.0).contains(&hi),
        "finite value range {lo}..{hi}"
    );
    let centre = v.voxel_to_world(Vec3::splat(9.5));
    let voxel = v.spacing()[0];
    for iso in [-0.9, -0.5, 0.0, 0.3, 0.8] {
        let mesh = marching_cubes(&v, iso);
        assert!(mesh.triangle_count() > 0, "iso {iso}");
        for p in &mesh.positions {
            let r = (Vec3::from_array(*p) - centre).length() / voxel;
            assert!(r <= 8.5, "iso {iso}: vertex {r} voxels from the centre");
        }
    }
}
