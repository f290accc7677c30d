//! hatchery as a library: open a saved graph, change a parameter, run it and read a port —
//! the steps the Python package mirrors (`hatchery.Graph(...)`, `g.set(...)`, `g.array(...)`).
//!
//! ```text
//! cargo run --release --example session -- [graph.ron] [node.port] [out.png]
//! ```
//!
//! Defaults: `graphs/shaded_surface.ron` (a procedural torus, no data files needed), its
//! `shaded.image` port, `session.png`. Each kind of failure is its own `SessionError` variant,
//! so a caller can tell a bad graph from a missing input file or a GPU fault.

use hatchery_nodes::{Session, SessionError, export};
use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let graph = args.first().map_or("graphs/shaded_surface.ron", |s| s);
    let port = args.get(1).map_or("shaded.image", |s| s);
    let out = args.get(2).map_or("session.png", |s| s);
    match run(Path::new(graph), port, Path::new(out)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let what = match &e {
                SessionError::Graph(_) => "the graph is invalid",
                SessionError::Input(_) | SessionError::Io { .. } => "a file could not be used",
                SessionError::Param { .. } => "a parameter was refused",
                SessionError::Gpu(_) => "the GPU failed",
                SessionError::NotFound(_) => "no such node or port",
                _ => "the render failed",
            };
            eprintln!("{what}: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(graph: &Path, port: &str, out: &Path) -> Result<(), SessionError> {
    // Loads, validates (every edge type-checked) and opens the GPU: 320×240 pixels.
    let mut session = Session::open(graph, 320, 240)?;
    eprintln!("adapter: {}", session.ctx.gpu.describe());

    // Parameters are set as `hatchery render --set node.param=value` writes them; the
    // value is checked against the parameter's type and range.
    if session.graph.node("camera").is_some() {
        session.set_param_text("camera", "azimuth", "60")?;
    }

    // Runs only what `node.port` needs and returns its value (a GPU texture, a mesh, …).
    let (node, port) = port
        .split_once('.')
        .ok_or_else(|| SessionError::NotFound(format!("`{port}` is not node.port")))?;
    let value = session.evaluate(node, port)?;

    // Read back as a float array (what numpy receives), shape [height, width, channels].
    let array =
        export::to_array(&value, &session.ctx.gpu).map_err(|source| SessionError::Export {
            port: format!("{node}.{port}"),
            source,
        })?;
    let mean = array.data.iter().sum::<f32>() / array.data.len().max(1) as f32;
    println!("{node}.{port}: shape {:?}, mean {mean:.4}", array.shape);

    // The same port as a PNG, written atomically (the old file or the new one, never half).
    session.export_png(node, port, out)?;
    println!("wrote {}", out.display());
    Ok(())
}
