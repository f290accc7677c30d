//! `hatchery export-web GRAPH -o DIR`: a figure folder any static web server can host
//! (docs/web.md). The page renders the graph with WebGPU through the browser build
//! (crates/hatchery-web): the reader turns and zooms it and changes the graph's controls; a
//! browser without WebGPU shows the poster, the native render of the same graph and size.
//!
//! The folder: index.html, hatchery_web.js and hatchery_web_bg.wasm (the browser build, from
//! scripts/build-web.sh), figure.ron (the graph, its data paths pointing into data/),
//! figure.json (what the page fetches), poster.png, and data/ with the files the graph reads.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use hatchery_graph::ParamKind;
use hatchery_nodes::Session;

use crate::FrameArgs;

/// The page; `{{TITLE}}`, `{{WIDTH}}` and `{{HEIGHT}}` are filled in.
const PAGE: &str = include_str!("../crates/hatchery-web/page/index.html");
/// The browser build's two files, as wasm-bindgen writes them.
const WEB_FILES: [&str; 2] = ["hatchery_web.js", "hatchery_web_bg.wasm"];
/// Savers' paths are where a native render writes; the page runs none of them.
const WRITERS: [&str; 2] = ["SaveImage", "SaveSvg"];

#[derive(clap::Args)]
pub struct Args {
    /// The graph to export.
    graph: PathBuf,
    /// The folder to write (created; files of an earlier export in it are replaced).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    frame: FrameArgs,
    /// The browser build's folder (hatchery_web.js and hatchery_web_bg.wasm). Default:
    /// $HATCHERY_WEB_PKG, else target/web-pkg next to this program (scripts/build-web.sh
    /// writes it there).
    #[arg(long, value_name = "DIR")]
    web_pkg: Option<PathBuf>,
}

pub fn run(args: &Args) -> Result<()> {
    let pkg = web_pkg(args.web_pkg.as_deref())?;
    let mut session = crate::open(&args.graph, &args.frame)?;
    let (width, height) = session.ctx.size();
    let out = &args.output;
    // Refuse what the page cannot read before writing anything.
    let reads = data_reads(&session)?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;

    // The poster first, from the graph as the user's paths have it.
    let poster = session
        .render_picture(None, None)
        .context("rendering the poster")?;
    poster
        .save(out.join("poster.png"))
        .with_context(|| format!("cannot write {}", out.join("poster.png").display()))?;

    let (files, moved) = copy_data(reads, out)?;
    let mut doc = session.document();
    doc.base_dir = None;
    // The copies' paths are written into the document, not set on the graph: a CustomShader's
    // file decides its ports, so the graph refuses to change it while open.
    for ((node, param), path) in moved {
        if let Some(n) = doc.nodes.iter_mut().find(|n| n.id == node) {
            n.params.insert(param, ron::Value::String(path));
        }
    }
    write(out, "figure.ron", &doc.to_ron_string())?;
    let manifest = serde_json::json!({
        "graph": "figure.ron",
        "width": width,
        "height": height,
        "scale": args.frame.scale,
        "files": files,
    });
    write(
        out,
        "figure.json",
        &serde_json::to_string_pretty(&manifest)?,
    )?;
    let title = match session.graph.description() {
        "" => args
            .graph
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default(),
        d => d.to_owned(),
    };
    let page = PAGE
        .replace("{{TITLE}}", &html_escape(&title))
        .replace("{{WIDTH}}", &width.to_string())
        .replace("{{HEIGHT}}", &height.to_string());
    write(out, "index.html", &page)?;
    let mut wasm_bytes = 0;
    for name in WEB_FILES {
        let bytes = std::fs::copy(pkg.join(name), out.join(name))
            .with_context(|| format!("cannot copy {} into {}", name, out.display()))?;
        if name.ends_with(".wasm") {
            wasm_bytes = bytes;
        }
    }
    eprintln!(
        "wrote {} ({width}×{height}, {} data file{}, wasm {:.1} MB); host it on any static web \
         server, e.g. `python3 -m http.server -d {}`",
        out.display(),
        files.len(),
        if files.len() == 1 { "" } else { "s" },
        wasm_bytes as f64 / 1e6,
        out.display()
    );
    Ok(())
}

