//! `hatchery`: render, validate, benchmark and document illustration graphs.

mod batch;
mod bench;
mod catalogue;
mod convert;
mod export_web;
mod info;
mod logging;
mod orbit;
mod presets;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};
use hatchery_graph::{Graph, GraphDocument, ParamKind, SchemaLookup};
use hatchery_nodes::{Session, export};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Parser)]
#[command(
    name = "hatchery",
    version,
    about = "Illustrative visualization as typed node graphs on the GPU"
)]
struct Cli {
    /// Log more (repeat for more detail); RUST_LOG overrides.
    #[arg(short, long, global = true, action = clap::ArgAction::Count)]
    verbose: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a graph: run its SaveImage nodes (and any --dump ports).
    Render {
        graph: PathBuf,
        /// Output file: a .png replaces the path of the graph's single SaveImage node, a .svg
        /// that of its single SaveSvg node; a single saver of the other kind writes the same
        /// name with its own extension.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        frame: FrameArgs,
        /// Write a port's data: `node.port=file.npy` (raw floats) or `=file.png` (a picture).
        #[arg(long, value_name = "NODE.PORT=PATH")]
        dump: Vec<String>,
        /// A turntable of N frames (the camera's azimuth a full turn) written to -o as an
        /// animation: .mp4 (H.264) or .webm (VP9) through ffmpeg, .gif, or .png (APNG).
        #[arg(long, value_name = "N")]
        orbit: Option<usize>,
        /// Frames per second of the --orbit animation.
        #[arg(long, default_value_t = 24.0)]
        fps: f64,
        /// The Camera node --orbit turns (default: the graph's only one).
        #[arg(long)]
        camera: Option<String>,
    },
    /// Load and validate a graph without running it.
    Validate { graph: PathBuf },
    /// List a graph's inputs: the data files it reads, with their type, doc and default.
    Inputs {
        graph: PathBuf,
        /// A JSON list of objects with `name`, `type`, `doc`, `default` and `to`.
        #[arg(long)]
        json: bool,
    },
    /// List the presets (graphs/) with their one-line description and inputs.
    Presets {
        /// The folder of presets (default: ./graphs, else the repository's).
        #[arg(long)]
        dir: Option<PathBuf>,
        #[arg(long)]
        json: bool,
    },
    /// List every node kind with its ports, parameters and docs.
    Nodes {
        /// Markdown, as committed in docs/nodes.md.
        #[arg(long)]
        markdown: bool,
    },
    /// Measure graphs frame by frame, side by side: per-node medians and frame-time ratios.
    Bench {
        /// One or more graphs, measured interleaved.
        #[arg(required = true)]
        graphs: Vec<PathBuf>,
        #[arg(long, default_value_t = 10)]
        frames: usize,
        /// Frame sizes (repeat for several).
        #[arg(long, value_parser = parse_size, default_value = "1024x768")]
        size: Vec<(u32, u32)>,
        /// What changes between frames: `full`, `orbit:CAMERA`, `vary:NODE.PARAM=a,b` (repeatable).
        #[arg(long, default_value = "full")]
        scenario: Vec<String>,
        /// Override a parameter in every graph that has the node: `node.param=value`, or in the
        /// N-th graph only: `N:node.param=value` (so one graph can be measured in two settings).
        #[arg(long, value_name = "NODE.PARAM=VALUE")]
        set: Vec<String>,
        /// Measure the N-th graph (1-based) with every node in a pass of its own: no fused
        /// image-space passes (repeatable; list a graph twice to compare).
        #[arg(long, value_name = "N")]
        unfused: Vec<usize>,
        /// Measure the N-th graph (1-based) as the editor runs it: fused passes write every
        /// member output something reads, so an edit re-runs only what is downstream of it
        /// (repeatable; list a graph twice to compare).
        #[arg(long, value_name = "N")]
        interactive: Vec<usize>,
        /// Measure the N-th graph (1-based) with its volumes bricked: the single-texture limit
        /// forced to 64 voxels per axis (HATCHERY_MAX_TEXTURE_3D; brick size and pool from the
        /// environment). Repeatable; list a graph twice to compare bricked with one texture.
        #[arg(long, value_name = "N")]
        bricked: Vec<usize>,
    },
    /// Describe a volume or mesh file: dims, spacing, the voxel → world affine (RAS+ mm),
    /// value range, voxel type and which header rule placed it.
    Info { file: PathBuf },
    /// Write a volume (any format `info` reads), and optionally a label map on its grid, as an
    /// OME-Zarr 0.5 multiscale image: a pyramid of 2×2×2 means in zstd chunks (docs/data.md).
    Convert(convert::Args),
    /// Render a batch job: a parameter sweep, camera path and data sets over one graph, this
    /// process's shard of it (docs/batch.md).
    Batch(batch::Args),
    /// Write a figure folder for the web: the graph rendered in the browser with WebGPU, turned
    /// and zoomed by the reader, with the graph's controls (docs/web.md).
    ExportWeb(export_web::Args),
    /// Rewrite a graph file in the canonical layout (what saving writes).
    Fmt {
        graph: PathBuf,
        /// Only check: exit non-zero if the file is not canonical.
        #[arg(long)]
        check: bool,
    },
}

