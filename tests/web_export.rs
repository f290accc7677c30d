//! `hatchery export-web` (issue 33): the folder it writes, natively. The page itself runs in
//! Chromium in scripts/web-test.sh; here a stand-in browser build (two marked files) shows what
//! the command copies, and the exported graph is rendered again from the folder to show that it
//! is self-contained: the same pixels as its poster.

mod common;

use common::{hatchery, read_png};
use std::path::{Path, PathBuf};
use std::process::Output;

/// A stand-in for target/web-pkg: the two files the command copies, with known bytes.
fn fake_pkg(dir: &Path) -> PathBuf {
    let pkg = dir.join("pkg");
    std::fs::create_dir_all(&pkg).unwrap();
    std::fs::write(pkg.join("hatchery_web.js"), "// glue").unwrap();
    std::fs::write(pkg.join("hatchery_web_bg.wasm"), b"\0asm-test").unwrap();
    pkg
}

fn ok(o: &Output) {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

fn export(graph: &str, out: &Path, pkg: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "export-web",
        graph,
        "-o",
        out.to_str().unwrap(),
        "--web-pkg",
        pkg.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    hatchery(&args)
}

/// Renders `graph` natively at `size` and returns the picture.
fn render(graph: &Path, size: &str, dir: &Path) -> image::RgbaImage {
    let png = dir.join("native.png");
    ok(&hatchery(&[
        "render",
        graph.to_str().unwrap(),
        "--size",
        size,
        "-o",
        png.to_str().unwrap(),
    ]));
    read_png(&png)
}

fn manifest(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("figure.json")).unwrap()).unwrap()
}

