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
    /// The folder to write (created; an earlier export in it is replaced, its data/ too).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    frame: FrameArgs,
    /// The browser build's folder (hatchery_web.js and hatchery_web_bg.wasm). Default:
    /// $HATCHERY_WEB_PKG, else target/web-pkg next to this program (scripts/build-web.sh
    /// writes it there).
    #[arg(long, value_name = "DIR")]
    web_pkg: Option<PathBuf>,
    /// The page's title and the poster's alternative text. Default: the graph's description,
    /// else its file name.
    #[arg(long)]
    title: Option<String>,
}

pub fn run(args: &Args) -> Result<()> {
    let pkg = web_pkg(args.web_pkg.as_deref())?;
    let mut session = crate::open(&args.graph, &args.frame)?;
    let (width, height) = session.ctx.size();
    let out = &args.output;
    // Everything that can be refused is refused before anything is written: data the page
    // cannot read, files it names that cannot travel with it, a graph that does not render.
    let plan = plan_data(data_reads(&session)?)?;
    let poster = session
        .render_picture(None, None)
        .context("rendering the poster")?;
    refuse_foreign_data(out)?;
    let files = plan.files();
    let mut doc = session.document();
    doc.base_dir = None;
    // The copies' paths are written into the document, not set on the graph: a CustomShader's
    // file decides its ports, so the graph refuses to change it while open.
    for (node, param, entry, path) in &plan.moved {
        let Some(n) = doc.nodes.iter_mut().find(|n| &n.id == node) else {
            continue;
        };
        let value = match entry {
            // A StyleSet's entry: its name replaced within the text.
            Some(entry) => match n.params.get(param) {
                Some(ron::Value::String(text)) => text.replace(entry, path),
                _ => continue,
            },
            None => path.clone(),
        };
        n.params.insert(param.clone(), ron::Value::String(value));
    }
    let manifest = serde_json::json!({
        "graph": "figure.ron",
        "width": width,
        "height": height,
        "scale": args.frame.scale,
        "files": files,
    });
    let title = match args.title.as_deref().unwrap_or(session.graph.description()) {
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

    // Everything is written into a new folder beside the figure's files first, then moved in:
    // a failure leaves an earlier figure as it was.
    let created = !out.exists();
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let staging = out.join(".export-new");
    let written = (|| -> Result<u64> {
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot remove {}", staging.display()))?;
        }
        std::fs::create_dir_all(&staging)
            .with_context(|| format!("cannot create {}", staging.display()))?;
        copy_data(&plan, &staging)?;
        poster
            .save(staging.join("poster.png"))
            .with_context(|| format!("cannot write {}", staging.join("poster.png").display()))?;
        write(&staging, "figure.ron", &doc.to_ron_string())?;
        write(
            &staging,
            "figure.json",
            &serde_json::to_string_pretty(&manifest)?,
        )?;
        write(&staging, "index.html", &page)?;
        let mut wasm_bytes = 0;
        for name in WEB_FILES {
            let bytes = std::fs::copy(pkg.join(name), staging.join(name))
                .with_context(|| format!("cannot copy {} into {}", name, staging.display()))?;
            if name.ends_with(".wasm") {
                wasm_bytes = bytes;
            }
        }
        move_in(&staging, out)?;
        Ok(wasm_bytes)
    })();
    let wasm_bytes = match written {
        Ok(bytes) => bytes,
        Err(e) => {
            let _ = std::fs::remove_dir_all(if created { out } else { &staging });
            return Err(e);
        }
    };
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

/// A file a node reads.
struct Read {
    node: String,
    param: String,
    /// As the graph resolves it (relative to its folder).
    path: PathBuf,
    /// For a file named inside a text parameter (a StyleSet's lit-sphere images): the entry
    /// as written there, which the copy's path replaces.
    entry: Option<String>,
}

/// The files the graph reads: its non-empty path parameters (savers' excepted) and the images
/// a StyleSet names. Errors, naming the node: a folder or a file whose format the browser build
/// reads as a folder (a DICOM series, OME-Zarr), or a missing file.
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
                reads.push(Read {
                    node: node.id.clone(),
                    param: spec.name.to_owned(),
                    path,
                    entry: None,
                });
            }
        }
        if node.kind == "StyleSet" {
            for entry in hatchery_nodes::style_set::split_entries(node.params.text("styles")) {
                let lower = entry.to_ascii_lowercase();
                if [".png", ".jpg", ".jpeg"].iter().any(|e| lower.ends_with(e)) {
                    let path = match node.params.base_dir() {
                        Some(base) if Path::new(&entry).is_relative() => base.join(&entry),
                        _ => PathBuf::from(&entry),
                    };
                    reads.push(Read {
                        node: node.id.clone(),
                        param: "styles".into(),
                        path,
                        entry: Some(entry),
                    });
                }
            }
        }
    }
    for Read {
        node, param, path, ..
    } in &reads
    {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        if path.is_dir() {
            bail!(
                "node `{node}` reads the folder {} ({param}); the browser build reads single \
                 files only: convert it to NIfTI or NRRD first",
                path.display()
            );
        }
        if name.ends_with(".dcm") || ["zarr.json", ".zattrs", ".zgroup"].contains(&name.as_str()) {
            bail!(
                "node `{node}` reads {} ({param}), which means its whole folder (a DICOM series, \
                 an OME-Zarr image); the browser build reads single files only: convert it to \
                 NIfTI or NRRD first",
                path.display()
            );
        }
        if !path.is_file() {
            bail!("node `{node}`: {param} {} is not a file", path.display());
        }
    }
    Ok(reads)
}

