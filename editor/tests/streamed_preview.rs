//! The editor's render thread and a volume beyond the host budget (issue 30): the first answer
//! shows the streamed volume's preview level at once and says it is refining; the next answer,
//! unasked, is the view at the level it needs. Its own test binary: it sets
//! `HATCHERY_HOST_BUDGET_MB` for the process before any thread starts.

use hatchery_editor::render_worker::{Picture, RenderWorker, Rendered, Request};
use std::time::{Duration, Instant};

const N: u32 = 128;

/// A uint8 ball, a checkerboard inside, as a raw NRRD (as `teem` writes it): 2 MiB.
fn write_ball(path: &std::path::Path) {
    let header = format!(
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: {N} {N} {N}\nspace: left-posterior-superior\n\
         space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nencoding: raw\n\n"
    );
    let mut bytes = header.into_bytes();
    let c = (N as f32 - 1.0) / 2.0;
    for z in 0..N {
        for y in 0..N {
            for x in 0..N {
                let p = glam::Vec3::new(x as f32, y as f32, z as f32) - c;
                let r = p.length();
                // A checkerboard of single voxels, which every coarser level averages away, and
                // a solid core off the view's axis, which keeps the value range [0, 255] at
                // every level (a streamed volume's transfer functions span its preview's).
                let stripe = if (x + y) % 2 == 0 { 255 } else { 60 };
                let core = (p - glam::Vec3::new(30.0, 0.0, 0.0)).length() < 8.0;
                bytes.push(if core {
                    255
                } else if r < 50.0 {
                    stripe
                } else {
                    0
                });
            }
        }
    }
    std::fs::write(path, bytes).unwrap();
}

fn graph(volume: &std::path::Path, dir: &std::path::Path) -> hatchery_graph::Graph {
    let text = format!(
        r#"(
    version: 3,
    nodes: [
        (id: "volume", kind: "VolumeFile", params: {{"path": "{}"}}),
        (id: "camera", kind: "Camera", params: {{"framing": "fixed", "target": (-63.5, -63.5, 63.5),
            "distance": 300.0, "azimuth": 0.0, "elevation": 89.0, "up": "z", "fov": 3.0,
            "near": 1.0, "far": 2000.0}}),
        (id: "tf", kind: "TransferFunction1D", params: {{"preset": "custom",
            "points": "range(0): 0 0 0 1; range(1): 1 1 1 1"}}),
        (id: "ray", kind: "Raycast", params: {{"mode": "mip"}}),
    ],
    edges: [
        (from: ("camera", "camera"), to: ("ray", "camera")),
        (from: ("volume", "volume"), to: ("ray", "volume")),
        (from: ("volume", "volume"), to: ("tf", "volume")),
        (from: ("tf", "tf"), to: ("ray", "tf")),
    ],
)"#,
        volume.display()
    );
    let path = dir.join("view.ron");
    std::fs::write(&path, text).unwrap();
    hatchery_graph::Graph::load_file(&path, &hatchery_nodes::registry()).expect("graph loads")
}

fn next_answer(worker: &RenderWorker) -> Rendered {
    let started = Instant::now();
    loop {
        if let Some(a) = worker.next_answer() {
            return a;
        }
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no answer from the render thread"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn pixels(answer: Rendered) -> image::RgbaImage {
    match answer.viewport {
        Some(Ok(Picture::Pixels(p))) => p,
        Some(Err(e)) => panic!("render failed: {e}"),
        _ => panic!("no pixels (the worker renders on a device of its own here)"),
    }
}

#[test]
fn a_streamed_volume_shows_its_preview_first_then_refines_by_itself() {
    // 3 MiB: the 2 MiB ball streams (over a quarter of the budget), its preview is level 1
    // (64³, the checkerboard averaged away) and a view may read 384 K voxels: the narrow view
    // below reads a level-0 column of about 32 × 32 × 128 voxels, checkerboard and all.
    // Safety: set before any thread of this process starts (the only test in this binary).
    unsafe { std::env::set_var("HATCHERY_HOST_BUDGET_MB", "3") };
    let dir = tempfile::tempdir().unwrap();
    let nrrd = dir.path().join("ball.nrrd");
    write_ball(&nrrd);
    let worker = RenderWorker::spawn(None, egui::Context::default()).expect("render thread");
    worker
        .send(Request {
            id: 1,
            graph: graph(&nrrd, dir.path()),
            size: (128, 128),
            viewport: Some(("ray".into(), "image".into())),
            thumbnails: Vec::new(),
            thumbnail_bound: (64, 64),
            timing: false,
            depth: Vec::new(),
        })
        .unwrap();
    let first = next_answer(&worker);
    assert_eq!(first.id, 1);
    if first.refining.is_empty() {
        panic!(
            "the first answer should be the preview level, refining; warnings: {:?}",
            first.warnings
        );
    }
    assert_eq!(first.refining, vec!["ray".to_owned()]);
    let coarse = pixels(first);
    let second = next_answer(&worker);
    assert_eq!(second.id, 1, "the refined answer is for the same request");
    assert!(second.refining.is_empty(), "refined: {:?}", second.refining);
    let fine = pixels(second);
    // The checkerboard survives only at full resolution: the refined picture differs.
    let differing = coarse
        .pixels()
        .zip(fine.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 16))
        .count();
    assert!(
        differing > 500,
        "the refined picture should show the checkerboard the preview lacks: {differing} pixels \
         differ"
    );
}
