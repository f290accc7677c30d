//! `hatchery batch` (issue 27): sharded runs add up to the whole, a killed run resumes without
//! re-rendering what it finished, failing items are recorded and the rest go on, merge checks.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_hatchery"));
    c.current_dir(common::repo_root());
    c
}

fn batch(args: &[&str]) -> std::process::Output {
    bin()
        .arg("batch")
        .args(args)
        .output()
        .expect("hatchery runs")
}

fn text(o: &std::process::Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Output files (not manifests or hidden temporaries) with their bytes.
fn outputs(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "png" || e == "svg"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect()
}

/// `hatchery batch JOB --out OUT --merge` (`args` = [JOB, "--out", OUT]), which must succeed.
fn merged(args: &[&str]) -> std::process::Output {
    let o = batch(&[args, &["--merge"]].concat());
    assert!(o.status.success(), "{}", text(&o));
    o
}

fn job_file(dir: &Path, body: &str) -> PathBuf {
    let path = dir.join("job.ron");
    std::fs::write(&path, body).unwrap();
    path
}

#[test]
fn two_shards_equal_the_unsharded_run_byte_for_byte() {
    let tmp = tempfile::tempdir().unwrap();
    let (all, shards) = (tmp.path().join("all"), tmp.path().join("shards"));
    let job = "jobs/default_turntable.ron";
    let o = batch(&[job, "--out", all.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    for k in ["0/2", "1/2"] {
        let o = batch(&[job, "--out", shards.to_str().unwrap(), "--shard", k]);
        assert!(o.status.success(), "{}", text(&o));
    }
    let (a, b) = (outputs(&all), outputs(&shards));
    assert_eq!(a.len(), 4);
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (name, bytes) in &a {
        assert!(bytes == &b[name], "{name} differs between the runs");
    }
    // The four quarters are four different pictures.
    let distinct: std::collections::BTreeSet<_> = a.values().collect();
    assert_eq!(distinct.len(), 4);
    let o = merged(&[job, "--out", shards.to_str().unwrap()]);
    assert!(
        text(&o).contains("all 4 items present once"),
        "{}",
        text(&o)
    );
    let merged: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(shards.join("manifest.json")).unwrap())
            .unwrap();
    let items = merged["items"].as_array().unwrap();
    assert_eq!(items.len(), 4);
    assert_eq!(items[2]["params"]["camera.azimuth"], "180");
    assert_eq!(items[2]["output"], "frame_0002.png");
    assert_eq!(items[2]["sha256"].as_str().unwrap().len(), 64);
    assert!(items[2]["adapter"].as_str().unwrap().contains("("));
}

#[test]
fn shards_come_from_slurm_and_kubernetes_environments() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let o = bin()
        .args([
            "batch",
            "jobs/default_turntable.ron",
            "--out",
            out.to_str().unwrap(),
        ])
        .env("SLURM_ARRAY_TASK_ID", "4")
        .env("SLURM_ARRAY_TASK_MIN", "3")
        .env("SLURM_ARRAY_TASK_COUNT", "2")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(
        outputs(&out).keys().cloned().collect::<Vec<_>>(),
        ["frame_0001.png", "frame_0003.png"]
    );
    assert!(out.join("manifest-1-of-2.json").exists());
    let o = bin()
        .args([
            "batch",
            "jobs/default_turntable.ron",
            "--out",
            out.to_str().unwrap(),
        ])
        .env("JOB_COMPLETION_INDEX", "0")
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(
        text(&o).contains("give the job's completions as --shard-count"),
        "{}",
        text(&o)
    );
    let o = bin()
        .args([
            "batch",
            "jobs/default_turntable.ron",
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--shard-count", "2"])
        .env("JOB_COMPLETION_INDEX", "0")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(outputs(&out).len(), 4);
    merged(&["jobs/default_turntable.ron", "--out", out.to_str().unwrap()]);
}

#[test]
fn a_killed_run_resumes_without_rerendering_and_leaves_no_corrupt_file() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let root = common::repo_root();
    let job = job_file(
        tmp.path(),
        &format!(
            "(graph: {:?}, size: (160, 120), camera: Some(Orbit(node: \"camera\", frames: 24)), \
             output: \"turn_{{frame:03}}.png\")",
            root.join("graphs/hidden_structures.ron").to_string_lossy()
        ),
    );
    let mut child = bin()
        .args([
            "batch",
            job.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .stderr(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait until a few items are recorded, then SIGKILL it mid-run.
    let manifest = out.join("manifest-0-of-1.json");
    let start = std::time::Instant::now();
    loop {
        let n = std::fs::read_to_string(&manifest)
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .map_or(0, |m| m["items"].as_array().map_or(0, |a| a.len()));
        if n >= 3 {
            break;
        }
        assert!(start.elapsed().as_secs() < 120, "the run made no progress");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap(); // SIGKILL on Unix
    child.wait().unwrap();
    let before = outputs(&out);
    assert!(
        before.len() >= 3 && before.len() < 24,
        "{} outputs",
        before.len()
    );
    for (name, bytes) in &before {
        image::load_from_memory(bytes).unwrap_or_else(|e| panic!("{name} is corrupt: {e}"));
    }
    let o = batch(&[job.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    let summary = text(&o);
    let done = before.len();
    // Items whose file was written but not yet recorded are rendered again (same bytes).
    let stdout = String::from_utf8_lossy(&o.stdout);
    let rendered: usize = stdout
        .lines()
        .find_map(|l| l.strip_prefix("batch: ")?.split_once(" rendered, "))
        .and_then(|(n, _)| n.parse().ok())
        .unwrap_or_else(|| panic!("no summary line: {summary}"));
    assert!(rendered <= 24 - done + 1, "{summary}");
    assert!(
        summary.contains(&format!("{} done before", 24 - rendered)),
        "{summary}"
    );
    let after = outputs(&out);
    assert_eq!(after.len(), 24);
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty(), "temporaries left: {leftovers:?}");
    for (name, bytes) in &before {
        assert!(&after[name] == bytes, "{name} changed when resumed");
    }
    merged(&[job.to_str().unwrap(), "--out", out.to_str().unwrap()]);
}

#[test]
fn a_failing_item_is_recorded_and_the_rest_go_on() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    std::fs::write(tmp.path().join("broken.nii.gz"), b"not a volume").unwrap();
    let good = common::shared_data("volumes/mni152_gm.nii.gz");
    let job = job_file(
        tmp.path(),
        &format!(
            "(graph: {:?}, size: (64, 48), inputs: [{{\"volume\": {:?}}}, {{\"volume\": \
             \"broken.nii.gz\"}}], output: \"{{input}}.png\")",
            common::repo_root()
                .join("graphs/brain_surface.ron")
                .to_string_lossy(),
            good.to_string_lossy()
        ),
    );
    let o = batch(&[job.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("1 rendered, 0 done before, 1 failed"),
        "{}",
        text(&o)
    );
    assert!(out.join("mni152_gm.png").exists());
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("manifest-0-of-1.json")).unwrap())
            .unwrap();
    let failed = &m["items"][1];
    assert_eq!(failed["status"], "failed");
    let error = failed["error"].as_str().unwrap();
    assert!(
        error.starts_with("input `volume`: ") && error.contains("broken.nii.gz"),
        "{error}"
    );
    assert!(!error.contains('\n'));
    let o = batch(&[
        job.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--merge",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        text(&o).contains("item 1 (broken.png) failed: input `volume`"),
        "{}",
        text(&o)
    );
}

#[test]
fn bad_jobs_are_one_line_errors_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            "(graph: \"g.ron\", size: (8, 8), output: \"x_{colour}.png\")",
            "unknown placeholder `{colour}`",
        ),
        (
            "(graph: \"g.ron\", size: (8, 8), sweep: [(\"camera.azimuth\", [0, 90])], output: \"x.png\")",
            "items 0 and 1 both write `x.png`",
        ),
        (
            "(graph: \"g.ron\", size: (8, 8), output: \"x.jpg\")",
            "must end in .png",
        ),
        (
            "(graph: \"g.ron\", size: (8, 8), output: \"x.png\", colour: 1)",
            "job.ron:1:",
        ),
        (
            "(graph: \"g.ron\", size: (8, 8), sweep: [(\"azimuth\", [1])], output: \"x.png\")",
            "expected node.param",
        ),
    ];
    for (body, message) in cases {
        let job = job_file(tmp.path(), body);
        let o = batch(&[job.to_str().unwrap(), "--list"]);
        assert!(!o.status.success());
        let t = text(&o);
        assert!(t.contains(message) && t.contains("job.ron"), "{body}: {t}");
        assert_eq!(t.trim().lines().count(), 1, "{t}");
    }
}

/// `hatchery render GRAPH --orbit FRAMES --size SIZE -o OUT`, which must succeed.
fn orbit(graph: &str, frames: &str, size: &str, out: &Path) {
    let o = bin()
        .args(["render", graph, "--orbit", frames, "--size", size, "-o"])
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
}

/// The frames of an animated PNG.
fn apng_frames(path: &Path) -> Vec<Vec<u8>> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let n = reader
        .info()
        .animation_control()
        .expect("an animated PNG")
        .num_frames;
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    (0..n)
        .map(|_| {
            let info = reader.next_frame(&mut buf).unwrap();
            buf[..info.buffer_size()].to_vec()
        })
        .collect()
}

#[test]
fn orbit_animations_hold_the_batch_frames() {
    let tmp = tempfile::tempdir().unwrap();
    let root = common::repo_root();
    let graph = root.join("graphs/hidden_structures.ron");
    let apng = tmp.path().join("turn.png");
    orbit(graph.to_str().unwrap(), "6", "96x72", &apng);
    let frames = apng_frames(&apng);
    assert_eq!(frames.len(), 6);
    // The same turntable as a batch job: its PNG frames and its animation.
    let job = job_file(
        tmp.path(),
        &format!(
            "(graph: {:?}, size: (96, 72), camera: Some(Orbit(node: \"camera\", frames: 6)), \
             output: \"f_{{frame}}.png\", animation: Some(\"turn.gif\"), fps: Some(12.0))",
            graph.to_string_lossy()
        ),
    );
    let out = tmp.path().join("batch");
    let o = batch(&[job.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("wrote"), "{}", text(&o));
    for (i, frame) in frames.iter().enumerate() {
        let png = image::open(out.join(format!("f_{i}.png")))
            .unwrap()
            .to_rgba8();
        assert!(
            png.as_raw() == frame,
            "frame {i} differs between --orbit and the batch"
        );
    }
    assert!(
        frames[0] != frames[1],
        "the camera turned between frames 0 and 1"
    );
    use image::AnimationDecoder;
    let gif = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(out.join("turn.gif")).unwrap(),
    ))
    .unwrap()
    .into_frames()
    .collect_frames()
    .unwrap();
    assert_eq!(gif.len(), 6);
}

#[test]
fn orbit_video_plays_as_h264() {
    if Command::new("ffprobe").arg("-version").output().is_err() {
        eprintln!(
            "SKIPPED: ffmpeg/ffprobe are not installed (scripts/install-deps.sh installs them)"
        );
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let mp4 = tmp.path().join("turn.mp4");
    orbit("graphs/default.ron", "8", "97x64", &mp4);
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-show_entries"])
        .args([
            "stream=codec_name,width,height,nb_read_frames,pix_fmt",
            "-of",
            "compact",
        ])
        .arg(&mp4)
        .output()
        .unwrap();
    let info = String::from_utf8_lossy(&probe.stdout);
    assert!(
        info.contains("codec_name=h264")
            && info.contains("width=98")
            && info.contains("pix_fmt=yuv420p")
            && info.contains("nb_read_frames=8"),
        "{info}"
    );
    let o = bin()
        .args([
            "render",
            "graphs/default.ron",
            "--orbit",
            "8",
            "-o",
            "x.avi",
        ])
        .output()
        .unwrap();
    assert!(
        !o.status.success() && text(&o).contains(".mp4, .webm, .gif"),
        "{}",
        text(&o)
    );
}

#[test]
fn svg_outputs_are_the_graphs_figures() {
    let tmp = tempfile::tempdir().unwrap();
    let job = job_file(
        tmp.path(),
        &format!(
            "(graph: {:?}, size: (128, 96), sweep: [(\"camera.azimuth\", [10, 40])], \
             output: \"fig_{{camera.azimuth}}.svg\")",
            common::repo_root()
                .join("graphs/default.ron")
                .to_string_lossy()
        ),
    );
    let out = tmp.path().join("o");
    let o = batch(&[job.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    let figures = outputs(&out);
    assert_eq!(
        figures.keys().collect::<Vec<_>>(),
        ["fig_10.svg", "fig_40.svg"]
    );
    for (name, bytes) in &figures {
        let svg = String::from_utf8_lossy(bytes);
        assert!(
            svg.contains("<svg") && svg.contains("inkscape:groupmode"),
            "{name}"
        );
    }
    assert!(
        figures["fig_10.svg"] != figures["fig_40.svg"],
        "the views differ"
    );
}