#[derive(clap::Args)]
pub(crate) struct FrameArgs {
    /// Frame size in pixels.
    #[arg(long, default_value = "1024x768", value_parser = parse_size)]
    size: (u32, u32),
    /// Render the figure designed at --size at SCALE times its resolution: the frame is SCALE ×
    /// --size and every length in pixels (hatching cells, line widths, label sizes) is scaled
    /// alike, so e.g. `--scale 2` is the same figure for print.
    #[arg(long, default_value_t = 1.0, value_parser = parse_scale)]
    scale: f64,
    /// Override a parameter: `node.param=value` (paths relative to the current folder).
    #[arg(long, value_name = "NODE.PARAM=VALUE")]
    set: Vec<String>,
    /// Give a graph input another file: `name=path` (see `hatchery inputs GRAPH`; paths
    /// relative to the current folder).
    #[arg(long, value_name = "NAME=PATH")]
    input: Vec<String>,
}

fn parse_scale(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(s) if s.is_finite() && (1.0 / 64.0..=64.0).contains(&s) => Ok(s),
        _ => Err(format!(
            "`{text}` is not a scale between 1/64 and 64 (e.g. 2)"
        )),
    }
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("`{text}` is not a size like 1024x768"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=16384).contains(v))
    };
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!(
            "`{text}` is not a size like 1024x768 (1 to 16384 pixels per side)"
        )),
    }
}

/// Splits `node.name=value`.
fn split_assignment<'a>(text: &'a str, what: &str) -> Result<(&'a str, &'a str, &'a str)> {
    let (target, value) = text
        .split_once('=')
        .with_context(|| format!("`{text}`: expected {what}=VALUE"))?;
    let (node, name) = target
        .split_once('.')
        .with_context(|| format!("`{text}`: expected {what}=VALUE"))?;
    Ok((node.trim(), name.trim(), value))
}

/// Mesa's drivers print "XDG_RUNTIME_DIR is invalid" on stderr when it is unset (headless
/// machines, CI); give them a private folder so that a successful run prints no false errors.
fn ensure_runtime_dir() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some() {
        return;
    }
    let user = std::env::var("USER").unwrap_or_else(|_| "user".into());
    let dir = std::env::temp_dir().join(format!("hatchery-runtime-{user}"));
    if std::fs::create_dir_all(&dir).is_ok() {
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
        }
        // SAFETY: called first thing in main, before any other thread exists.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}

