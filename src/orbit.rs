//! `hatchery render GRAPH --orbit N -o turn.mp4`: a turntable of the graph's camera as an
//! animation (MP4, WebM, GIF or APNG; see hatchery_batch::animation).

use anyhow::{Context, Result, bail};
use hatchery_graph::ParamValue;
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// Renders `frames` frames, the camera's azimuth turning a full circle from its value in the
/// graph, and writes them to `output` at `fps`.
pub fn render(
    graph: &Path,
    output: Option<&Path>,
    frame: &crate::FrameArgs,
    frames: usize,
    fps: f64,
    camera: Option<&str>,
) -> Result<()> {
    let start = Instant::now();
    let output = output.context("--orbit needs -o FILE (.mp4, .webm, .gif or .png)")?;
    hatchery_batch::animation::format_of(output).map_err(anyhow::Error::msg)?;
    if frames == 0 {
        bail!("--orbit 0: give at least one frame");
    }
    let mut session = crate::open(graph, frame)?;
    let camera = match camera {
        Some(c) => c.to_owned(),
        None => {
            let cameras: Vec<String> = session
                .graph
                .nodes()
                .filter(|n| n.kind == "Camera")
                .map(|n| n.id.clone())
                .collect();
            match cameras.as_slice() {
                [one] => one.clone(),
                _ => bail!(
                    "{}: --orbit turns the graph's camera; it has {} Camera nodes ({}): name one \
                     with --camera",
                    graph.display(),
                    cameras.len(),
                    cameras.join(", ")
                ),
            }
        }
    };
    let base = match session
        .graph
        .node(&camera)
        .and_then(|n| n.params.get("azimuth"))
    {
        Some(ParamValue::Float(a)) => *a,
        _ => bail!("--camera {camera}: not a Camera node of the graph"),
    };
    let bar = std::io::stderr()
        .is_terminal()
        .then(|| indicatif::ProgressBar::new(frames as u64));
    let mut pictures = Vec::with_capacity(frames);
    for i in 0..frames {
        let azimuth = (base + 360.0 * i as f64 / frames as f64 + 180.0).rem_euclid(360.0) - 180.0;
        session.set_param_text(&camera, "azimuth", &format!("{azimuth:?}"))?;
        pictures.push(session.render_picture(None, None)?);
        if let Some(bar) = &bar {
            bar.inc(1);
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    hatchery_batch::animation::write(output, &pictures, fps).map_err(anyhow::Error::msg)?;
    let (w, h) = session.ctx.size();
    println!(
        "wrote {} ({frames} frames at {fps} fps, {w}×{h}) in {:.2} s on {}",
        output.display(),
        start.elapsed().as_secs_f64(),
        session.ctx.gpu.describe()
    );
    Ok(())
}
