//! Running a job's items in one session: shards, resuming, atomic outputs, a manifest per shard.

use hatchery_nodes::{Session, SessionError};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::BatchError;
use crate::job::{Item, Job, Setting};
use crate::manifest::{self, Entry, Manifest};

/// Items K, K+N, K+2N, … of a job (`--shard K/N`, a Slurm array task, a Kubernetes index).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole job.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Parses "K/N" (0 ≤ K < N).
    pub fn parse(text: &str) -> Result<Shard, BatchError> {
        let bad = || {
            BatchError::Shard(format!(
                "--shard `{text}`: expected K/N with 0 ≤ K < N, e.g. 0/4"
            ))
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            k.trim().parse::<usize>().map_err(|_| bad())?,
            n.trim().parse::<usize>().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The shard a scheduler gives this process through the environment: a Slurm job array
    /// (`SLURM_ARRAY_TASK_ID` less `SLURM_ARRAY_TASK_MIN`, of `SLURM_ARRAY_TASK_COUNT`) or a
    /// Kubernetes Indexed Job (`JOB_COMPLETION_INDEX`, of `count` or `HATCHERY_SHARD_COUNT`).
    /// `None` when neither is set.
    pub fn from_env(
        var: impl Fn(&str) -> Option<String>,
        count: Option<usize>,
    ) -> Result<Option<Shard>, BatchError> {
        Self::from_variables(var, count).map_err(BatchError::Shard)
    }

    fn from_variables(
        var: impl Fn(&str) -> Option<String>,
        count: Option<usize>,
    ) -> Result<Option<Shard>, String> {
        let number = |name: &str| -> Result<Option<usize>, String> {
            var(name)
                .map(|v| {
                    v.trim()
                        .parse::<usize>()
                        .map_err(|_| format!("{name}={v}: not a whole number"))
                })
                .transpose()
        };
        let count = match count {
            Some(c) => Some(c),
            None => number("HATCHERY_SHARD_COUNT")?,
        };
        let shard = if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let n = match count {
                Some(c) => c,
                None => number("SLURM_ARRAY_TASK_COUNT")?.ok_or(
                    "SLURM_ARRAY_TASK_ID is set but not SLURM_ARRAY_TASK_COUNT: give --shard-count",
                )?,
            };
            Shard {
                index: id
                    .checked_sub(min)
                    .ok_or("SLURM_ARRAY_TASK_ID below its MIN")?,
                count: n,
            }
        } else if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            Shard {
                index,
                count: count.ok_or(
                    "JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job): give the job's \
                     completions as --shard-count or HATCHERY_SHARD_COUNT",
                )?,
            }
        } else {
            return Ok(None);
        };
        if shard.count == 0 || shard.index >= shard.count {
            return Err(format!(
                "shard {} of {} from the environment: the index must be below the count",
                shard.index, shard.count
            ));
        }
        Ok(Some(shard))
    }

    /// "K-of-N", the manifest's name.
    pub fn tag(&self) -> String {
        format!("{}-of-{}", self.index, self.count)
    }

    /// The indices of this shard's items.
    pub fn indices(&self, job: &Job) -> Vec<usize> {
        (self.index..job.items.len()).step_by(self.count).collect()
    }
}

/// What happened to one item.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    Rendered,
    /// Done before (its output matches its manifest entry).
    Skipped,
    Failed(String),
}

/// Totals of a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    pub rendered: usize,
    pub skipped: usize,
    pub failed: usize,
    pub manifest: PathBuf,
}