fn main() {
    ensure_runtime_dir();
    let cli = Cli::parse();
    logging::init(cli.verbose);

    if let Err(error) = run(cli) {
        // One line: the chain of causes joined, leaving out a cause whose text is already there
        // (the library's errors name their source in their own message).
        let mut message = String::new();
        for cause in error.chain().map(|c| c.to_string()) {
            if message.is_empty() {
                message = cause;
            } else if !message.ends_with(&cause) {
                message = format!("{message}: {cause}");
            }
        }
        eprintln!("error: {}", message.replace('\n', " "));
        std::process::exit(1);
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render {
            graph,
            output,
            frame,
            dump,
            orbit: Some(frames),
            fps,
            camera,
        } => {
            if !dump.is_empty() {
                bail!("--orbit writes an animation; render --dump separately");
            }
            orbit::render(
                &graph,
                output.as_deref(),
                &frame,
                frames,
                fps,
                camera.as_deref(),
            )
        }
        Command::Render {
            graph,
            output,
            frame,
            dump,
            orbit: None,
            ..
        } => render(&graph, output.as_deref(), &frame, &dump),
        Command::ExportWeb(args) => export_web::run(&args),
        Command::Validate { graph } => {
            let registry = hatchery_nodes::registry();
            let g = Graph::load_file(&graph, &registry)?;
            println!("{}: valid ({} nodes)", graph.display(), g.nodes().count());
            Ok(())
        }
        Command::Inputs { graph, json } => {
            print!("{}", presets::inputs(&graph, json)?);
            Ok(())
        }
        Command::Presets { dir, json } => {
            let dir = dir.unwrap_or_else(presets::default_dir);
            print!("{}", presets::presets(&dir, json)?);
            Ok(())
        }
        Command::Nodes { markdown } => {
            let registry = hatchery_nodes::registry();
            print!(
                "{}",
                if markdown {
                    catalogue::markdown(&registry)
                } else {
                    catalogue::text(&registry)
                }
            );
            Ok(())
        }
        Command::Bench {
            graphs,
            frames,
            size,
            scenario,
            set,
            unfused,
            interactive,
            bricked,
        } => {
            let scenarios = scenario
                .iter()
                .map(|s| bench::Scenario::parse(s))
                .collect::<Result<Vec<_>>>()?;
            let mut sessions = Vec::new();
            for graph in &graphs {
                let mut session = open(
                    graph,
                    &FrameArgs {
                        size: size[0],
                        scale: 1.0,
                        set: Vec::new(),
                        input: Vec::new(),
                    },
                )?;
                // Each override applies to the graphs that have its node.
                for assignment in &set {
                    // `N:node.param=value` applies to the N-th graph only (1-based).
                    let (only, assignment) = match assignment.split_once(':') {
                        Some((n, rest))
                            if n.chars().all(|c| c.is_ascii_digit()) && !n.is_empty() =>
                        {
                            (n.parse::<usize>().ok(), rest)
                        }
                        _ => (None, assignment.as_str()),
                    };
                    if only.is_some_and(|n| n != sessions.len() + 1) {
                        continue;
                    }
                    let (node, param, value) = split_assignment(assignment, "NODE.PARAM")?;
                    if session.graph.node(node).is_some() {
                        let value = resolve_cli_path(&session, node, param, value);
                        session.set_param_text(node, param, &value)?;
                    }
                }
                if unfused.contains(&(sessions.len() + 1)) {
                    session.executor.set_fusion(false);
                }
                if interactive.contains(&(sessions.len() + 1)) {
                    session.executor.set_keep_fused(true);
                }
                if bricked.contains(&(sessions.len() + 1)) {
                    let mut limits = session.ctx.gpu.volume_limits()?;
                    limits.max_texture_3d = Some(limits.max_texture_3d.map_or(64, |m| m.min(64)));
                    session.ctx.gpu.set_volume_limits(limits);
                }
                sessions.push(session);
            }
            for (flag, list) in [
                ("--unfused", &unfused),
                ("--interactive", &interactive),
                ("--bricked", &bricked),
            ] {
                if let Some(n) = list.iter().find(|&&n| n == 0 || n > graphs.len()) {
                    bail!(
                        "{flag} {n}: there are {} graphs (counted from 1)",
                        graphs.len()
                    );
                }
            }
            bench::run(&graphs, &mut sessions, &scenarios, &size, frames.max(1))
        }
        Command::Convert(args) => convert::command(args),
        Command::Batch(args) => {
            let code = batch::command(args)?;
            if code != 0 {
                std::process::exit(code);
            }
            Ok(())
        }
        Command::Info { file } => {
            print!("{}", info::describe(&file)?);
            Ok(())
        }
        Command::Fmt { graph, check } => {
            let (doc, _) = GraphDocument::load(&graph)?;
            let text = std::fs::read_to_string(&graph)?;
            let canonical = doc.to_ron_string();
            if check {
                if canonical != text {
                    bail!(
                        "{}: not in canonical layout (run `hatchery fmt {}`)",
                        graph.display(),
                        graph.display()
                    );
                }
            } else if canonical != text {
                doc.save(&graph)
                    .with_context(|| format!("cannot write {}", graph.display()))?;
                println!("{}: rewritten", graph.display());
            }
            Ok(())
        }
    }
}

