//! The `hatchery` command line: exit codes, one-line errors without panics, dumps, the catalogue.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::hatchery;

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A failed command: non-zero exit and exactly one error line, no panic.
fn assert_clean_failure(output: &Output, needles: &[&str]) {
    let err = stderr(output);
    assert!(
        !output.status.success(),
        "expected failure, got success; stderr: {err}"
    );
    assert!(
        !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
        "panic text in: {err}"
    );
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(lines.len(), 1, "expected one error line, got: {err}");
    // Said once: a cause whose text its error already holds is not repeated.
    let parts: Vec<&str> = lines[0].split(": ").filter(|p| p.len() >= 12).collect();
    for (i, part) in parts.iter().enumerate() {
        assert!(
            !parts[i + 1..].contains(part),
            "`{part}` said twice in: {}",
            lines[0]
        );
    }
    for needle in needles {
        assert!(
            lines[0].contains(needle),
            "`{needle}` missing from: {}",
            lines[0]
        );
    }
}

#[test]
fn validate_accepts_presets_and_rejects_every_bad_fixture_without_panicking() {
    let ok = hatchery(&["validate", "graphs/shaded_surface.ron"]);
    assert!(ok.status.success(), "{}", stderr(&ok));
    let dir = common::repo_root().join("tests/fixtures/bad");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let relative = format!(
            "tests/fixtures/bad/{}",
            path.file_name().unwrap().to_string_lossy()
        );
        let output = hatchery(&["validate", &relative]);
        assert_clean_failure(&output, &[&format!("error: {relative}:")]);
        count += 1;
    }
    assert!(count >= 10);
}

#[test]
fn render_writes_the_picture_and_every_requested_dump() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
    let output = hatchery(&[
        "render",
        "graphs/shaded_surface.ron",
        "-o",
        &p("out.png"),
        "--size",
        "200x150",
        "--set",
        "shells.resolution=40",
        "--set",
        "camera.azimuth=90",
        "--dump",
        &format!("shaded.image={}", p("image.npy")),
        "--dump",
        &format!("shaded.image={}", p("image.png")),
        "--dump",
        &format!("surface.mesh={}", p("mesh.npy")),
        "--dump",
        &format!("shells.volume={}", p("volume.npy")),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let picture = common::read_png(Path::new(&p("out.png")));
    assert_eq!(picture.dimensions(), (200, 150));
    assert!(
        common::non_background_fraction(&picture) > 0.1,
        "the render is blank"
    );

    let image = common::npy::read_npy(Path::new(&p("image.npy"))).unwrap();
    assert_eq!(image.shape, vec![150, 200, 4]);
    // The dumped PNG and the saved picture are the same pixels.
    assert_eq!(common::read_png(Path::new(&p("image.png"))), picture);
    let mesh = common::npy::read_npy(Path::new(&p("mesh.npy"))).unwrap();
    assert_eq!(mesh.shape[1], 6);
    assert!(mesh.shape[0] > 1000);
    let volume = common::npy::read_npy(Path::new(&p("volume.npy"))).unwrap();
    assert_eq!(volume.shape, vec![40, 40, 40]);
}

/// Issue 9 item 4 through the command line: an iso value with no surface renders the rest of
/// the picture and says why in one warning line naming the node.
#[test]
fn an_iso_value_without_surface_renders_with_one_warning_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let output = hatchery(&[
        "render",
        "graphs/shaded_surface.ron",
        "-o",
        &out.to_string_lossy(),
        "--size",
        "64x48",
        "--set",
        "surface.iso=3",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(out.exists());
    let err = stderr(&output);
    let lines: Vec<&str> = err.lines().filter(|l| l.contains("no surface")).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].contains("surface:") && lines[0].contains("outside the volume's value range"),
        "{err}"
    );
}

