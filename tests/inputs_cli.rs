//! Graph inputs on the command line (issue 25): `hatchery inputs` on every preset, `--input`
//! swapping data, one-line errors naming the input, `hatchery presets`.

mod common;

use common::hatchery;
use std::process::Output;

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// One `error:` line holding every needle, no panic, non-zero exit.
fn assert_one_error(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "expected failure: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(lines.len(), 1, "{err}");
    for n in needles {
        assert!(lines[0].contains(n), "`{n}` missing from: {}", lines[0]);
    }
}

/// Every preset lists its inputs as JSON; every file-reading parameter of a preset is bound to
/// one of them; the defaults are the files the preset reads.
#[test]
fn every_preset_declares_the_files_it_reads_as_inputs() {
    let registry = hatchery_nodes::registry();
    for preset in common::presets() {
        let rel = preset.strip_prefix(common::repo_root()).unwrap();
        let out = hatchery(&["inputs", rel.to_str().unwrap(), "--json"]);
        assert!(
            out.status.success(),
            "{}: {}",
            rel.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let list: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        let list = list.as_array().unwrap();
        let bound: Vec<String> = list
            .iter()
            .flat_map(|i| {
                for key in ["name", "type", "doc", "default"] {
                    assert!(i[key].is_string(), "{}: {key} in {i}", rel.display());
                }
                assert!(
                    !i["doc"].as_str().unwrap().is_empty(),
                    "{}: {i}",
                    rel.display()
                );
                let default = std::path::Path::new(i["default"].as_str().unwrap());
                assert!(
                    default.exists(),
                    "{}: default {} missing",
                    rel.display(),
                    default.display()
                );
                i["to"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|t| t.as_str().unwrap().to_owned())
                    .collect::<Vec<_>>()
            })
            .collect();
        let graph = hatchery_graph::Graph::load_file(&preset, &registry).unwrap();
        for node in graph.nodes() {
            let schema = node.schema(&registry).unwrap();
            for spec in schema.params.iter().filter(|p| p.reads.is_some()) {
                let written = node.params.text(spec.name);
                let key = format!("{}.{}", node.id, spec.name);
                assert!(
                    written.is_empty() || bound.contains(&key),
                    "{}: {key} reads {written} but no input is bound to it",
                    rel.display()
                );
            }
        }
    }
}

#[test]
fn input_swaps_data_and_bad_inputs_are_one_line_errors_naming_the_input() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("brain.png");
    let out_png = out_png.to_str().unwrap();
    // The WM map given as the MRI renders (another value range, same grid).
    let wm = common::shared_data("volumes/mni152_wm.nii.gz");
    let o = hatchery(&[
        "render",
        "graphs/brain_surface.ron",
        "--input",
        &format!("volume={}", wm.display()),
        "--size",
        "96x72",
        "-o",
        out_png,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let picture = common::read_png(std::path::Path::new(out_png));
    assert!(common::non_background_fraction(&picture) > 0.1);

    let bunny = common::shared_data("meshes/bunny.obj");
    let bunny = bunny.to_str().unwrap();
    let cases: [(Vec<String>, Vec<&str>); 5] = [
        (
            vec!["--input".into(), "vol=x.nii".into()],
            vec!["no input `vol`", "inputs are: volume"],
        ),
        (
            vec!["--input".into(), format!("volume={bunny}")],
            vec!["input `volume` takes a volume file", "is a mesh file"],
        ),
        (
            vec!["--input".into(), "volume=/no/such/head.nii.gz".into()],
            vec!["input `volume`: cannot read", "head.nii.gz"],
        ),
        (
            vec!["--input".into(), "volume".into()],
            vec!["expected NAME=PATH"],
        ),
        (
            vec![
                "--input".into(),
                format!("volume={}", dir.path().join("bad.nii").display()),
            ],
            vec!["input `volume`", "bad.nii"],
        ),
    ];
    std::fs::write(dir.path().join("bad.nii"), b"not a nifti file").unwrap();
    for (extra, needles) in cases {
        let mut args = vec![
            "render",
            "graphs/brain_surface.ron",
            "--size",
            "32x24",
            "-o",
            out_png,
        ];
        args.extend(extra.iter().map(String::as_str));
        assert_one_error(&hatchery(&args), &needles);
    }
    // A graph without inputs says so.
    assert_one_error(
        &hatchery(&[
            "render",
            "graphs/shaded_surface.ron",
            "--input",
            "volume=a.nii",
            "-o",
            out_png,
        ]),
        &["no input `volume`", "declares no inputs"],
    );
}

#[test]
fn presets_lists_every_preset_with_its_description_and_inputs() {
    let o = hatchery(&["presets", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let list: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let list = list.as_array().unwrap();
    assert_eq!(list.len(), common::presets().len());
    for p in list {
        assert!(p.get("error").is_none(), "{p}");
        assert!(
            !p["description"].as_str().unwrap().is_empty(),
            "no description: {p}"
        );
    }
    let frog = list.iter().find(|p| p["name"] == "two_level_frog").unwrap();
    let names: Vec<&str> = frog["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["labels", "names"]);
    let text = stdout(&hatchery(&["presets"]));
    assert!(
        text.contains("brain_surface\n") && text.contains("inputs: volume (volume)"),
        "{text}"
    );
    assert!(text.contains("inputs: none (procedural)"), "{text}");
}