/// Opens a session and applies `--set` overrides.
pub(crate) fn open(graph: &Path, frame: &FrameArgs) -> Result<Session> {
    let scaled = |side: u32| (side as f64 * frame.scale).round() as u32;
    let (width, height) = (scaled(frame.size.0), scaled(frame.size.1));
    if !(1..=16384).contains(&width) || !(1..=16384).contains(&height) {
        bail!(
            "--size {}x{} at --scale {} is {width}x{height}: 1 to 16384 pixels per side",
            frame.size.0,
            frame.size.1,
            frame.scale
        );
    }
    let mut session = Session::open(graph, width, height)?;
    session.ctx.set_pixel_scale(frame.scale);
    for assignment in &frame.input {
        let (name, path) = assignment
            .split_once('=')
            .with_context(|| format!("--input `{assignment}`: expected NAME=PATH"))?;
        let path = std::path::absolute(path.trim())
            .with_context(|| format!("--input `{assignment}`: not a usable path"))?;
        session.set_input(name.trim(), &path)?;
    }
    for assignment in &frame.set {
        let (node, param, value) = split_assignment(assignment, "NODE.PARAM")?;
        let value = resolve_cli_path(&session, node, param, value);
        session.set_param_text(node, param, &value)?;
    }
    Ok(session)
}

/// Paths typed on the command line are relative to the current folder, not the graph's.
fn resolve_cli_path(session: &Session, node: &str, param: &str, value: &str) -> String {
    let is_path = session
        .graph
        .node(node)
        .and_then(|n| n.schema(&session.registry))
        .and_then(|s| s.param(param))
        .is_some_and(|p| p.kind == ParamKind::Path);
    match std::path::absolute(value) {
        Ok(abs) if is_path && !value.is_empty() => abs.to_string_lossy().into_owned(),
        _ => value.to_owned(),
    }
}