/// Renders the items `indices` of `job` into `out` in one session (the executor's cache keeps
/// what does not change from item to item), writing each output atomically and the manifest
/// `manifest-{tag}.json` after each item. Items already done — output present, matching an
/// `ok` entry of any manifest in `out` for the same parameters — are skipped. A failing item is
/// recorded with its one-line error and the rest go on. `progress` hears of each item.
///
/// Errors: the graph cannot be opened (or the GPU), the manifest cannot be written.
pub fn run(
    job: &Job,
    out: &Path,
    indices: &[usize],
    tag: &str,
    progress: &mut dyn FnMut(&Item, &Outcome, f64),
) -> Result<Summary, BatchError> {
    std::fs::create_dir_all(out)
        .map_err(|e| BatchError::Io(format!("cannot create {}: {e}", out.display())))?;
    remove_stale_temporaries(job, out);
    let done = done_entries(out)?;
    let mut session = Session::open(&job.graph, job.size.0, job.size.1)?;
    let adapter = session.ctx.gpu.describe();
    let start_values = start_values(&session, job);
    let mut manifest = Manifest {
        job: job.path.display().to_string(),
        graph: job.graph.display().to_string(),
        size: job.size,
        shard: tag.to_owned(),
        adapter: adapter.clone(),
        items: Vec::new(),
    };
    let manifest_path = manifest::path(out, tag);
    let mut summary = Summary {
        manifest: manifest_path.clone(),
        ..Default::default()
    };
    for &index in indices {
        let item = &job.items[index];
        let key = item.key(job);
        let target = out.join(&item.output);
        let started = Instant::now();
        let previous = done.get(&index).filter(|e| {
            e.key == key
                && e.output == item.output
                && manifest::file_sha256(&target).is_some_and(|sha| sha == e.sha256)
        });
        let (outcome, entry) = if let Some(e) = previous {
            let mut e = e.clone();
            e.seconds = 0.0;
            (Outcome::Skipped, e)
        } else {
            let params = item_params(item, &start_values);
            let result = render_item(&mut session, job, item, &params, &target);
            let mut entry = Entry {
                index,
                output: item.output.clone(),
                status: "ok".into(),
                sha256: String::new(),
                seconds: started.elapsed().as_secs_f64(),
                params: params
                    .iter()
                    .map(|(n, p, v)| (format!("{n}.{p}"), v.clone()))
                    .collect(),
                input: item.input.as_ref().map(|(n, _)| n.clone()),
                files: item
                    .input
                    .iter()
                    .flat_map(|(_, f)| f.iter())
                    .map(|(k, v)| (k.clone(), v.display().to_string()))
                    .collect(),
                frame: item.frame,
                key,
                error: None,
                adapter: adapter.clone(),
            };
            match result {
                Ok(sha) => {
                    entry.sha256 = sha;
                    (Outcome::Rendered, entry)
                }
                Err(message) => {
                    entry.status = "failed".into();
                    entry.error = Some(message.clone());
                    (Outcome::Failed(message), entry)
                }
            }
        };
        match &outcome {
            Outcome::Rendered => summary.rendered += 1,
            Outcome::Skipped => summary.skipped += 1,
            Outcome::Failed(_) => summary.failed += 1,
        }
        manifest.items.push(entry);
        let text = serde_json::to_string_pretty(&manifest).expect("serialisable");
        crate::files::write_atomic(&manifest_path, text.as_bytes())?;
        progress(item, &outcome, started.elapsed().as_secs_f64());
    }
    Ok(summary)
}