/// Each read's node and parameter, the entry it replaces (if any) and its copy's path.
type Moved = Vec<(String, String, Option<String>, String)>;

/// What the folder's data/ will hold: each file the graph reads in `data/N/` (one folder per
/// file, with the files it names beside it).
struct DataPlan {
    /// Source, and the copy's path relative to the folder.
    copies: Vec<(PathBuf, String)>,
    moved: Moved,
}

impl DataPlan {
    /// The copies' paths relative to the folder, for the page to fetch.
    fn files(&self) -> Vec<String> {
        self.copies.iter().map(|(_, to)| to.clone()).collect()
    }
}

/// Plans the copies of the files the graph reads, reading only headers. Errors: an unreadable
/// file, a file it names that cannot travel with it (see [`companions`]).
fn plan_data(reads: Vec<Read>) -> Result<DataPlan> {
    let mut plan = DataPlan {
        copies: Vec::new(),
        moved: Moved::new(),
    };
    // By the file's canonical path, so that a file read twice is copied once; names and
    // companions come from the path as given (a symlinked data store's target is a hash).
    let mut planned: BTreeMap<PathBuf, String> = BTreeMap::new();
    for read in reads {
        let Read {
            node, param, path, ..
        } = &read;
        let key = std::fs::canonicalize(path)
            .with_context(|| format!("node `{node}`: cannot read {}", path.display()))?;
        let target = match planned.get(&key) {
            Some(target) => target.clone(),
            None => {
                let folder = format!("data/{}", planned.len() + 1);
                let mut names = vec![file_name(path)?];
                names.extend(
                    companions(path)
                        .with_context(|| format!("node `{node}` ({param}): {}", path.display()))?,
                );
                for name in &names {
                    let from = path.parent().unwrap_or(Path::new("")).join(name);
                    plan.copies.push((from, format!("{folder}/{name}")));
                }
                let target = format!("{folder}/{}", names[0]);
                planned.insert(key, target.clone());
                target
            }
        };
        plan.moved.push((read.node, read.param, read.entry, target));
    }
    Ok(plan)
}

/// Copies the planned files into `dir/data/N/`. Errors: an unreadable source, an unwritable
/// folder.
fn copy_data(plan: &DataPlan, dir: &Path) -> Result<()> {
    for (from, to) in &plan.copies {
        let to = dir.join(to);
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create {}", parent.display()))?;
        }
        std::fs::copy(from, &to).with_context(|| format!("cannot copy {}", from.display()))?;
    }
    Ok(())
}

/// The files an export writes beside data/.
const FIGURE_FILES: [&str; 6] = [
    "poster.png",
    "figure.ron",
    "figure.json",
    "index.html",
    WEB_FILES[0],
    WEB_FILES[1],
];

