//! Every output `hatchery render` writes is the old file or the complete new one, never a
//! partial file (hatchery_graph::atomic): each writer — SaveImage, SaveSvg, `--dump` to .png,
//! .npy and .json — is killed mid-write by the file-size limit (`ulimit -f`: SIGXFSZ when a write
//! passes it), after a small render at the same paths wrote files under the limit. The targets
//! must then hold exactly the small render's bytes.

mod common;

use std::path::Path;
use std::process::Command;

/// A shaded torus (gradients that do not compress to nothing) into `saver`.
fn graph(saver: &str) -> String {
    format!(
        r#"(
    version: 3,
    nodes: [
        (id: "camera", kind: "Camera", params: {{"distance": 3.2, "azimuth": 20.0, "elevation": 15.0}}),
        (id: "field", kind: "ProceduralVolume", params: {{"shape": "torus", "resolution": 48}}),
        (id: "surface", kind: "MarchingCubes", params: {{"iso": 0.0}}),
        (id: "light", kind: "Light"),
        (id: "shade", kind: "ShadedSurface"),
        {saver}
    ],
    edges: [
        (from: ("field", "volume"), to: ("surface", "volume")),
        (from: ("surface", "mesh"), to: ("shade", "mesh")),
        (from: ("camera", "camera"), to: ("shade", "camera")),
        (from: ("light", "light"), to: ("shade", "light")),
        {edge}
    ],
)"#,
        edge = if saver.is_empty() {
            ""
        } else {
            r#"(from: ("shade", "image"), to: ("out", "image")),"#
        }
    )
}

/// Runs `hatchery render` in `dir` under a file-size limit of `limit_kb` KiB (none: 0).
fn render(dir: &Path, args: &[&str], limit_kb: u32) -> std::process::ExitStatus {
    let limit = if limit_kb == 0 {
        String::new()
    } else {
        format!("ulimit -f {limit_kb}; ")
    };
    let mut command = format!(
        "{limit}exec '{}' render graph.ron",
        env!("CARGO_BIN_EXE_hatchery")
    );
    for a in args {
        command += &format!(" '{a}'");
    }
    Command::new("sh")
        .args(["-c", &command])
        .current_dir(dir)
        .status()
        .unwrap()
}

#[test]
fn a_writer_killed_mid_write_leaves_the_old_file() {
    let cases: [(&str, &str, &[&str], &[&str]); 3] = [
        (
            "SaveImage",
            r#"(id: "out", kind: "SaveImage", params: {"path": "figure.png"}),"#,
            &[],
            &["figure.png"],
        ),
        (
            "SaveSvg",
            r#"(id: "out", kind: "SaveSvg", params: {"path": "figure.svg"}),"#,
            &[],
            &["figure.svg"],
        ),
        (
            "--dump",
            "",
            &[
                "--dump",
                "shade.image=shade.png",
                "--dump",
                "shade.image=shade.npy",
                "--dump",
                "camera.camera=camera.json",
            ],
            &["shade.png", "shade.npy", "camera.json"],
        ),
    ];
    for (writer, saver, dumps, files) in cases {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("graph.ron"), graph(saver)).unwrap();
        let small = [&["--size", "24x16"][..], dumps].concat();
        assert!(
            render(dir.path(), &small, 0).success(),
            "{writer}: the small render"
        );
        let old: Vec<Vec<u8>> = files
            .iter()
            .map(|f| std::fs::read(dir.path().join(f)).unwrap())
            .collect();
        for (f, bytes) in files.iter().zip(&old) {
            assert!(
                bytes.len() < 16 * 1024,
                "{writer}: {f} is {} bytes",
                bytes.len()
            );
        }
        // The big render's first large write passes the limit: the process is killed in it.
        let big = [&["--size", "1024x768"][..], dumps].concat();
        let status = render(dir.path(), &big, 16);
        assert!(
            !status.success(),
            "{writer}: the render was not stopped by the limit"
        );
        for (f, bytes) in files.iter().zip(&old) {
            let now = std::fs::read(dir.path().join(f)).unwrap();
            // camera.json is small: written whole before the kill, or not at all.
            let whole_new = *f == "camera.json" && now.starts_with(b"{") && now.ends_with(b"}\n");
            assert!(
                now == *bytes || whole_new,
                "{writer}: {f} is neither the old file nor a whole new one ({} bytes, old {})",
                now.len(),
                bytes.len()
            );
        }
    }
}
