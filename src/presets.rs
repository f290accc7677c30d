//! `hatchery inputs` and `hatchery presets`: what a graph reads and which presets there are,
//! for people (a table) and for scripts (`--json`).

use anyhow::{Context, Result};
use hatchery_graph::Graph;
use serde_json::json;
use std::path::{Path, PathBuf};

/// One input as JSON: `name`, `type`, `doc`, `default` (the file the graph reads unless told
/// otherwise, resolved against the graph's folder), `to` (the `node.param`s it sets).
fn input_json(graph: &Graph, input: &hatchery_graph::GraphInput) -> serde_json::Value {
    json!({
        "name": input.name,
        "type": input.kind.name(),
        "doc": input.doc,
        "default": shown_path(&input.default_path(graph.base_dir())),
        "to": input.to.iter().map(|(n, p)| format!("{n}.{p}")).collect::<Vec<_>>(),
    })
}

/// A path as a user can paste it: absolute and without `..` when the file exists.
fn shown_path(path: &Path) -> String {
    std::fs::canonicalize(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

/// `hatchery inputs GRAPH`: the graph's inputs, one per line (or a JSON list).
pub fn inputs(path: &Path, as_json: bool) -> Result<String> {
    let registry = hatchery_nodes::registry();
    let graph = Graph::load_file(path, &registry)?;
    if as_json {
        let list: Vec<_> = graph
            .inputs()
            .iter()
            .map(|i| input_json(&graph, i))
            .collect();
        return Ok(serde_json::to_string_pretty(&list)? + "\n");
    }
    if graph.inputs().is_empty() {
        return Ok(format!(
            "{}: no inputs (the graph reads no data file, or declares none)\n",
            path.display()
        ));
    }
    let mut out = String::new();
    for i in graph.inputs() {
        out += &format!(
            "{}  ({})  {}\n    default: {}\n    sets: {}\n",
            i.name,
            i.kind,
            i.doc,
            shown_path(&i.default_path(graph.base_dir())),
            i.to.iter()
                .map(|(n, p)| format!("{n}.{p}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    out += &format!(
        "give one another file with: hatchery render {} --input NAME=PATH\n",
        path.display()
    );
    Ok(out)
}

/// Where the presets are: `graphs/` in the current folder, else the repository's.
pub fn default_dir() -> PathBuf {
    let here = PathBuf::from("graphs");
    if here.is_dir() {
        here
    } else {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/graphs"))
    }
}

/// Every `.ron` graph in `dir`, sorted by name.
pub fn preset_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot list presets in {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    Ok(files)
}

/// `hatchery presets`: each preset with its description and inputs (a preset that does not
/// load is listed with its error, so one broken file does not hide the others).
pub fn presets(dir: &Path, as_json: bool) -> Result<String> {
    let registry = hatchery_nodes::registry();
    let mut rows = Vec::new();
    let mut out = String::new();
    for path in preset_files(dir)? {
        let name = path
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        match Graph::load_file(&path, &registry) {
            Ok(graph) => {
                rows.push(json!({
                    "name": name,
                    "path": shown_path(&path),
                    "description": graph.description(),
                    "inputs": graph.inputs().iter().map(|i| input_json(&graph, i)).collect::<Vec<_>>(),
                }));
                let inputs: Vec<String> = graph
                    .inputs()
                    .iter()
                    .map(|i| format!("{} ({})", i.name, i.kind))
                    .collect();
                out += &format!(
                    "{name}\n    {}\n    inputs: {}\n",
                    if graph.description().is_empty() {
                        "(no description)"
                    } else {
                        graph.description()
                    },
                    if inputs.is_empty() {
                        "none (procedural)".to_owned()
                    } else {
                        inputs.join(", ")
                    }
                );
            }
            Err(e) => {
                rows.push(json!({"name": name, "path": shown_path(&path), "error": e.to_string()}));
                out += &format!("{name}\n    does not load: {}\n", e.first());
            }
        }
    }
    if as_json {
        return Ok(serde_json::to_string_pretty(&rows)? + "\n");
    }
    Ok(out)
}
