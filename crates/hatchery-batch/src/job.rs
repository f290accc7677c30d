//! Job files: a graph, a frame size and the work (input files × a parameter sweep × a camera
//! path), expanded into a deterministic list of items, each with its output path.

use crate::BatchError;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A job as written in its RON file (docs/batch.md).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JobFile {
    /// The graph, relative to the job file's folder.
    pub graph: String,
    /// Frame size in pixels (width, height).
    pub size: (u32, u32),
    /// Sets of files for the graph's inputs, one set per data set: `[{"volume": "a.nii.gz"}]`
    /// (relative to the job file's folder). Empty: the graph's own files.
    #[serde(default)]
    pub inputs: Vec<BTreeMap<String, String>>,
    /// A grid of parameter values: every combination, the first entry varying slowest.
    #[serde(default)]
    pub sweep: Vec<(String, Vec<ron::Value>)>,
    /// A camera path, innermost (a turntable per data set and sweep point).
    #[serde(default)]
    pub camera: Option<CameraPath>,
    /// Where each item goes, relative to the output folder: `{index}`, `{index:04}`, `{frame}`,
    /// `{frame:03}`, `{input}` (the data set's name) and `{node.param}` (the item's value).
    /// `.png` writes the picture (what SaveImage writes), `.svg` the graph's SaveSvg figure.
    pub output: String,
    /// The camera path's frames also as an animation (.mp4, .webm, .gif, .png/.apng), one per
    /// data set and sweep point: `{input}` and `{node.param}` placeholders, not `{frame}`.
    /// Written by `--merge` (and at the end of an unsharded run), from the frames' PNGs.
    #[serde(default)]
    pub animation: Option<String>,
    /// Frames per second of the animation (default 24).
    #[serde(default)]
    pub fps: Option<f64>,
}

/// A camera path over `frames` frames.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum CameraPath {
    /// A full turn of the azimuth from its value in the graph (`frames` steps of 360°/frames).
    Orbit { node: String, frames: usize },
    /// Camera parameters at key frames (`{"azimuth": 0, "elevation": 20}`), interpolated
    /// linearly over `frames` frames from the first key to the last (keys evenly spaced).
    Keys {
        node: String,
        frames: usize,
        keys: Vec<BTreeMap<String, f64>>,
    },
}

/// A parameter to set: (node, param, value as `--set` text).
pub type Setting = (String, String, String);

/// One unit of work: a data set, parameter values and a camera frame, and its output.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// Position in the job's work list (0-based).
    pub index: usize,
    /// The data set's name (`{input}`) and its files by input name (absolute).
    pub input: Option<(String, BTreeMap<String, PathBuf>)>,
    /// `(node, param, value text)` to set, sweep first, then the camera frame's.
    pub params: Vec<Setting>,
    /// The camera frame (0-based), when the job has a camera path.
    pub frame: Option<usize>,
    /// The output, relative to the output folder.
    pub output: String,
    /// The animation this item is a frame of, relative to the output folder.
    pub animation: Option<String>,
}

impl Item {
    /// What determines the item's output, for the manifest: the same key, the same bytes.
    pub fn key(&self, job: &Job) -> String {
        let mut key = format!("{}|{}x{}", job.graph.display(), job.size.0, job.size.1);
        if let Some((_, files)) = &self.input {
            for (name, path) in files {
                key.push_str(&format!("|{name}={}", path.display()));
            }
        }
        for (node, param, value) in &self.params {
            key.push_str(&format!("|{node}.{param}={value}"));
        }
        key
    }
}

/// A loaded job: paths resolved, the work list expanded and checked.
#[derive(Clone, Debug)]
pub struct Job {
    pub path: PathBuf,
    /// The graph file (absolute).
    pub graph: PathBuf,
    pub size: (u32, u32),
    pub items: Vec<Item>,
    /// Whether outputs are SVG figures (else PNG pictures).
    pub svg: bool,
    /// Frames per second of the animations.
    pub fps: f64,
}

