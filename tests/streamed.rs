//! Volumes beyond the host memory budget (issue 30, streaming): with `HATCHERY_HOST_BUDGET_MB`
//! forced down, a 160³ volume in a raw MetaImage or an OME-Zarr pyramid is streamed — the ray
//! caster reads only the region and level each view needs — and renders what the same volume
//! held in memory renders at that level. Run through the `hatchery` binary as a user runs it.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

const N: u32 = 160;

/// A uint16 ball: 1000 within radius 35 of (84, 76, 80), falling off to 0 at radius 70 with a
/// ripple, 0 beyond. The plateaus keep the value range [0, 1000] at every coarser level (each
/// level's 2×2×2 means), so the streamed preview's range is the whole volume's.
fn ball() -> Vec<u16> {
    let mut out = Vec::with_capacity((N * N * N) as usize);
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let (dx, dy, dz) = (x as f32 - 84.0, y as f32 - 76.0, z as f32 - 80.0);
                let r = (dx * dx + dy * dy + dz * dz).sqrt();
                let ripple = 0.8 + 0.2 * (x as f32 / 5.0).sin() * (y as f32 / 7.0).cos();
                let v = (2000.0 * (1.0 - r / 70.0) * ripple).clamp(0.0, 1000.0);
                out.push(if r < 35.0 { 1000 } else { v.round() as u16 });
            }
        }
    }
    out
}

/// The ball as ITK writes a MetaImage: a text header, then the raw little-endian voxels. Its
/// origin and spacing (LPS) place it off the world origin.
fn write_mha(path: &Path) {
    let header = format!(
        "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n\
         CompressedData = False\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = -20 10 -30\n\
         CenterOfRotation = 0 0 0\nAnatomicalOrientation = RAI\nElementSpacing = 1 1 1.25\n\
         DimSize = {N} {N} {N}\nElementType = MET_USHORT\nElementDataFile = LOCAL\n"
    );
    let mut bytes = header.into_bytes();
    for v in ball() {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    std::fs::write(path, bytes).unwrap();
}

/// A graph rendering `volume` by DVR with Phong shading from a fixed camera (a streamed
/// volume's preview would frame differently from the whole) at `distance` from `target`,
/// `elevation` degrees up, a field of view of `fov` degrees.
fn graph(
    dir: &Path,
    volume: &Path,
    target: [f32; 3],
    distance: f32,
    elevation: f32,
    fov: f32,
) -> PathBuf {
    let text = format!(
        r#"(
    version: 3,
    nodes: [
        (id: "volume", kind: "VolumeFile", params: {{"path": "{}"}}),
        (id: "camera", kind: "Camera", params: {{"framing": "fixed", "target": ({}, {}, {}),
            "distance": {distance}, "azimuth": 30.0, "elevation": {elevation}, "up": "z",
            "fov": {fov},
            "near": 1.0, "far": 4000.0}}),
        (id: "tf", kind: "TransferFunction1D", params: {{"preset": "custom",
            "points": "range(0.1): 0.8 0.6 0.5 0.0; range(0.5): 0.9 0.5 0.3 0.1; range(0.9): 0.95 0.95 0.9 0.8; range(1): 1 1 1 1"}}),
        (id: "ray", kind: "Raycast", params: {{"shading": "phong"}}),
        (id: "paper", kind: "Fill", params: {{"color": (1.0, 1.0, 1.0, 1.0)}}),
        (id: "over", kind: "Over", params: {{}}),
        (id: "save", kind: "SaveImage", params: {{"path": "out.png"}}),
    ],
    edges: [
        (from: ("camera", "camera"), to: ("ray", "camera")),
        (from: ("volume", "volume"), to: ("ray", "volume")),
        (from: ("volume", "volume"), to: ("tf", "volume")),
        (from: ("tf", "tf"), to: ("ray", "tf")),
        (from: ("paper", "image"), to: ("over", "back")),
        (from: ("ray", "image"), to: ("over", "front")),
        (from: ("over", "image"), to: ("save", "image")),
    ],
)"#,
        volume.display(),
        target[0],
        target[1],
        target[2],
    );
    let path = dir.join(format!("view_{distance}_{elevation}.ron"));
    std::fs::write(&path, text).unwrap();
    path
}

/// Renders `graph` at `size`² pixels with the environment `env`; returns the picture and the
/// log (`-v`: what was streamed).
fn render(graph: &Path, size: u32, env: &[(&str, &str)], out: &Path) -> (image::RgbaImage, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_hatchery"));
    command
        .args(["-v", "render"])
        .arg(graph)
        .arg("-o")
        .arg(out)
        .args(["--size", &format!("{size}x{size}")]);
    for var in [
        "HATCHERY_HOST_BUDGET_MB",
        "HATCHERY_GPU_POOL_MB",
        "HATCHERY_MAX_TEXTURE_3D",
        "HATCHERY_BRICK",
    ] {
        command.env_remove(var);
    }
    command.envs(env.iter().copied());
    let output = command.output().expect("hatchery runs");
    let log = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(
        output.status.success(),
        "hatchery render {env:?} failed:\n{log}"
    );
    (common::read_png(out), log)
}