#[test]
fn bad_command_line_input_is_one_clean_error() {
    let cases: &[(&[&str], &[&str])] = &[
        (
            &[
                "render",
                "graphs/shaded_surface.ron",
                "--set",
                "camera.zoom=2",
            ],
            &["node `camera`", "no parameter `zoom`"],
        ),
        (
            &[
                "render",
                "graphs/shaded_surface.ron",
                "--set",
                "camera.azimuth=far",
            ],
            &["parameter `azimuth`", "far"],
        ),
        (
            &["render", "graphs/shaded_surface.ron", "--set", "ghost.x=1"],
            &["no node `ghost`"],
        ),
        (
            &[
                "render",
                "graphs/shaded_surface.ron",
                "--dump",
                "shaded.picture=x.npy",
            ],
            &["no output port `picture`", "image"],
        ),
        (
            &[
                "render",
                "graphs/shaded_surface.ron",
                "--dump",
                "camera.camera=x.npy",
            ],
            &["Camera value holds no array"],
        ),
        (
            &[
                "render",
                "graphs/shaded_surface.ron",
                "--set",
                "camera.near=5000",
            ],
            &["node `camera` (Camera)", "must be less than far"],
        ),
        (
            &[
                "render",
                "graphs/brain_surface.ron",
                "--set",
                "mri.path=Cargo.toml",
            ],
            &["node `mri` (VolumeFile)", "Cargo.toml"],
        ),
        (
            &["render", "graphs/shaded_surface.ron", "--size", "0x10"],
            &["0x10"],
        ),
        (
            &["info", "Cargo.lock"],
            &["Cargo.lock", "unknown file ending", ".nii.gz", ".stl"],
        ),
        (
            &["validate", "graphs/nope.ron"],
            &["graphs/nope.ron", "cannot read graph file"],
        ),
        (
            &["convert", "tests/fixtures/world/nifti_ras.nii", "out.nii"],
            &["out.nii", "name it with the ending .zarr"],
        ),
        (
            &["convert", "tests/fixtures/world/nope.nii", "out.zarr"],
            &["nope.nii"],
        ),
        (
            &[
                "convert",
                "tests/fixtures/world/nifti_ras.nii",
                "out.zarr",
                "--names",
                "names.csv",
            ],
            &["--labels FILE"],
        ),
        (
            &["info", "tests/fixtures/world/ome_v05.zarr/labels/organs/s0"],
            &["a Zarr array, not an OME-Zarr image", "labels/organs/s0"],
        ),
    ];
    for (args, needles) in cases {
        let output = hatchery(args);
        assert_clean_failure(&output, needles);
    }
}