/// Removes the temporary files a killed process left beside outputs (`.NAME.tmp-PID` of a
/// process that no longer runs). Only where processes can be looked up (/proc).
fn remove_stale_temporaries(job: &Job, out: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let mut dirs: Vec<PathBuf> = job
        .items
        .iter()
        .filter_map(|i| out.join(&i.output).parent().map(Path::to_path_buf))
        .collect();
    dirs.push(out.to_path_buf());
    dirs.sort();
    dirs.dedup();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for path in entries.filter_map(|e| e.ok().map(|e| e.path())) {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            let pid = name.as_deref().and_then(|n| {
                n.starts_with('.')
                    .then(|| n.rsplit_once(".tmp-"))
                    .flatten()
                    .and_then(|(_, pid)| pid.parse::<u32>().ok())
            });
            if let Some(pid) = pid
                && !Path::new(&format!("/proc/{pid}")).exists()
            {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
}

/// The good entries of every manifest in `out`, by item index (the last one read wins).
fn done_entries(out: &Path) -> Result<BTreeMap<usize, Entry>, BatchError> {
    let mut done = BTreeMap::new();
    for (_, m) in manifest::read_all(out)? {
        for e in m.items.into_iter().filter(|e| e.status == "ok") {
            done.insert(e.index, e);
        }
    }
    Ok(done)
}

/// The values of parameters the job turns relative to the graph's (an Orbit's azimuth).
fn start_values(session: &Session, job: &Job) -> BTreeMap<(String, String), f64> {
    let mut values = BTreeMap::new();
    for item in &job.items {
        for (node, param, value) in &item.params {
            if value.starts_with('+') {
                let v = session
                    .graph
                    .node(node)
                    .and_then(|n| n.params.get(param))
                    .and_then(|v| match v {
                        hatchery_graph::ParamValue::Float(f) => Some(*f),
                        _ => None,
                    })
                    .unwrap_or(0.0);
                values.insert((node.clone(), param.clone()), v);
            }
        }
    }
    values
}

/// The item's parameters with relative turns (`+90.0`) made absolute azimuths in [-180, 180).
fn item_params(item: &Item, start: &BTreeMap<(String, String), f64>) -> Vec<Setting> {
    item.params
        .iter()
        .map(|(node, param, value)| {
            let value = match value.strip_prefix('+').and_then(|v| v.parse::<f64>().ok()) {
                Some(turn) => {
                    let base = start
                        .get(&(node.clone(), param.clone()))
                        .copied()
                        .unwrap_or(0.0);
                    let a = ((base + turn + 180.0).rem_euclid(360.0) - 180.0) * 1e6;
                    format!("{:?}", a.round() / 1e6)
                }
                None => value.clone(),
            };
            (node.clone(), param.clone(), value)
        })
        .collect()
}

/// Sets the item's data and parameters, renders it and writes its output atomically; returns
/// the output's SHA-256. Errors are one line; a node failing on an input's file names it.
fn render_item(
    session: &mut Session,
    job: &Job,
    item: &Item,
    params: &[Setting],
    target: &Path,
) -> Result<String, String> {
    if let Some((_, files)) = &item.input {
        for (name, path) in files {
            session.set_input(name, path).map_err(|e| e.to_string())?;
        }
    }
    for (node, param, value) in params {
        session
            .set_param_text(node, param, value)
            .map_err(|e| format!("{node}.{param}={value}: {e}"))?;
    }
    let named = |session: &Session, e: SessionError| match &e {
        SessionError::Exec(exec) => match session.input_of(&exec.node) {
            Some(input) => format!("input `{}`: {e}", input.name),
            None => e.to_string(),
        },
        _ => e.to_string(),
    };
    if job.svg {
        let savers: Vec<String> = session
            .graph
            .nodes()
            .filter(|n| n.kind == "SaveSvg")
            .map(|n| n.id.clone())
            .collect();
        let [saver] = savers.as_slice() else {
            return Err(format!(
                "an .svg output needs one SaveSvg node in the graph; it has {}",
                savers.len()
            ));
        };
        if let Some(dir) = target.parent() {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        }
        // SaveSvg writes atomically itself (hatchery_graph::atomic): straight to the target.
        session
            .set_param_text(saver, "path", &target.to_string_lossy())
            .map_err(|e| e.to_string())?;
        session.run(&[saver]).map_err(|e| named(session, e))?;
        let bytes = std::fs::read(target).map_err(|e| format!("{}: {e}", target.display()))?;
        Ok(manifest::sha256(&bytes))
    } else {
        let picture = session
            .render_picture(None, None)
            .map_err(|e| named(session, e))?;
        let mut png = Vec::new();
        picture
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .map_err(|e| format!("cannot encode the picture: {e}"))?;
        crate::files::write_atomic(target, &png).map_err(|e| e.to_string())?;
        Ok(manifest::sha256(&png))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shards_from_flags_and_schedulers() {
        assert_eq!(Shard::parse("1/3").unwrap(), Shard { index: 1, count: 3 });
        assert!(Shard::parse("3/3").is_err() && Shard::parse("a/2").is_err());
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        assert_eq!(
            Shard::from_env(env(&slurm), None).unwrap(),
            Some(Shard { index: 1, count: 3 })
        );
        let k8s = [("JOB_COMPLETION_INDEX", "2"), ("HATCHERY_SHARD_COUNT", "4")];
        assert_eq!(
            Shard::from_env(env(&k8s), None).unwrap(),
            Some(Shard { index: 2, count: 4 })
        );
        assert_eq!(
            Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "2")]), Some(3)).unwrap(),
            Some(Shard { index: 2, count: 3 })
        );
        assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "2")]), None).is_err());
        assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "5")]), Some(3)).is_err());
        assert_eq!(Shard::from_env(env(&[]), None).unwrap(), None);
    }

    #[test]
    fn orbit_turns_are_absolute_azimuths() {
        let item = Item {
            index: 0,
            input: None,
            params: vec![("cam".into(), "azimuth".into(), "+270.0".into())],
            frame: Some(3),
            output: "x.png".into(),
            animation: None,
        };
        let start = BTreeMap::from([(("cam".to_string(), "azimuth".to_string()), 35.0)]);
        assert_eq!(item_params(&item, &start)[0].2, "-55.0");
    }
}