/// Asserts two pictures agree within 1/255, saving the streamed one on failure.
fn assert_same(name: &str, got: &image::RgbaImage, want: &image::RgbaImage) {
    let (worst, x, y) = common::worst_channel(got, want);
    if worst > 1 {
        let saved = common::save_failure(name, got);
        panic!(
            "{name}: streamed off by {worst}/255 at ({x}, {y}): {:?}, in memory {:?}; see {}",
            got.get_pixel(x, y),
            want.get_pixel(x, y),
            saved.display()
        );
    }
    assert!(
        common::non_background_fraction(want) > 0.05,
        "{name}: the ball should fill part of the frame"
    );
}

/// The world centre of the ball's grid (MetaImage LPS → RAS: x and y flip).
const CENTRE: [f32; 3] = [20.0 - 79.5, -10.0 - 79.5, -30.0 + 79.5 * 1.25];

/// A 4 MiB budget streams the 8 MiB ball; a 4 MiB GPU pool with 48-voxel textures bricks it
/// and holds level 1 (80³) at most, in memory or streamed.
const BUDGET: (&str, &str) = ("HATCHERY_HOST_BUDGET_MB", "4");
const POOL: [(&str, &str); 2] = [
    ("HATCHERY_GPU_POOL_MB", "4"),
    ("HATCHERY_MAX_TEXTURE_3D", "48"),
];

fn check_whole_view(volume: &Path, dir: &Path, what: &str) {
    // The whole grid in view, 2.4 world units a pixel at its nearest corner: level 1.
    let g = graph(dir, volume, CENTRE, 700.0, 25.0, 30.0);
    let (want, held_log) = render(&g, 128, &POOL, &dir.join("held.png"));
    assert!(
        !held_log.contains("streamed"),
        "without a budget the volume is loaded whole:\n{held_log}"
    );
    let env = [POOL[0], POOL[1], BUDGET];
    let (got, log) = render(&g, 128, &env, &dir.join("streamed.png"));
    assert!(
        log.contains("exceed the host budget") && log.contains("streamed region read"),
        "{what}: the volume should stream and read a region:\n{log}"
    );
    assert!(
        log.contains("lod=1") && log.contains("size=[80, 80, 80]"),
        "{what}: a whole view under the budget reads all of level 1:\n{log}"
    );
    assert_same(&format!("streamed_whole_{what}"), &got, &want);
}

#[test]
fn a_raw_file_beyond_the_budget_streams_and_renders_as_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let mha = dir.path().join("ball.mha");
    write_mha(&mha);
    check_whole_view(&mha, dir.path(), "mha");
}

#[test]
fn an_ome_zarr_pyramid_beyond_the_budget_streams_its_stored_levels() {
    let dir = tempfile::tempdir().unwrap();
    let mha = dir.path().join("ball.mha");
    write_mha(&mha);
    let zarr = dir.path().join("ball.zarr");
    let out = Command::new(env!("CARGO_BIN_EXE_hatchery"))
        .arg("convert")
        .arg(&mha)
        .arg(&zarr)
        .output()
        .expect("hatchery runs");
    assert!(
        out.status.success(),
        "convert: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    check_whole_view(&zarr, dir.path(), "zarr");
}

#[test]
fn a_close_view_reads_only_the_region_it_shows_at_full_resolution() {
    let dir = tempfile::tempdir().unwrap();
    let mha = dir.path().join("ball.mha");
    write_mha(&mha);
    // Looking down at the top of the ball from 90 above the grid through a 10° cone: a column
    // of about 64 × 64 × 160 voxels, 0.1 world units a pixel: level 0.
    let target = [CENTRE[0], CENTRE[1], CENTRE[2] + 40.0];
    let g = graph(dir.path(), &mha, target, 150.0, 89.0, 10.0);
    let (want, _) = render(&g, 160, &[], &dir.path().join("held.png"));
    // 12 MiB: under 4 × the ball's 8 MiB, so it streams; regions up to 1.5 M voxels.
    let budget = ("HATCHERY_HOST_BUDGET_MB", "12");
    let (got, log) = render(&g, 160, &[budget], &dir.path().join("streamed.png"));
    let line = log
        .lines()
        .find(|l| l.contains("streamed region read"))
        .unwrap_or_else(|| panic!("no region was read:\n{log}"));
    assert!(line.contains("lod=0"), "full resolution: {line}");
    // The region is a part of the grid: not all 160 voxels along every axis.
    let size: Vec<u32> = line
        .split("size=[")
        .nth(1)
        .and_then(|s| s.split(']').next())
        .map(|s| s.split(", ").map(|n| n.trim().parse().unwrap()).collect())
        .unwrap_or_else(|| panic!("no size in {line}"));
    let voxels: u64 = size.iter().map(|&n| n as u64).product();
    assert!(
        voxels <= 12 * 1024 * 1024 / 8 && voxels < (N * N * N / 2) as u64,
        "the region {size:?} is under half the grid and within the budget's voxels"
    );
    assert_same("streamed_close", &got, &want);
}