#[test]
fn info_lists_an_ome_zarr_pyramid_and_its_named_label_images() {
    let output = hatchery(&["info", "tests/fixtures/world/ome_v04.zarr"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = String::from_utf8_lossy(&output.stdout);
    for needle in [
        "dims: 20 x 16 x 12",
        "spacing: 0.800000 1.500000 2.000000",
        "OME-Zarr 0.4 multiscales",
        "level 1 (s1): 10 x 8 x 12, spacing 1.600000 3.000000 2.000000",
        "label image labels/organs: 2 named objects (1 box, 2 knob)",
    ] {
        assert!(text.contains(needle), "`{needle}` missing from:\n{text}");
    }
}

#[test]
fn the_committed_node_catalogue_is_current() {
    let output = hatchery(&["nodes", "--markdown"]);
    assert!(output.status.success());
    let generated = String::from_utf8(output.stdout).unwrap();
    let committed = std::fs::read_to_string(common::repo_root().join("docs/nodes.md")).unwrap();
    assert!(
        generated == committed,
        "docs/nodes.md is stale: run `cargo run --release -- nodes --markdown > docs/nodes.md`"
    );
    for kind in [
        "ProceduralVolume",
        "VolumeFile",
        "MeshFile",
        "MarchingCubes",
        "Camera",
        "Light",
        "GBuffer",
        "ShadedSurface",
        "SaveImage",
    ] {
        assert!(
            generated.contains(&format!("### {kind}")),
            "{kind} missing from the catalogue"
        );
    }
}

/// The help the Inspector shows on hover is each parameter's doc line (issue 24: help written
/// as formulas only, "c_a of eq. 3", told an illustrator nothing): every parameter of every kind
/// says in at least two words of its own what it does, beside any symbol or equation.
#[test]
fn every_parameter_says_in_words_what_it_does() {
    const NOT_WORDS: [&str; 6] = ["the", "and", "for", "with", "eq", "of"];
    let registry = hatchery_nodes::registry();
    let mut bare = Vec::new();
    for schema in registry.schemas() {
        for param in &schema.params {
            let words = param
                .doc
                .split(|c: char| !c.is_ascii_alphabetic())
                .filter(|w| w.len() >= 3 && !NOT_WORDS.contains(&w.to_ascii_lowercase().as_str()))
                .count();
            if words < 2 {
                bare.push(format!("{}.{}: {:?}", schema.kind, param.name, param.doc));
            }
        }
    }
    assert!(
        bare.is_empty(),
        "parameters without words:\n{}",
        bare.join("\n")
    );
}

/// Groups, reroutes and frames organise the editor only: the CLI renders a graph that uses all
/// three (tests/fixtures/organised_shaded_surface.ron: graphs/shaded_surface.ron with its volume
/// nodes grouped, the mesh wire through a reroute, and a frame) exactly as the plain preset.
#[test]
fn the_cli_renders_groups_reroutes_and_frames_as_the_plain_graph() {
    let dir = tempfile::tempdir().unwrap();
    let render = |graph: &str, name: &str| {
        let out = dir.path().join(name);
        let output = hatchery(&[
            "render",
            graph,
            "-o",
            &out.to_string_lossy(),
            "--size",
            "160x120",
        ]);
        assert!(output.status.success(), "{graph}: {}", stderr(&output));
        common::read_png(&out)
    };
    let organised = render(
        "tests/fixtures/organised_shaded_surface.ron",
        "organised.png",
    );
    let plain = render("graphs/shaded_surface.ron", "plain.png");
    assert!(common::non_background_fraction(&organised) > 0.05, "blank");
    assert_eq!(organised.dimensions(), plain.dimensions());
    common::assert_images_close(
        "organised_vs_plain",
        &common::rgba8_pixels(&organised),
        &common::rgba8_pixels(&plain),
        organised.width(),
        1.0,
    );
    let output = hatchery(&["validate", "tests/fixtures/organised_shaded_surface.ron"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let output = hatchery(&[
        "fmt",
        "--check",
        "tests/fixtures/organised_shaded_surface.ron",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
}

#[test]
fn fmt_check_accepts_canonical_presets() {
    for preset in ["graphs/shaded_surface.ron", "graphs/brain_surface.ron"] {
        let output = hatchery(&["fmt", "--check", preset]);
        assert!(output.status.success(), "{preset}: {}", stderr(&output));
    }
}

#[test]
fn no_gpu_adapter_is_a_clear_error_saying_what_to_install() {
    // Metal does not exist on this platform, so restricting wgpu to it finds no adapter at all.
    if cfg!(target_os = "macos") {
        return;
    }
    let output = Command::new(env!("CARGO_BIN_EXE_hatchery"))
        .args([
            "render",
            "graphs/shaded_surface.ron",
            "--size",
            "32x32",
            "-o",
        ])
        .arg(std::env::temp_dir().join("hatchery-no-adapter.png"))
        .env("HATCHERY_BACKEND", "metal")
        .current_dir(common::repo_root())
        .output()
        .unwrap();
    assert_clean_failure(&output, &["no GPU adapter found", "mesa-vulkan-drivers"]);
}

#[test]
fn every_intermediate_buffer_of_the_hidden_structures_preset_can_be_dumped() {
    // The buffers of Fischer et al.'s Fig. 3 (layer 1), 5 (layer 2) and 7 (silhouettes), and the rest.
    let dir = tempfile::tempdir().unwrap();
    let ports = [
        ("layer1", "gbuffer", 4),
        ("layer2", "gbuffer", 4),
        ("secondary", "intensity", 0),
        ("secondary", "gbuffer", 4),
        ("silhouette1", "mask", 0),
        ("silhouette2", "mask", 0),
        ("intensity1", "intensity", 0),
        ("hatching", "mask", 0),
        ("secondary_behind", "mask", 0),
        ("secondary_final", "mask", 0),
        ("back_layer", "image", 4),
        ("front_hatching", "image", 4),
    ];
    let mut args: Vec<String> = [
        "render",
        "graphs/hidden_structures.ron",
        "--size",
        "160x120",
        "-o",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push(dir.path().join("final.png").to_string_lossy().into_owned());
    for (node, port, _) in ports {
        for ext in ["npy", "png"] {
            args.push("--dump".into());
            args.push(format!(
                "{node}.{port}={}",
                dir.path().join(format!("{node}.{port}.{ext}")).display()
            ));
        }
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = hatchery(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    for (node, port, channels) in ports {
        let array = common::npy::read_npy(&dir.path().join(format!("{node}.{port}.npy"))).unwrap();
        let mut shape = vec![120, 160];
        if channels > 0 {
            shape.push(channels);
        }
        assert_eq!(array.shape, shape, "{node}.{port}");
        assert!(
            array.data.iter().all(|v| v.is_finite()),
            "{node}.{port} has non-finite values"
        );
        let picture = common::read_png(&dir.path().join(format!("{node}.{port}.png")));
        assert_eq!(picture.dimensions(), (160, 120), "{node}.{port}");
    }
    // Layer 1 and layer 2 differ (peeling did something), and the silhouettes are not empty.
    let l1 = common::npy::read_npy(&dir.path().join("layer1.gbuffer.npy")).unwrap();
    let l2 = common::npy::read_npy(&dir.path().join("layer2.gbuffer.npy")).unwrap();
    let behind = l1
        .data
        .chunks(4)
        .zip(l2.data.chunks(4))
        .filter(|(a, b)| b[0] < 1.0 && b[0] > a[0])
        .count();
    assert!(
        behind > 1000,
        "layer 2 must lie behind layer 1 on the block: {behind} pixels"
    );
    let silhouettes = common::npy::read_npy(&dir.path().join("silhouette2.mask.npy")).unwrap();
    assert!(silhouettes.data.iter().filter(|v| **v > 0.5).count() > 100);
}

#[test]
fn a_camera_dumps_to_json_for_other_tools() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cam.json");
    let output = hatchery(&[
        "render",
        "graphs/shaded_surface.ron",
        "-o",
        &dir.path().join("out.png").to_string_lossy(),
        "--size",
        "160x120",
        "--set",
        "shells.resolution=24",
        "--dump",
        &format!("camera.camera={}", path.display()),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let vec3 = |key: &str| -> Vec<f64> {
        json[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    // The preset's camera: azimuth 30°, elevation 20°, distance 3.5 around the origin, y up.
    let (eye, target) = (vec3("eye"), vec3("target"));
    assert_eq!(target, vec![0.0, 0.0, 0.0]);
    assert_eq!(vec3("up"), vec![0.0, 1.0, 0.0]);
    let distance = eye.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((distance - 3.5).abs() < 1e-4, "eye {eye:?}");
    assert!(
        (eye[1] / 3.5 - 20f64.to_radians().sin()).abs() < 1e-4,
        "eye {eye:?}"
    );
    // The field of view spans the shorter (vertical) side of the 160×120 frame.
    assert!((json["fov_y_deg"].as_f64().unwrap() - 40.0).abs() < 1e-3);
    assert_eq!(json["width"], 160);
    // Other values are refused with a clear error.
    let output = hatchery(&[
        "render",
        "graphs/shaded_surface.ron",
        "--set",
        "shells.resolution=24",
        "--dump",
        &format!("shaded.image={}", path.display()),
    ]);
    assert_clean_failure(&output, &[".json is written for cameras"]);
}

#[test]
fn the_readme_main_command_renders_the_labelled_default_as_png_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("figure.png");
    let output = hatchery(&[
        "render",
        "graphs/default.ron",
        "-o",
        png.to_str().unwrap(),
        "--size",
        "480x360",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let picture = common::read_png(&png);
    assert_eq!(picture.dimensions(), (480, 360));
    // The SVG beside it carries the labels as text.
    let svg = std::fs::read_to_string(dir.path().join("figure.svg")).unwrap();
    for part in ["cylinder bore", "piston", "oil gallery"] {
        assert!(
            svg.contains(&format!(">{part}<")),
            "no label `{part}` in the SVG"
        );
    }
    // Nothing was written into graphs/.
    assert!(!common::repo_root().join("graphs/default.svg").exists());
    assert!(!common::repo_root().join("graphs/default.png").exists());
}

/// Issue 29: no module of a crate imports, directly or through others, a module that imports
/// it (scripts/import-circles.py reads every crate's `crate::` paths).
#[test]
fn no_crate_has_import_circles_between_its_files() {
    let script = common::repo_root().join("scripts/import-circles.py");
    let out = match std::process::Command::new("python3").arg(&script).output() {
        Ok(out) => out,
        Err(e) => {
            eprintln!("skipped: python3 is not installed ({e})");
            return;
        }
    };
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "import circles:\n{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("crates/hatchery-nodes/src"), "{text}");
}
