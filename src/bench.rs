//! `hatchery bench`: measures graphs frame by frame, side by side in one run.
//!
//! Every (graph, scenario) pair is measured in turn inside each frame, so that the machine's
//! load drifts equally over all of them and their ratios are fair. Scenarios:
//! - `full`: every node from scratch (loading and geometry included);
//! - `orbit:CAMERA`: the camera's azimuth advances each frame (an animation, as in the papers'
//!   frame-rate tables): the camera and everything below it re-run, geometry stays cached;
//! - `vary:NODE.PARAM=a,b,…`: the parameter cycles through the values: the cached re-render after
//!   changing one parameter.

use anyhow::{Context, Result, bail};
use hatchery_graph::SchemaLookup;
use hatchery_nodes::{Session, Value};
use indicatif::{ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::{Duration, Instant};

#[derive(Clone, Debug)]
pub enum Scenario {
    Full,
    Orbit {
        camera: String,
    },
    Vary {
        node: String,
        param: String,
        values: Vec<String>,
    },
}

impl Scenario {
    pub fn parse(text: &str) -> Result<Scenario> {
        if text == "full" {
            return Ok(Scenario::Full);
        }
        if let Some(camera) = text.strip_prefix("orbit:") {
            return Ok(Scenario::Orbit {
                camera: camera.to_owned(),
            });
        }
        if let Some(rest) = text.strip_prefix("vary:") {
            let (target, values) = rest
                .split_once('=')
                .context("vary:NODE.PARAM=a,b,… expected")?;
            let (node, param) = target
                .split_once('.')
                .context("vary:NODE.PARAM=a,b,… expected")?;
            let values: Vec<String> = values.split(',').map(|v| v.trim().to_owned()).collect();
            if values.len() < 2 {
                bail!("--scenario {text}: give at least two values to alternate");
            }
            return Ok(Scenario::Vary {
                node: node.to_owned(),
                param: param.to_owned(),
                values,
            });
        }
        bail!("--scenario {text}: expected `full`, `orbit:CAMERA` or `vary:NODE.PARAM=a,b,…`")
    }

    fn name(&self) -> String {
        match self {
            Scenario::Full => "full".into(),
            Scenario::Orbit { camera } => format!("orbit:{camera}"),
            Scenario::Vary { node, param, .. } => format!("vary:{node}.{param}"),
        }
    }

    fn applies_to(&self, session: &Session) -> bool {
        match self {
            Scenario::Full => true,
            Scenario::Orbit { camera } => session
                .graph
                .node(camera)
                .is_some_and(|n| n.kind == "Camera"),
            Scenario::Vary { node, .. } => session.graph.node(node).is_some(),
        }
    }

    /// Makes the change this scenario measures, before frame `frame` of `frames`.
    fn apply(&self, session: &mut Session, frame: usize, frames: usize) -> Result<()> {
        match self {
            Scenario::Full => session.executor.clear(),
            Scenario::Orbit { camera } => {
                let start = session
                    .graph
                    .node(camera)
                    .map(|n| n.params.float("azimuth"))
                    .unwrap_or(0.0);
                let step = 360.0 / (frames + 1) as f64;
                let azimuth = (start + step + 180.0).rem_euclid(360.0) - 180.0;
                session.set_param_text(camera, "azimuth", &azimuth.to_string())?;
            }
            Scenario::Vary {
                node,
                param,
                values,
            } => {
                session.set_param_text(node, param, &values[frame % values.len()])?;
            }
        }
        Ok(())
    }
}

/// What the sinks of a graph need, without writing files every frame.
fn targets(session: &Session) -> Vec<String> {
    let mut targets: Vec<String> = Vec::new();
    for node in session.graph.nodes() {
        if session.registry.schema(&node.kind).is_some_and(|s| s.sink) {
            targets.extend(
                session
                    .graph
                    .input_sources(&node.id)
                    .values()
                    .map(|(source, _)| source.to_string()),
            );
        }
    }
    if targets.is_empty() {
        targets = session
            .graph
            .nodes()
            .filter(|n| !session.graph.has_consumers(&n.id))
            .map(|n| n.id.clone())
            .collect();
    }
    targets.sort();
    targets.dedup();
    targets
}

fn median(values: &[Duration]) -> Duration {
    let mut sorted = values.to_vec();
    sorted.sort();
    sorted[sorted.len() / 2]
}

fn ms(d: Duration) -> String {
    format!("{:.2}", d.as_secs_f64() * 1000.0)
}

/// Measurements of one (graph, scenario) at one size.
#[derive(Default)]
struct Series {
    frames: Vec<Duration>,
    cpu: BTreeMap<String, Vec<Duration>>,
    gpu: BTreeMap<String, Vec<Duration>>,
}

pub fn run(
    graphs: &[PathBuf],
    sessions: &mut [Session],
    scenarios: &[Scenario],
    sizes: &[(u32, u32)],
    frames: usize,
) -> Result<()> {
    let mut gpu_timing = true;
    for session in sessions.iter_mut() {
        gpu_timing &= session.ctx.enable_gpu_timing();
    }
    let all_targets: Vec<Vec<String>> = sessions.iter().map(targets).collect();
    // A scenario applies to the graphs that have the node it changes.
    let pairs: Vec<(usize, usize)> = (0..sessions.len())
        .flat_map(|g| (0..scenarios.len()).map(move |s| (g, s)))
        .filter(|&(g, s)| scenarios[s].applies_to(&sessions[g]))
        .collect();
    if pairs.is_empty() {
        bail!("no scenario applies to any of the graphs (check the node names)");
    }

    let bar = ProgressBar::new((sizes.len() * (frames + 1) * pairs.len()) as u64);
    bar.set_style(
        ProgressStyle::with_template("bench {bar:30} {pos}/{len} runs {msg}")
            .expect("valid template"),
    );
    let mut results: BTreeMap<((u32, u32), usize, usize), Series> = BTreeMap::new();
    for &(width, height) in sizes {
        bar.set_message(format!("{width}x{height}"));
        for session in sessions.iter_mut() {
            session.ctx.set_size(width, height)?;
        }
        for frame in 0..=frames {
            for &(g, s) in &pairs {
                let session = &mut sessions[g];
                scenarios[s].apply(session, frame, frames)?;
                let targets: Vec<&str> = all_targets[g].iter().map(String::as_str).collect();
                let start = Instant::now();
                let report = session.run(&targets)?;
                session.ctx.gpu.wait_idle();
                let elapsed = start.elapsed();
                bar.inc(1);
                if frame == 0 {
                    continue; // warm-up: pipelines, uploads, first loads
                }
                let series = results.entry(((width, height), g, s)).or_default();
                series.frames.push(elapsed);
                for id in &report.executed {
                    let stats = &session.executor.stats()[id];
                    series
                        .cpu
                        .entry(id.clone())
                        .or_default()
                        .push(stats.cpu_time);
                    if let Some(t) = stats.gpu_time {
                        series.gpu.entry(id.clone()).or_default().push(t);
                    }
                }
            }
        }
    }
    bar.finish_and_clear();

    let gpu = &sessions[0].ctx.gpu;
    println!("adapter: {}", gpu.describe());
    if gpu.is_software() {
        println!(
            "note: a CPU (software) driver: every time below, GPU times included, is CPU time"
        );
    }
    if !gpu_timing {
        println!("note: this adapter has no timestamp queries inside encoders: no GPU times");
    }
    println!(
        "frames: {frames} per (graph, scenario, size), after 1 warm-up; medians; interleaved in one run"
    );
    for ((size, g, s), series) in &results {
        let session = &sessions[*g];
        println!();
        println!(
            "{} — {} — {}x{}",
            graphs[*g].display(),
            scenarios[*s].name(),
            size.0,
            size.1
        );
        println!(
            "  {:<22} {:<18} {:>12} {:>12}  output",
            "node", "kind", "cpu ms", "gpu ms"
        );
        for id in session.graph.topological_order() {
            let Some(times) = series.cpu.get(id) else {
                continue;
            };
            let kind = session
                .graph
                .node(id)
                .map(|n| n.kind.as_str())
                .unwrap_or("");
            let g = series
                .gpu
                .get(id)
                .map(|t| ms(median(t)))
                .unwrap_or_else(|| "-".into());
            // Fused nodes: the pass's times are on its last node.
            let fused = &session.executor.stats()[id].fused_with;
            let note = match fused.last() {
                None => describe_output(session, id),
                Some(last) if last == id => format!("one pass: {}", fused.join(", ")),
                Some(last) => format!("fused into {last}'s pass"),
            };
            println!(
                "  {:<22} {:<18} {:>12} {:>12}  {}",
                id,
                kind,
                ms(median(times)),
                g,
                note
            );
        }
        println!(
            "  frame (wall, incl. GPU wait): median {} ms",
            ms(median(&series.frames))
        );
        // Cached inputs (meshes, volumes) do not re-run in orbit/vary scenarios but say what
        // the frame drew: list them so a report states its triangle and voxel counts.
        let data: Vec<String> = session
            .graph
            .topological_order()
            .into_iter()
            .filter(|id| !series.cpu.contains_key(*id))
            .filter_map(|id| {
                let note = describe_output(session, id);
                (!note.is_empty()).then(|| format!("{id} {note}"))
            })
            .collect();
        if !data.is_empty() {
            println!("  cached data: {}", data.join(", "));
        }
    }

    println!();
    println!("summary: median frame time in ms (ratio to the first column)");
    let columns: Vec<String> = pairs
        .iter()
        .map(|&(g, s)| {
            format!(
                "{}:{} [{}{}{}]",
                g + 1,
                file_name(&graphs[g]),
                scenarios[s].name(),
                match (
                    sessions[g].executor.fusion(),
                    sessions[g].executor.keep_fused()
                ) {
                    (false, _) => ", unfused",
                    (true, true) => ", interactive",
                    (true, false) => "",
                },
                if sessions[g]
                    .ctx
                    .gpu
                    .volume_limits()
                    .is_ok_and(|l| l.max_texture_3d.is_some())
                {
                    ", bricked"
                } else {
                    ""
                }
            )
        })
        .collect();
    println!("| size | {} |", columns.join(" | "));
    println!("|---|{}", "---|".repeat(columns.len()));
    for &size in sizes {
        let base = results
            .get(&(size, pairs[0].0, pairs[0].1))
            .map(|s| median(&s.frames));
        let cells: Vec<String> = pairs
            .iter()
            .map(
                |&(g, s)| match (results.get(&(size, g, s)).map(|r| median(&r.frames)), base) {
                    (Some(t), Some(b)) => {
                        format!("{} ({:.2}×)", ms(t), t.as_secs_f64() / b.as_secs_f64())
                    }
                    _ => "-".into(),
                },
            )
            .collect();
        println!("| {}x{} | {} |", size.0, size.1, cells.join(" | "));
    }
    Ok(())
}

fn file_name(path: &std::path::Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// A short note on a node's first output (mesh or volume size) for the report.
fn describe_output(session: &Session, id: &str) -> String {
    match session.executor.output(id, 0) {
        Some(Value::Mesh(mesh)) => format!("{} triangles", mesh.data.triangle_count()),
        Some(Value::Volume(volume)) => {
            let [x, y, z] = volume.data.dims;
            format!("{x}x{y}x{z} voxels")
        }
        _ => String::new(),
    }
}