/// Loads a job file and expands its work list. Errors (one line, naming the job file): RON
/// syntax, an output pattern with an unknown placeholder or an extension other than .png/.svg,
/// an empty sweep list, a camera path of no frames, two items writing one file.
pub fn load(path: &Path) -> Result<Job, BatchError> {
    read_job(path).map_err(BatchError::Job)
}

fn read_job(path: &Path) -> Result<Job, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the job file: {e}", path.display()))?;
    let file: JobFile = ron::from_str(&text).map_err(|e| {
        format!(
            "{}:{}:{}: {}",
            path.display(),
            e.span.start.line,
            e.span.start.col,
            e.code
        )
    })?;
    work_list(path, &file).map_err(|e| format!("{}: {e}", path.display()))
}

fn folder(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    abs.parent().map(Path::to_path_buf).unwrap_or_default()
}

/// The work list of a parsed job (`path` locates relative files). Errors: [`BatchError::Job`],
/// as for [`load`].
pub fn expand(path: &Path, file: &JobFile) -> Result<Job, BatchError> {
    work_list(path, file).map_err(BatchError::Job)
}

fn work_list(path: &Path, file: &JobFile) -> Result<Job, String> {
    let base = folder(path);
    let (w, h) = file.size;
    if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
        return Err(format!("size ({w}, {h}): 1 to 16384 pixels per side"));
    }
    let lower = file.output.to_ascii_lowercase();
    let svg = lower.ends_with(".svg");
    if !svg && !lower.ends_with(".png") {
        return Err(format!(
            "output `{}` must end in .png (the picture) or .svg (the SaveSvg figure)",
            file.output
        ));
    }
    // Data sets: their files, named by the first file's stem.
    let inputs: Vec<Option<(String, BTreeMap<String, PathBuf>)>> = if file.inputs.is_empty() {
        vec![None]
    } else {
        file.inputs
            .iter()
            .map(|set| {
                let files: BTreeMap<String, PathBuf> = set
                    .iter()
                    .map(|(name, p)| (name.clone(), base.join(p)))
                    .collect();
                let name = set.values().next().map(|p| stem(p)).unwrap_or_default();
                Some((name, files))
            })
            .collect()
    };
    if let Some(animation) = &file.animation {
        if file.camera.is_none() || svg {
            return Err(format!(
                "animation `{animation}` needs a camera path and .png frames"
            ));
        }
        if animation.contains("{frame") || animation.contains("{index") {
            return Err(format!(
                "animation `{animation}`: one file holds every frame; use {{input}} or swept \
                 {{node.param}} placeholders, not {{frame}} or {{index}}"
            ));
        }
        crate::animation::format_of(Path::new(animation)).map_err(|e| e.to_string())?;
    }
    let sweep = sweep_points(&file.sweep)?;
    let frames = camera_frames(file.camera.as_ref())?;
    let mut items = Vec::new();
    for input in &inputs {
        for point in &sweep {
            for frame in &frames {
                let index = items.len();
                let mut params = point.clone();
                params.extend(frame.1.iter().cloned());
                let mut item = Item {
                    index,
                    input: input.clone(),
                    params,
                    frame: frame.0,
                    output: String::new(),
                    animation: None,
                };
                item.output = fill(&file.output, &item)?;
                if let Some(pattern) = &file.animation {
                    item.animation = Some(fill(pattern, &item)?);
                }
                items.push(item);
            }
        }
    }
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    for item in &items {
        if let Some(first) = seen.insert(&item.output, item.index) {
            return Err(format!(
                "items {first} and {} both write `{}`: put {{index}} (or the varying \
                 placeholders) into the output pattern",
                item.index, item.output
            ));
        }
    }
    Ok(Job {
        path: std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()),
        graph: base.join(&file.graph),
        size: (w, h),
        items,
        svg,
        fps: file.fps.unwrap_or(24.0),
    })
}

/// A file's name without its extensions ("sub-01_T1w.nii.gz" → "sub-01_T1w").
fn stem(path: &str) -> String {
    let name = Path::new(path)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    name.split('.').next().unwrap_or_default().to_owned()
}