#[test]
fn the_default_figure_folder_holds_the_page_the_build_the_graph_and_its_poster() {
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    let out = dir.path().join("figure");
    ok(&export(
        "graphs/default.ron",
        &out,
        &pkg,
        &["--size", "160x120"],
    ));

    let m = manifest(&out);
    assert_eq!(
        (&m["graph"], &m["width"], &m["height"], &m["scale"]),
        (
            &serde_json::json!("figure.ron"),
            &serde_json::json!(160),
            &serde_json::json!(120),
            &serde_json::json!(1.0)
        )
    );
    assert_eq!(m["files"], serde_json::json!([]));
    assert_eq!(
        std::fs::read(out.join("hatchery_web_bg.wasm")).unwrap(),
        b"\0asm-test"
    );
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains(r#"<canvas id="figure" width="160" height="120">"#));
    assert!(page.contains("<title>the default: the hidden-structures engine block"));
    assert!(!page.contains("{{"), "every placeholder filled");

    // The poster is the native render of the graph at that size, and the exported graph renders
    // the same pixels from its folder.
    let poster = read_png(&out.join("poster.png"));
    assert_eq!(
        poster,
        render(Path::new("graphs/default.ron"), "160x120", dir.path())
    );
    assert_eq!(
        poster,
        render(&out.join("figure.ron"), "160x120", dir.path())
    );
    let exported = std::fs::read_to_string(out.join("figure.ron")).unwrap();
    assert!(
        exported.contains("controls: ["),
        "the controls travel with the graph"
    );
}

#[test]
fn the_data_a_graph_reads_is_copied_and_the_graph_points_at_the_copies() {
    let mri = common::shared_data("volumes/mni152_t1.nii.gz");
    if !mri.is_file() {
        eprintln!("skipped: {} is missing (../shared/data)", mri.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    let out = dir.path().join("brain");
    ok(&export(
        "graphs/brain_surface.ron",
        &out,
        &pkg,
        &["--size", "96x72"],
    ));

    assert_eq!(
        manifest(&out)["files"],
        serde_json::json!(["data/1/mni152_t1.nii.gz"])
    );
    assert_eq!(
        std::fs::read(out.join("data/1/mni152_t1.nii.gz")).unwrap(),
        std::fs::read(&mri).unwrap()
    );
    let exported = std::fs::read_to_string(out.join("figure.ron")).unwrap();
    assert!(
        exported.contains(r#""path": "data/1/mni152_t1.nii.gz""#),
        "{exported}"
    );
    let poster = read_png(&out.join("poster.png"));
    assert_eq!(poster, render(&out.join("figure.ron"), "96x72", dir.path()));
}

/// A CustomShader's file decides its ports, so the graph refuses to change it while open; the
/// export writes the copy's path into the document instead.
#[test]
fn a_custom_shader_travels_with_the_figure() {
    if !common::shared_data("volumes/mni152_t1.nii.gz").is_file() {
        eprintln!("skipped: ../shared/data is missing");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    let out = dir.path().join("shader");
    ok(&export(
        "graphs/custom_shader_brain.ron",
        &out,
        &pkg,
        &["--size", "96x72"],
    ));
    assert_eq!(
        manifest(&out)["files"],
        serde_json::json!(["data/1/depth_darkening.wgsl", "data/2/mni152_t1.nii.gz"])
    );
    let exported = std::fs::read_to_string(out.join("figure.ron")).unwrap();
    assert!(
        exported.contains(r#""shader": "data/1/depth_darkening.wgsl""#),
        "{exported}"
    );
    let poster = read_png(&out.join("poster.png"));
    assert_eq!(poster, render(&out.join("figure.ron"), "96x72", dir.path()));
}

#[test]
fn a_metaimage_header_travels_with_the_voxel_file_it_names() {
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    // A 12³ ball of 200 in 0, as ITK writes a MetaImage: a text header naming its raw voxels.
    let n = 12usize;
    let voxels: Vec<u8> = (0..n * n * n)
        .map(|i| {
            let (x, y, z) = (i % n, (i / n) % n, i / (n * n));
            let d = |a: usize| a as f32 - 5.5;
            if d(x).hypot(d(y)).hypot(d(z)) < 4.0 {
                200
            } else {
                0
            }
        })
        .collect();
    let data = dir.path().join("data");
    std::fs::create_dir_all(&data).unwrap();
    std::fs::write(data.join("ball.raw"), &voxels).unwrap();
    std::fs::write(
        data.join("ball.mhd"),
        "ObjectType = Image\nNDims = 3\nDimSize = 12 12 12\nElementSpacing = 4 4 4\n\
         ElementType = MET_UCHAR\nElementDataFile = ball.raw\n",
    )
    .unwrap();
    let out = dir.path().join("ball");
    let set = format!("mri.path={}", data.join("ball.mhd").display());
    ok(&export(
        "graphs/brain_surface.ron",
        &out,
        &pkg,
        &["--size", "64x48", "--set", &set],
    ));
    assert_eq!(
        manifest(&out)["files"],
        serde_json::json!(["data/1/ball.mhd", "data/1/ball.raw"])
    );
    assert_eq!(std::fs::read(out.join("data/1/ball.raw")).unwrap(), voxels);
    // Self-contained: with the original files gone the folder still renders its poster.
    std::fs::remove_dir_all(&data).unwrap();
    let poster = read_png(&out.join("poster.png"));
    assert_eq!(poster, render(&out.join("figure.ron"), "64x48", dir.path()));

    // Exported again into its own folder, from its own graph: the copies stay whole.
    ok(&export(
        out.join("figure.ron").to_str().unwrap(),
        &out,
        &pkg,
        &["--size", "64x48"],
    ));
    assert_eq!(std::fs::read(out.join("data/1/ball.raw")).unwrap(), voxels);
    assert_eq!(read_png(&out.join("poster.png")), poster);
    assert!(!out.join(".export-new").exists() && !out.join(".data-old").exists());
}

#[test]
fn a_folder_and_a_missing_build_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    let set = format!("mri.path={}", dir.path().display());
    let out = dir.path().join("refused");
    let o = export("graphs/brain_surface.ron", &out, &pkg, &["--set", &set]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("node `mri` reads the folder") && err.contains("single files only"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written for a refused export");

    // A file that means its folder (a DICOM series), and a header whose data lies outside its
    // folder: the page could fetch neither.
    let slice = dir.path().join("series/slice_001.dcm");
    std::fs::create_dir_all(slice.parent().unwrap()).unwrap();
    std::fs::write(&slice, b"not read").unwrap();
    let outside = dir.path().join("headers/ball.mhd");
    std::fs::create_dir_all(outside.parent().unwrap()).unwrap();
    std::fs::write(dir.path().join("ball.raw"), [0u8; 8]).unwrap();
    std::fs::write(
        &outside,
        "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = ../ball.raw\n",
    )
    .unwrap();
    for (file, needle) in [
        (&slice, "which means its whole folder (a DICOM series"),
        (
            &outside,
            "names its data as `../ball.raw`, which cannot travel with it",
        ),
    ] {
        let set = format!("mri.path={}", file.display());
        let o = export("graphs/brain_surface.ron", &out, &pkg, &["--set", &set]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(needle), "{err}");
        assert!(err.contains("node `mri`"), "{err}");
        assert!(!out.exists(), "nothing written for a refused export");
    }

    let o = export(
        "graphs/default.ron",
        &out,
        &dir.path().join("no-such-build"),
        &[],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert_eq!(
        err.lines().filter(|l| l.starts_with("error:")).count(),
        1,
        "{err}"
    );
    assert!(err.contains("run scripts/build-web.sh"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// Exports default.ron into `out` and expects a refusal saying `needle`.
fn refused_over(out: &Path, pkg: &Path, needle: &str) {
    let o = export("graphs/default.ron", out, pkg, &["--size", "32x24"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains(needle), "{err}");
}

/// A 2³ MetaImage beside its voxels, `data` naming them as `data_file`.
fn tiny_metaimage(dir: &Path, name: &str, data_file: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("tiny.raw"), [0u8, 50, 100, 150, 200, 250, 25, 75]).unwrap();
    let header = dir.join(name);
    std::fs::write(
        &header,
        format!(
            "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = {data_file}\n"
        ),
    )
    .unwrap();
    header
}

#[test]
fn a_refused_export_leaves_an_earlier_figure_as_it_was_and_a_new_one_replaces_its_data() {
    let dir = tempfile::tempdir().unwrap();
    let pkg = fake_pkg(dir.path());
    let out = dir.path().join("figure");
    let good = tiny_metaimage(&dir.path().join("good"), "tiny.mhd", "tiny.raw");
    let set = format!("mri.path={}", good.display());
    ok(&export(
        "graphs/brain_surface.ron",
        &out,
        &pkg,
        &["--size", "32x24", "--set", &set],
    ));
    let poster = std::fs::read(out.join("poster.png")).unwrap();
    let graph = std::fs::read_to_string(out.join("figure.ron")).unwrap();

    // Refused after the graph opened (its header names voxels by a path that cannot travel):
    // the figure already there keeps its poster, graph and data.
    let raw = dir.path().join("bad/tiny.raw");
    let bad = tiny_metaimage(&dir.path().join("bad"), "tiny.mhd", raw.to_str().unwrap());
    std::fs::write(&raw, [250u8, 250, 250, 250, 250, 250, 250, 0]).unwrap();
    let set = format!("mri.path={}", bad.display());
    // Its poster would differ from the one there (so a poster written before the refusal shows).
    let bad_render = dir.path().join("bad.png");
    ok(&hatchery(&[
        "render",
        "graphs/brain_surface.ron",
        "--size",
        "32x24",
        "--set",
        &set,
        "-o",
        bad_render.to_str().unwrap(),
    ]));
    assert_ne!(read_png(&bad_render), read_png(&out.join("poster.png")));
    let o = export(
        "graphs/brain_surface.ron",
        &out,
        &pkg,
        &["--size", "32x24", "--set", &set],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("cannot travel"),
        "{err}"
    );
    assert_eq!(std::fs::read(out.join("poster.png")).unwrap(), poster);
    assert_eq!(
        std::fs::read_to_string(out.join("figure.ron")).unwrap(),
        graph
    );
    assert!(out.join("data/1/tiny.raw").is_file());

    // Another graph exported over it: none of the earlier data stays behind.
    ok(&export(
        "graphs/default.ron",
        &out,
        &pkg,
        &["--size", "32x24", "--title", "Engine & <pistons>"],
    ));
    assert_eq!(manifest(&out)["files"], serde_json::json!([]));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains("<title>Engine &amp; &lt;pistons&gt;</title>"));
    assert!(
        !out.join("data").exists(),
        "the earlier export's data/ is left"
    );

    // A folder holding its own data/ (not an export's: no figure.json, another program's
    // figure.json) is not emptied, nor is a file added to an export's data/.
    let project = dir.path().join("project");
    std::fs::create_dir_all(project.join("data")).unwrap();
    std::fs::write(project.join("data/notes.txt"), "mine").unwrap();
    refused_over(&project, &pkg, "not an earlier export's");
    std::fs::write(project.join("figure.json"), r#"{"name": "my figure"}"#).unwrap();
    refused_over(&project, &pkg, "not an earlier export's");
    std::fs::create_dir_all(out.join("data/1")).unwrap();
    std::fs::write(out.join("data/1/notes.txt"), "mine").unwrap();
    refused_over(&out, &pkg, "holds data/1/notes.txt");
    assert_eq!(
        std::fs::read_to_string(out.join("data/1/notes.txt")).unwrap(),
        "mine"
    );
    assert!(!out.join(".export-new").exists() && !out.join(".data-old").exists());
    assert_eq!(
        std::fs::read_to_string(project.join("data/notes.txt")).unwrap(),
        "mine"
    );
}