/// Moves a written figure from `staging` into `out`, replacing an earlier export's files and
/// its data/ (whose files may be the sources just copied: a figure re-exported in place). The
/// earlier data/ is moved aside first and back if the new one cannot take its place.
fn move_in(staging: &Path, out: &Path) -> Result<()> {
    let (data, aside) = (out.join("data"), out.join(".data-old"));
    if aside.exists() {
        std::fs::remove_dir_all(&aside)
            .with_context(|| format!("cannot remove {}", aside.display()))?;
    }
    if data.exists() {
        std::fs::rename(&data, &aside)
            .with_context(|| format!("cannot move {} aside", data.display()))?;
    }
    let new_data = staging.join("data");
    if new_data.exists()
        && let Err(e) = std::fs::rename(&new_data, &data)
    {
        let _ = std::fs::rename(&aside, &data);
        return Err(e).with_context(|| format!("cannot move {}", new_data.display()));
    }
    for name in FIGURE_FILES {
        std::fs::rename(staging.join(name), out.join(name))
            .with_context(|| format!("cannot move {name} into {}", out.display()))?;
    }
    let _ = std::fs::remove_dir_all(&aside);
    let _ = std::fs::remove_dir(staging);
    Ok(())
}

/// Refuses a folder whose data/ an export did not write: one beside a figure.json manifest
/// that lists every file in it. Errors name the folder and, where there is one, a file the
/// manifest does not list.
fn refuse_foreign_data(out: &Path) -> Result<()> {
    let data = out.join("data");
    let Ok(meta) = std::fs::symlink_metadata(&data) else {
        return Ok(());
    };
    let listed: Option<Vec<String>> = std::fs::read_to_string(out.join("figure.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .filter(|m| m["graph"] == "figure.ron")
        .and_then(|m| serde_json::from_value(m["files"].clone()).ok());
    let (Some(listed), true) = (listed, meta.is_dir()) else {
        bail!(
            "{} exists and is not an earlier export's (no figure.json manifest of one beside \
             it): choose another folder",
            data.display()
        );
    };
    let mut folders = vec![data.clone()];
    while let Some(folder) = folders.pop() {
        let entries = std::fs::read_dir(&folder)
            .with_context(|| format!("cannot read {}", folder.display()))?;
        for entry in entries {
            let path = entry?.path();
            if path.is_dir() && !path.is_symlink() {
                folders.push(path);
                continue;
            }
            let relative = path.strip_prefix(out).unwrap_or(&path);
            let name = relative.to_string_lossy().replace('\\', "/");
            if !listed.contains(&name) {
                bail!(
                    "{} holds {name}, which the export beside it did not write: choose another \
                     folder",
                    data.display()
                );
            }
        }
    }
    Ok(())
}

fn file_name(path: &Path) -> Result<String> {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .with_context(|| format!("{} names no file", path.display()))
}

/// The files a data file names beside it: a MetaImage header's `ElementDataFile`, an NRRD
/// header's `data file`, an OBJ's material libraries. Errors: a name the copy could not keep
/// beside it (absolute, through `..`), a file list or pattern, a missing file — the page would
/// not find it.
fn companions(path: &Path) -> Result<Vec<String>> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    // Headers are text up to the data; their first 1 MiB is enough.
    let text = || -> Result<String> {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(std::fs::File::open(path)?, 1 << 20),
            &mut bytes,
        )?;
        Ok(String::from_utf8_lossy(&bytes).into_owned())
    };
    let value_after = |line: &str, keys: &[&str], sep: char| {
        let (key, value) = line.split_once(sep)?;
        keys.iter()
            .any(|k| key.trim().eq_ignore_ascii_case(k))
            .then(|| value.trim().to_owned())
    };
    let names: Vec<String> = match ext.as_str() {
        "mhd" | "mha" => text()?
            .lines()
            .filter_map(|l| value_after(l, &["ElementDataFile"], '='))
            .filter(|v| !v.eq_ignore_ascii_case("LOCAL"))
            .collect(),
        // The header ends at its first empty line (attached data follows).
        "nhdr" | "nrrd" => text()?
            .lines()
            .take_while(|l| !l.trim().is_empty())
            .filter_map(|l| value_after(l, &["data file", "datafile"], ':'))
            .collect(),
        "obj" => text()?
            .lines()
            .filter_map(|l| l.trim().strip_prefix("mtllib "))
            .map(|v| v.trim().to_owned())
            .collect(),
        _ => Vec::new(),
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    for name in &names {
        let p = Path::new(name);
        let travels = !name.is_empty()
            && !name.contains('%')
            && !name.to_ascii_uppercase().starts_with("LIST")
            && p.is_relative()
            && !p
                .components()
                .any(|c| matches!(c, std::path::Component::ParentDir));
        if !travels {
            bail!(
                "it names its data as `{name}`, which cannot travel with it (only a file beside \
                 it or below its folder): convert it to a single file (.nii.gz, .nrrd, .mha)"
            );
        }
        if !folder.join(p).is_file() {
            bail!("the file `{name}` it names is missing");
        }
    }
    Ok(names)
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