/// Every combination of the sweep's values, the first entry varying slowest.
fn sweep_points(sweep: &[(String, Vec<ron::Value>)]) -> Result<Vec<Vec<Setting>>, String> {
    let mut points = vec![Vec::new()];
    for (target, values) in sweep {
        let (node, param) = target
            .split_once('.')
            .ok_or_else(|| format!("sweep `{target}`: expected node.param"))?;
        if values.is_empty() {
            return Err(format!("sweep `{target}`: no values"));
        }
        let texts = values
            .iter()
            .map(value_text)
            .collect::<Result<Vec<_>, _>>()?;
        points = points
            .into_iter()
            .flat_map(|point| {
                texts.iter().map(move |t| {
                    let mut p = point.clone();
                    p.push((node.to_owned(), param.to_owned(), t.clone()));
                    p
                })
            })
            .collect();
    }
    Ok(points)
}

/// A sweep value as the command line's `--set` text.
fn value_text(value: &ron::Value) -> Result<String, String> {
    Ok(match value {
        ron::Value::Number(n) => match n {
            ron::Number::F32(f) => format!("{:?}", f.get()),
            ron::Number::F64(f) => format!("{:?}", f.get()),
            other => format!("{}", other.into_f64()),
        },
        ron::Value::String(s) => s.clone(),
        ron::Value::Bool(b) => b.to_string(),
        ron::Value::Seq(items) => format!(
            "[{}]",
            items
                .iter()
                .map(value_text)
                .collect::<Result<Vec<_>, _>>()?
                .join(", ")
        ),
        other => {
            return Err(format!(
                "sweep value {other:?}: a number, text, bool or list"
            ));
        }
    })
}

/// The camera path's frames: (frame index, parameters to set); one frame of nothing without a
/// path.
/// A camera frame: its index and what it sets.
type Frame = (Option<usize>, Vec<Setting>);

