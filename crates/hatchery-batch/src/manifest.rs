//! Manifests: one JSON file per shard listing each item's parameters, data, output, SHA-256,
//! time and adapter; resuming reads them back, `--merge` checks that every item is there once.

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::BatchError;
use crate::job::Job;

/// One item's record.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Entry {
    pub index: usize,
    /// Relative to the output folder.
    pub output: String,
    /// "ok" or "failed".
    pub status: String,
    /// Of the output file's bytes ("" when failed).
    pub sha256: String,
    /// Seconds the item took (0 when it was skipped as done).
    pub seconds: f64,
    /// "node.param" → value, as set.
    pub params: BTreeMap<String, String>,
    /// The data set's name and files, when the job has inputs.
    pub input: Option<String>,
    pub files: BTreeMap<String, String>,
    pub frame: Option<usize>,
    /// What determines the output (graph, size, files, values): see [`crate::job::Item::key`].
    pub key: String,
    /// The one-line error of a failed item.
    pub error: Option<String>,
    pub adapter: String,
}

/// A shard's manifest.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Manifest {
    pub job: String,
    pub graph: String,
    pub size: (u32, u32),
    /// "0-of-2", or the name a caller gave (a Dask chunk).
    pub shard: String,
    pub adapter: String,
    /// Items in the order they ran.
    pub items: Vec<Entry>,
}

/// The file of shard `tag`'s manifest in `out`.
pub fn path(out: &Path, tag: &str) -> PathBuf {
    out.join(format!("manifest-{tag}.json"))
}

/// Every shard manifest in `out` (`manifest-*.json`, not the merged `manifest.json`), by file
/// name. Unreadable or malformed ones are errors naming the file.
pub fn read_all(out: &Path) -> Result<Vec<(PathBuf, Manifest)>, BatchError> {
    let Ok(dir) = std::fs::read_dir(out) else {
        return Ok(Vec::new());
    };
    let mut files: Vec<PathBuf> = dir
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("manifest-") && n.ends_with(".json"))
        })
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p)
                .map_err(|e| BatchError::Manifest(format!("{}: cannot read: {e}", p.display())))?;
            let m = serde_json::from_str(&text).map_err(|e| {
                BatchError::Manifest(format!("{}: not a batch manifest: {e}", p.display()))
            })?;
            Ok((p, m))
        })
        .collect()
}

/// SHA-256 of `bytes`, hex.
pub fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// SHA-256 of a file, or None when it cannot be read.
pub fn file_sha256(path: &Path) -> Option<String> {
    std::fs::read(path).ok().map(|b| sha256(&b))
}

/// What `--merge` found.
#[derive(Debug, Default)]
pub struct Merged {
    /// Items with one good output.
    pub complete: usize,
    /// One line per problem: missing, failed, changed or duplicated items.
    pub problems: Vec<String>,
    /// Where the merged manifest went (when complete).
    pub written: Option<PathBuf>,
    /// The animations written (when complete and the job makes them).
    pub animations: Vec<PathBuf>,
}

/// Checks that every item of `job` is present once in the shard manifests in `out`, done with
/// the job's current parameters and with its output file unchanged, and writes the merged
/// `manifest.json` (items in order) when they all are.
pub fn merge(job: &Job, out: &Path) -> Result<Merged, BatchError> {
    let manifests = read_all(out)?;
    let mut by_index: BTreeMap<usize, Vec<(&Path, &Entry)>> = BTreeMap::new();
    for (file, m) in &manifests {
        for e in &m.items {
            by_index
                .entry(e.index)
                .or_default()
                .push((file.as_path(), e));
        }
    }
    let mut merged = Merged::default();
    let mut entries = Vec::new();
    for item in &job.items {
        let found = by_index.remove(&item.index).unwrap_or_default();
        let key = item.key(job);
        let good: Vec<&Entry> = found
            .iter()
            .map(|(_, e)| *e)
            .filter(|e| e.status == "ok" && e.key == key && e.output == item.output)
            .collect();
        let mut shas: Vec<&str> = good.iter().map(|e| e.sha256.as_str()).collect();
        shas.sort_unstable();
        shas.dedup();
        match (good.first(), shas.len()) {
            (None, _) => merged.problems.push(match found.iter().find(|(_, e)| e.status == "failed") {
                Some((_, e)) => format!(
                    "item {} ({}) failed: {}",
                    item.index,
                    item.output,
                    e.error.as_deref().unwrap_or("no message")
                ),
                None if found.is_empty() => {
                    format!("item {} ({}) is in no manifest", item.index, item.output)
                }
                None => format!(
                    "item {} ({}) was rendered with other parameters or data than the job's now",
                    item.index, item.output
                ),
            }),
            (Some(_), n) if n > 1 => merged.problems.push(format!(
                "item {} ({}) is in several manifests with different outputs",
                item.index, item.output
            )),
            (Some(e), _) => match file_sha256(&out.join(&item.output)) {
                Some(sha) if sha == e.sha256 => {
                    merged.complete += 1;
                    entries.push((*e).clone());
                }
                Some(_) => merged.problems.push(format!(
                    "item {} ({}): the file changed since it was rendered",
                    item.index, item.output
                )),
                None => merged.problems.push(format!(
                    "item {} ({}): the file is missing",
                    item.index, item.output
                )),
            },
        }
    }
    for index in by_index.keys() {
        merged.problems.push(format!(
            "item {index} is not in the job (a manifest of another job?)"
        ));
    }
    if merged.problems.is_empty() {
        let adapter = entries
            .first()
            .map(|e| e.adapter.clone())
            .unwrap_or_default();
        let manifest = Manifest {
            job: job.path.display().to_string(),
            graph: job.graph.display().to_string(),
            size: job.size,
            shard: "merged".into(),
            adapter,
            items: entries,
        };
        let path = out.join("manifest.json");
        let text = serde_json::to_string_pretty(&manifest).expect("serialisable");
        crate::files::write_atomic(&path, text.as_bytes())?;
        merged.written = Some(path);
        merged.animations = animations(job, out)?;
    }
    Ok(merged)
}

/// Writes each animation of the job from its frames' PNGs (in frame order).
fn animations(job: &Job, out: &Path) -> Result<Vec<PathBuf>, BatchError> {
    let mut groups: BTreeMap<&str, Vec<&crate::job::Item>> = BTreeMap::new();
    for item in &job.items {
        if let Some(a) = &item.animation {
            groups.entry(a).or_default().push(item);
        }
    }
    let mut written = Vec::new();
    for (animation, mut items) in groups {
        items.sort_by_key(|i| i.frame);
        let frames = items
            .iter()
            .map(|i| {
                let path = out.join(&i.output);
                image::open(&path)
                    .map(|p| p.to_rgba8())
                    .map_err(|e| BatchError::Animation(format!("{}: {e}", path.display())))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let path = out.join(animation);
        crate::animation::write(&path, &frames, job.fps)?;
        written.push(path);
    }
    Ok(written)
}
