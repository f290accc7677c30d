//! `hatchery bench`: runs a graph's nodes N times from scratch and reports per-node medians.

use anyhow::Result;
use hatchery_graph::SchemaLookup;
use hatchery_nodes::{Session, Value};
use indicatif::{ProgressBar, ProgressStyle};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

fn median(values: &mut [Duration]) -> Duration {
    values.sort();
    values[values.len() / 2]
}

fn ms(d: Duration) -> String {
    format!("{:.2}", d.as_secs_f64() * 1000.0)
}

pub fn run(session: &mut Session, graph: &Path, frames: usize) -> Result<()> {
    let gpu_timing = session.ctx.enable_gpu_timing();
    // Benchmark what the sinks need, without writing files every frame.
    let mut targets: Vec<String> = Vec::new();
    for node in session.graph.nodes() {
        let sink = session.registry.schema(&node.kind).is_some_and(|s| s.sink);
        if sink {
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
    let targets: Vec<&str> = targets.iter().map(String::as_str).collect();

    let mut cpu: BTreeMap<String, Vec<Duration>> = BTreeMap::new();
    let mut gpu: BTreeMap<String, Vec<Duration>> = BTreeMap::new();
    let mut frame_times = Vec::new();
    let bar = ProgressBar::new(frames as u64 + 1);
    bar.set_style(
        ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} frames").expect("valid template"),
    );
    bar.set_message("bench");
    for frame in 0..=frames {
        session.executor.clear();
        let start = Instant::now();
        session.run(&targets)?;
        session.ctx.gpu.wait_idle();
        let elapsed = start.elapsed();
        bar.inc(1);
        if frame == 0 {
            continue; // warm-up: pipeline compilation, uploads
        }
        frame_times.push(elapsed);
        for (id, stats) in session.executor.stats() {
            cpu.entry(id.clone()).or_default().push(stats.cpu_time);
            if let Some(g) = stats.gpu_time {
                gpu.entry(id.clone()).or_default().push(g);
            }
        }
    }
    bar.finish_and_clear();

    let (w, h) = session.ctx.size();
    println!(
        "graph: {}  size: {w}x{h}  frames: {frames} (+1 warm-up, not counted)",
        graph.display()
    );
    println!("adapter: {}", session.ctx.gpu.describe());
    if session.ctx.gpu.is_software() {
        println!("note: a CPU (software) driver: GPU times below are CPU timings of the driver");
    }
    if !gpu_timing {
        println!("note: this adapter has no timestamp queries inside encoders: no GPU times");
    }
    println!(
        "{:<24} {:<18} {:>14} {:>14}",
        "node", "kind", "cpu median ms", "gpu median ms"
    );
    for id in session.graph.topological_order() {
        let Some(times) = cpu.get_mut(id) else {
            continue;
        };
        let kind = session
            .graph
            .node(id)
            .map(|n| n.kind.as_str())
            .unwrap_or("");
        let g = gpu
            .get_mut(id)
            .map(|t| ms(median(t)))
            .unwrap_or_else(|| "-".into());
        println!(
            "{:<24} {:<18} {:>14} {:>14}",
            id,
            kind,
            ms(median(times)),
            g
        );
    }
    let mut sorted = frame_times.clone();
    sorted.sort();
    println!(
        "frame (wall, all nodes from scratch, incl. GPU wait): median {} ms, min {} ms, max {} ms",
        ms(median(&mut frame_times)),
        ms(sorted[0]),
        ms(sorted[sorted.len() - 1])
    );
    Ok(())
}

/// A short note on a node's first output (mesh size, volume size) for the report.
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