fn render(graph: &Path, output: Option<&Path>, frame: &FrameArgs, dumps: &[String]) -> Result<()> {
    let start = Instant::now();
    let mut session = open(graph, frame)?;
    let sinks: Vec<String> = session
        .graph
        .nodes()
        .filter(|n| session.registry.schema(&n.kind).is_some_and(|s| s.sink))
        .map(|n| n.id.clone())
        .collect();
    if let Some(output) = output {
        let svg = output
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let kind = if svg { "SaveSvg" } else { "SaveImage" };
        let savers: Vec<&String> = sinks
            .iter()
            .filter(|id| session.graph.node(id).is_some_and(|n| n.kind == kind))
            .collect();
        match savers.as_slice() {
            [one] => {
                let one = (*one).clone();
                let abs = std::path::absolute(output)?;
                session.set_param_text(&one, "path", &abs.to_string_lossy())?;
                // The figure's other format (a graph with one SaveImage and one SaveSvg) goes
                // next to it: -o figure.png also writes figure.svg, and the other way round.
                let (other, extension) = if svg {
                    ("SaveImage", "png")
                } else {
                    ("SaveSvg", "svg")
                };
                let others: Vec<String> = sinks
                    .iter()
                    .filter(|id| session.graph.node(id).is_some_and(|n| n.kind == other))
                    .cloned()
                    .collect();
                if let [single] = others.as_slice() {
                    let path = abs.with_extension(extension);
                    session.set_param_text(single, "path", &path.to_string_lossy())?;
                }
            }
            [] => bail!(
                "{}: -o {} needs a {kind} node in the graph (or use --dump NODE.PORT=FILE)",
                graph.display(),
                output.display()
            ),
            many => bail!(
                "{}: -o is ambiguous with {} {kind} nodes ({}); set each with --set NODE.path=FILE",
                graph.display(),
                many.len(),
                many.iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
    let mut requests = Vec::new();
    for dump in dumps {
        let (node, port, path) = split_assignment(dump, "NODE.PORT")?;
        // Check the port exists before running anything.
        let instance = session
            .graph
            .node(node)
            .with_context(|| format!("--dump {dump}: no node `{node}` in the graph"))?;
        let kind = &instance.kind;
        let schema = instance.schema(&session.registry).expect("validated kind");
        if schema.output_index(port).is_none() {
            bail!(
                "--dump {dump}: node `{node}` ({kind}) has no output port `{port}` (its outputs are: {})",
                schema.output_names().join(", ")
            );
        }
        requests.push((node.to_owned(), port.to_owned(), PathBuf::from(path)));
    }
    let mut targets: Vec<&str> = sinks.iter().map(String::as_str).collect();
    targets.extend(requests.iter().map(|(n, _, _)| n.as_str()));
    if targets.is_empty() {
        bail!(
            "{}: nothing to render: the graph has no SaveImage or SaveSvg node and no --dump was given",
            graph.display()
        );
    }
    if let Err(e) = session.run(&targets) {
        // A node that reads a graph input names it, so a bad file given with --input says so.
        if let hatchery_nodes::SessionError::Exec(exec) = &e
            && let Some(input) = session.input_of(&exec.node)
        {
            bail!("input `{}`: {e}", input.name);
        }
        return Err(e.into());
    }
    for (node, port, path) in &requests {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        let what = format!("--dump {node}.{port}={}", path.display());
        match ext.as_str() {
            "npy" => {
                let value = session.output(node, port)?;
                let array = export::to_array(value, &session.ctx.gpu)
                    .map_err(|e| anyhow::anyhow!("{what}: {e}"))?;
                export::write_npy(path, &array)
                    .with_context(|| format!("{what}: cannot write the file"))?;
            }
            // The editor's File → Export image writes through the same function.
            "png" => session
                .export_png(node, port, path)
                .map_err(|e| anyhow::anyhow!("{what}: {e}"))?,
            // A camera for other renderers (benches/peers): eye, target, up, field of view.
            "json" => match session.output(node, port)? {
                hatchery_nodes::Value::Camera(camera) => {
                    hatchery_graph::atomic::write_bytes_atomically(
                        path,
                        camera.to_json().as_bytes(),
                    )
                    .with_context(|| format!("{what}: cannot write the file"))?
                }
                other => bail!(
                    "{what}: .json is written for cameras; this is a {} (use .npy or .png)",
                    other.port_type()
                ),
            },
            _ => bail!(
                "{what}: the file must end in .npy (raw data), .png (a picture) or .json (a camera)"
            ),
        }
        println!("dumped {node}.{port} to {}", path.display());
    }
    for sink in &sinks {
        if let Some(node) = session
            .graph
            .node(sink)
            .filter(|n| n.kind == "SaveImage" || n.kind == "SaveSvg")
        {
            println!("wrote {}", node.params.path("path").display());
        }
    }
    let (w, h) = session.ctx.size();
    println!(
        "rendered {} at {w}×{h} in {:.2} s on {}",
        graph.display(),
        start.elapsed().as_secs_f64(),
        session.ctx.gpu.describe()
    );
    Ok(())
}