fn camera_frames(path: Option<&CameraPath>) -> Result<Vec<Frame>, String> {
    let Some(path) = path else {
        return Ok(vec![(None, Vec::new())]);
    };
    match path {
        CameraPath::Orbit { node, frames } => {
            if *frames == 0 {
                return Err("camera Orbit: frames must be at least 1".into());
            }
            // The start azimuth is the graph's; the offset is applied when the item runs
            // (see run::apply), so the path is written as a relative turn here.
            Ok((0..*frames)
                .map(|f| {
                    let turn = 360.0 * f as f64 / *frames as f64;
                    (
                        Some(f),
                        vec![(node.clone(), "azimuth".into(), format!("+{turn:?}"))],
                    )
                })
                .collect())
        }
        CameraPath::Keys { node, frames, keys } => {
            if *frames == 0 || keys.is_empty() {
                return Err("camera Keys: needs frames ≥ 1 and at least one key".into());
            }
            let names: Vec<&String> = keys[0].keys().collect();
            if let Some(k) = keys
                .iter()
                .position(|k| k.keys().collect::<Vec<_>>() != names)
            {
                return Err(format!(
                    "camera Keys: key {k} sets other parameters than key 0 ({})",
                    names
                        .iter()
                        .map(|s| s.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            Ok((0..*frames)
                .map(|f| {
                    let t = if *frames == 1 {
                        0.0
                    } else {
                        f as f64 / (*frames - 1) as f64 * (keys.len() - 1) as f64
                    };
                    let (i, u) = (t.floor() as usize, t.fract());
                    let j = (i + 1).min(keys.len() - 1);
                    let params = names
                        .iter()
                        .map(|name| {
                            let v = keys[i][*name] * (1.0 - u) + keys[j][*name] * u;
                            let v = (v * 1e6).round() / 1e6;
                            (node.clone(), (*name).clone(), format!("{v:?}"))
                        })
                        .collect();
                    (Some(f), params)
                })
                .collect())
        }
    }
}

/// The output pattern with the item's placeholders filled in. Hand-written: the placeholders
/// are a handful (with a zero-padded width), which no small, well-kept crate matches.
fn fill(pattern: &str, item: &Item) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = pattern;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let close = rest[open..]
            .find('}')
            .ok_or_else(|| format!("output `{pattern}`: `{{` without `}}`"))?
            + open;
        let spec = &rest[open + 1..close];
        let (name, width) = match spec.split_once(':') {
            Some((n, w)) => (
                n,
                Some(w.parse::<usize>().map_err(|_| {
                    format!("output `{pattern}`: `{{{spec}}}`: the width must be digits like 04")
                })?),
            ),
            None => (spec, None),
        };
        let number = |v: usize| match width {
            Some(w) => format!("{v:0w$}"),
            None => v.to_string(),
        };
        let text = match name {
            "index" => number(item.index),
            "frame" => number(item.frame.unwrap_or(0)),
            "input" => item
                .input
                .as_ref()
                .map(|(n, _)| n.clone())
                .unwrap_or_else(|| "graph".into()),
            other => match item
                .params
                .iter()
                .find(|(n, p, _)| format!("{n}.{p}") == other)
            {
                Some((_, _, v)) => v
                    .trim_start_matches('+')
                    .chars()
                    .map(|c| {
                        if c.is_alphanumeric() || "-._".contains(c) {
                            c
                        } else {
                            '_'
                        }
                    })
                    .collect(),
                None => {
                    return Err(format!(
                        "output `{pattern}`: unknown placeholder `{{{other}}}` (index, frame, \
                         input, or a swept node.param)"
                    ));
                }
            },
        };
        out.push_str(&text);
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(body: &str) -> Result<Job, String> {
        let file: JobFile = ron::from_str(body).map_err(|e| e.to_string())?;
        expand(Path::new("/jobs/j.ron"), &file).map_err(|e| e.to_string())
    }

    #[test]
    fn items_are_data_sets_by_sweep_grid_by_camera_frames() {
        let j = job(r#"(graph: "../g.ron", size: (8, 6),
            inputs: [{"volume": "a/sub-01.nii.gz"}, {"volume": "/d/sub-02.nii"}],
            sweep: [("hatch.cell", [4, 8.5]), ("style.select", ["ink", "gooch"])],
            camera: Some(Keys(node: "camera", frames: 3, keys: [{"azimuth": 0, "elevation": 10}, {"azimuth": 90, "elevation": 30}])),
            output: "{input}/{hatch.cell}_{style.select}_{frame:02}.png")"#).unwrap();
        assert_eq!(j.items.len(), 2 * 4 * 3);
        assert_eq!(j.graph, Path::new("/jobs/../g.ron"));
        let i = &j.items[5];
        assert_eq!(i.output, "sub-01/4_gooch_02.png");
        assert_eq!(
            i.params,
            vec![
                ("hatch".into(), "cell".into(), "4".into()),
                ("style".into(), "select".into(), "gooch".into()),
                ("camera".into(), "azimuth".into(), "90.0".into()),
                ("camera".into(), "elevation".into(), "30.0".into()),
            ]
        );
        assert_eq!(j.items[1].params[2].2, "45.0", "half-way between the keys");
        let last = j.items.last().unwrap();
        assert_eq!(last.output, "sub-02/8.5_gooch_02.png");
        assert_eq!(
            last.input.as_ref().unwrap().1["volume"],
            Path::new("/d/sub-02.nii")
        );
        // The same job gives the same list.
        assert_eq!(j.items, job(r#"(graph: "../g.ron", size: (8, 6),
            inputs: [{"volume": "a/sub-01.nii.gz"}, {"volume": "/d/sub-02.nii"}],
            sweep: [("hatch.cell", [4, 8.5]), ("style.select", ["ink", "gooch"])],
            camera: Some(Keys(node: "camera", frames: 3, keys: [{"azimuth": 0, "elevation": 10}, {"azimuth": 90, "elevation": 30}])),
            output: "{input}/{hatch.cell}_{style.select}_{frame:02}.png")"#).unwrap().items);
    }

    #[test]
    fn an_orbit_turns_from_the_graph_azimuth() {
        let j = job(r#"(graph: "g.ron", size: (8, 6), camera: Some(Orbit(node: "cam", frames: 4)), output: "{frame}.png")"#).unwrap();
        let turns: Vec<&str> = j.items.iter().map(|i| i.params[0].2.as_str()).collect();
        assert_eq!(turns, ["+0.0", "+90.0", "+180.0", "+270.0"]);
        assert_eq!(j.items[3].output, "3.png");
    }
}
