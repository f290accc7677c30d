//! Batch jobs from Python (`hatchery.batch`): the work list, a chunk of it rendered in this
//! process, and the merge check — the same code `hatchery batch` runs, so a Dask map of the
//! chunks writes what the command line's shards write.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};

use crate::errors::JobError;

fn load(job: &Path) -> PyResult<hatchery_batch::Job> {
    hatchery_batch::load(job).map_err(|e| JobError::new_err(e.to_string()))
}

/// The job's work list: dicts `{index, output, input, params, frame}` (params: {"node.param":
/// value text}). Raises JobError.
#[pyfunction]
pub fn batch_items(py: Python<'_>, job: PathBuf) -> PyResult<Bound<'_, PyList>> {
    let job = load(&job)?;
    let list = PyList::empty(py);
    for item in &job.items {
        let d = PyDict::new(py);
        d.set_item("index", item.index)?;
        d.set_item("output", &item.output)?;
        d.set_item("input", item.input.as_ref().map(|(n, _)| n.clone()))?;
        let params = PyDict::new(py);
        for (n, p, v) in &item.params {
            params.set_item(format!("{n}.{p}"), v)?;
        }
        d.set_item("params", params)?;
        d.set_item("frame", item.frame)?;
        list.append(d)?;
    }
    Ok(list)
}

/// Renders the items `indices` of `job` into `out` in one session (the GIL released), writing
/// the manifest `manifest-{tag}.json`; returns `{rendered, skipped, failed, manifest}`. Failed
/// items are in the manifest with their error. Raises JobError (the job, the graph or the GPU
/// cannot be opened).
#[pyfunction]
pub fn batch_run(
    py: Python<'_>,
    job: PathBuf,
    out: PathBuf,
    indices: Vec<usize>,
    tag: String,
) -> PyResult<Bound<'_, PyDict>> {
    let job = load(&job)?;
    if let Some(bad) = indices.iter().find(|&&i| i >= job.items.len()) {
        return Err(JobError::new_err(format!(
            "item {bad}: the job has {} items",
            job.items.len()
        )));
    }
    let summary = py
        .detach(|| hatchery_batch::run(&job, &out, &indices, &tag, &mut |_, _, _| {}))
        .map_err(|e| JobError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("rendered", summary.rendered)?;
    d.set_item("skipped", summary.skipped)?;
    d.set_item("failed", summary.failed)?;
    d.set_item("manifest", summary.manifest)?;
    Ok(d)
}

/// Checks the manifests in `out` cover every item once (as `hatchery batch JOB --merge`) and
/// writes `manifest.json` when they do: `{complete, problems, manifest}`. Raises JobError.
#[pyfunction]
pub fn batch_merge(py: Python<'_>, job: PathBuf, out: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let job = load(&job)?;
    let merged = hatchery_batch::manifest::merge(&job, &out)
        .map_err(|e| JobError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("complete", merged.complete)?;
    d.set_item("problems", merged.problems)?;
    d.set_item("manifest", merged.written)?;
    Ok(d)
}