/// Where the browser build is; errors say how to make it.
fn web_pkg(given: Option<&Path>) -> Result<PathBuf> {
    let candidates: Vec<PathBuf> = match given {
        Some(dir) => vec![dir.to_path_buf()],
        None => std::env::var_os("HATCHERY_WEB_PKG")
            .map(PathBuf::from)
            .into_iter()
            .chain(
                std::env::current_exe()
                    .ok()
                    .and_then(|exe| Some(exe.parent()?.parent()?.join("web-pkg"))),
            )
            .collect(),
    };
    for dir in &candidates {
        if WEB_FILES.iter().all(|f| dir.join(f).is_file()) {
            return Ok(dir.clone());
        }
    }
    bail!(
        "the browser build is missing (looked in {}): run scripts/build-web.sh, which writes \
         target/web-pkg, or give --web-pkg DIR",
        candidates
            .iter()
            .map(|d| d.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// A file a node reads: (node, parameter, path as resolved).
type Read = (String, String, PathBuf);

/// The files the graph reads (its non-empty path parameters, savers' excepted). Errors: a
/// folder (DICOM series, TIFF stack, OME-Zarr), which the browser build does not read, or a
/// missing file, naming the node.
fn data_reads(session: &Session) -> Result<Vec<Read>> {
    let mut reads: Vec<Read> = Vec::new();
    for node in session.graph.nodes() {
        if WRITERS.contains(&node.kind.as_str()) {
            continue;
        }
        let Some(schema) = node.schema(&session.registry) else {
            continue;
        };
        for spec in schema.params.iter().filter(|p| p.kind == ParamKind::Path) {
            let path = node.params.path(spec.name);
            if !path.as_os_str().is_empty() {
                reads.push((node.id.clone(), spec.name.to_owned(), path));
            }
        }
    }
    for (node, param, path) in &reads {
        if path.is_dir() {
            bail!(
                "node `{node}` reads the folder {} ({param}); the browser build reads single \
                 files only: convert it to NIfTI or NRRD first",
                path.display()
            );
        }
        if !path.is_file() {
            bail!("node `{node}`: {param} {} is not a file", path.display());
        }
    }
    Ok(reads)
}

/// Each (node, parameter) reading a file, and the path of its copy in the folder.
type Moved = Vec<((String, String), String)>;

/// Copies the files the graph reads into `out/data/N/` (one folder per file, with the files it
/// names beside it). Returns the copied paths relative to `out`, and where each read moved.
fn copy_data(reads: Vec<Read>, out: &Path) -> Result<(Vec<String>, Moved)> {
    let mut moved = Moved::new();
    let mut copied: BTreeMap<PathBuf, String> = BTreeMap::new();
    let mut files = Vec::new();
    for (node, param, path) in reads {
        let source = std::fs::canonicalize(&path)
            .with_context(|| format!("node `{node}`: cannot read {}", path.display()))?;
        let target = match copied.get(&source) {
            Some(target) => target.clone(),
            None => {
                let folder = format!("data/{}", copied.len() + 1);
                let mut names = vec![file_name(&source)?];
                names.extend(companions(&source));
                for name in &names {
                    let from = source.parent().unwrap_or(Path::new("")).join(name);
                    let to = out.join(&folder).join(name);
                    if let Some(parent) = to.parent() {
                        std::fs::create_dir_all(parent)?;
                    }
                    std::fs::copy(&from, &to).with_context(|| {
                        format!("node `{node}`: cannot copy {}", from.display())
                    })?;
                    files.push(format!("{folder}/{name}"));
                }
                let target = format!("{folder}/{}", names[0]);
                copied.insert(source, target.clone());
                target
            }
        };
        moved.push(((node, param), target));
    }
    Ok((files, moved))
}

fn file_name(path: &Path) -> Result<String> {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .with_context(|| format!("{} names no file", path.display()))
}

/// The files a data file names beside it: a MetaImage header's `ElementDataFile`, a detached
/// NRRD header's `data file`, an Analyze/NIfTI pair's `.img`, an OBJ's material libraries. Only
/// names within the file's folder (no `..`); what is missing is left to the loader to report.
fn companions(path: &Path) -> Vec<String> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let text = || std::fs::read(path).map(|b| String::from_utf8_lossy(&b).into_owned());
    let value_after = |line: &str, keys: &[&str], sep: char| {
        let (key, value) = line.split_once(sep)?;
        keys.iter()
            .any(|k| key.trim().eq_ignore_ascii_case(k))
            .then(|| value.trim().to_owned())
    };
    let mut names: Vec<String> = match ext.as_str() {
        "mhd" => text()
            .map(|t| {
                t.lines()
                    .filter_map(|l| value_after(l, &["ElementDataFile"], '='))
                    .filter(|v| !v.eq_ignore_ascii_case("LOCAL"))
                    .collect()
            })
            .unwrap_or_default(),
        "nhdr" => text()
            .map(|t| {
                t.lines()
                    .filter_map(|l| value_after(l, &["data file", "datafile"], ':'))
                    .collect()
            })
            .unwrap_or_default(),
        "hdr" => vec![
            path.with_extension("img")
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
        ],
        "obj" => text()
            .map(|t| {
                t.lines()
                    .filter_map(|l| l.trim().strip_prefix("mtllib "))
                    .map(|v| v.trim().to_owned())
                    .collect()
            })
            .unwrap_or_default(),
        _ => Vec::new(),
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    names.retain(|n| {
        !n.is_empty()
            && Path::new(n).is_relative()
            && !Path::new(n)
                .components()
                .any(|c| matches!(c, std::path::Component::ParentDir))
            && folder.join(n).is_file()
    });
    names
}

fn write(out: &Path, name: &str, text: &str) -> Result<()> {
    let path = out.join(name);
    std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))
}

fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
