//! Helpers shared by the integration tests: graph sessions and tolerant comparisons that report
//! the worst sample and save the offending image.

#![allow(dead_code)]

pub mod bspline_reference;
pub mod images;
pub mod importance_reference;
pub mod importance_scene;
pub mod npy;
pub mod ray_columns;
pub mod raycast_reference;
pub mod selection_reference;
pub mod two_level_reference;

// Not every test uses every helper.
#[allow(unused_imports)]
pub use images::{
    Exact, ImageDiff, Pixel, assert_images_close, assert_images_close_where,
    assert_images_identical, channel_difference, diff_images, f32_at_most, rgba8_pixels, texels,
    worst_channel,
};

use hatchery_graph::{Graph, GraphDocument, NodeInputs, ParamValue, Params};
use hatchery_nodes::Session;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn shared_data(relative: &str) -> PathBuf {
    repo_root().join("../shared/data").join(relative)
}

/// A session on graph text (relative paths resolve against the repository root).
pub fn session_from_text(text: &str, width: u32, height: u32) -> Session {
    let registry = hatchery_nodes::registry();
    let (doc, source) = GraphDocument::parse(text, None).expect("test graph parses");
    let graph = Graph::from_document(&doc, &source, &registry, Some(&repo_root()))
        .expect("test graph is valid");
    Session::with_graph(registry, graph, width, height).expect("GPU available")
}

/// One compared sample.
pub struct Sample {
    pub x: u32,
    pub y: u32,
    pub what: String,
    pub error: f64,
}

/// Fails if any sample's error exceeds `tolerance`, naming the worst one and writing `picture`
/// (if given) to a temporary folder for inspection.
pub fn assert_samples(
    name: &str,
    samples: &[Sample],
    tolerance: f64,
    picture: Option<&image::RgbaImage>,
) {
    assert!(!samples.is_empty(), "{name}: no samples compared");
    let worst = samples
        .iter()
        .max_by(|a, b| a.error.total_cmp(&b.error))
        .expect("non-empty");
    let failing = samples.iter().filter(|s| s.error > tolerance).count();
    if failing > 0 {
        let saved = picture
            .map(|p| save_failure(name, p))
            .map(|p| format!("; image written to {}", p.display()));
        panic!(
            "{name}: {failing} of {} samples exceed tolerance {tolerance}; worst at pixel ({}, {}): {} (error {}){}",
            samples.len(),
            worst.x,
            worst.y,
            worst.what,
            worst.error,
            saved.unwrap_or_default()
        );
    }
}

/// The ids of a session's SaveImage nodes.
pub fn savers(session: &Session) -> Vec<String> {
    let nodes = session.graph.nodes();
    let savers = nodes.filter(|n| n.kind == "SaveImage");
    savers.map(|n| n.id.clone()).collect()
}

/// Writes `picture` as `name`.png (characters other than letters, digits, `.`, `-` and `_`
/// replaced) into a temporary folder, and says where.
pub fn save_failure(name: &str, picture: &image::RgbaImage) -> PathBuf {
    let dir = std::env::temp_dir().join("hatchery-test-failures");
    let _ = std::fs::create_dir_all(&dir);
    let file: String = name
        .chars()
        .map(|c| match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' | '.' | '-' | '_' => c,
            _ => '_',
        })
        .collect();
    let path = dir.join(format!("{file}.png"));
    let _ = picture.save(&path);
    path
}

/// Fraction of pixels whose colour differs from the first pixel's (a blank picture gives 0).
pub fn non_background_fraction(picture: &image::RgbaImage) -> f64 {
    let background = *picture.get_pixel(0, 0);
    let differing = picture.pixels().filter(|p| **p != background).count();
    differing as f64 / (picture.width() * picture.height()) as f64
}

pub fn read_png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
        .to_rgba8()
}

/// Runs one node kind directly on given inputs (for synthetic inputs no graph produces).
pub fn run_node(
    session: &mut Session,
    kind: &str,
    inputs: Vec<(&'static str, hatchery_nodes::Value)>,
    params: &[(&str, ParamValue)],
) -> Vec<hatchery_nodes::Value> {
    try_run_node(session, kind, inputs, params).unwrap_or_else(|e| panic!("{kind}: {e}"))
}

/// [`run_node`], returning the node's error (its message, with the port it names) instead of
/// failing.
pub fn try_run_node(
    session: &mut Session,
    kind: &str,
    inputs: Vec<(&'static str, hatchery_nodes::Value)>,
    params: &[(&str, ParamValue)],
) -> Result<Vec<hatchery_nodes::Value>, hatchery_graph::NodeError> {
    let node = session
        .registry
        .node(kind)
        .unwrap_or_else(|| panic!("no node kind {kind}"));
    let schema = node.schema();
    let mut values: BTreeMap<String, ParamValue> = schema
        .params
        .iter()
        .map(|p| (p.name.to_owned(), p.default.clone()))
        .collect();
    for (name, value) in params {
        values.insert((*name).to_owned(), value.clone());
    }
    let names: Vec<&'static str> = schema.inputs.iter().map(|p| p.name).collect();
    let ordered = names
        .iter()
        .map(|n| {
            inputs
                .iter()
                .find(|(name, _)| name == n)
                .map(|(_, v)| v.clone())
        })
        .collect();
    let outputs = node.execute(
        &mut session.ctx,
        &NodeInputs::new(names, ordered),
        &Params::new(values, None),
    )?;
    // What the executor checks: one value per declared output, of the declared type.
    assert_eq!(
        outputs.len(),
        schema.outputs.len(),
        "{kind}: outputs vs schema"
    );
    for (value, port) in outputs.iter().zip(&schema.outputs) {
        assert_eq!(value.port_type(), port.ty, "{kind}: output `{}`", port.name);
    }
    Ok(outputs)
}

/// `f` sampled on an n³ grid over world [-1, 1]³ (analytic surfaces as level sets).
pub fn field_on_cube(n: u32, f: impl Fn(glam::Vec3) -> f32) -> hatchery_data::VolumeData {
    let spacing = 2.0 / (n - 1) as f64;
    let geometry = hatchery_data::geometry::Geometry::axis_aligned([spacing; 3], [-1.0; 3]);
    let mut values = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let p = glam::Vec3::new(x as f32, y as f32, z as f32) * spacing as f32 - 1.0;
                values.push(f(p));
            }
        }
    }
    hatchery_data::VolumeData::with_geometry([n; 3], geometry, values).unwrap()
}

/// Every preset graph in graphs/, sorted.
pub fn presets() -> Vec<PathBuf> {
    ron_files(&repo_root().join("graphs"))
}

/// Every `.ron` file in `dir`, sorted.
pub fn ron_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    files
}

/// Runs the `hatchery` binary in the repository root.
pub fn hatchery(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_hatchery"))
        .args(args)
        .current_dir(repo_root())
        .output()
        .expect("hatchery runs")
}

/// What SaveImage node `saver` of `session` would write, rendered without writing it (its
/// input, as RGBA8). Errors: the render's, naming the node that failed.
pub fn saver_input(session: &mut Session, saver: &str) -> Result<image::RgbaImage, String> {
    let (source, port) = {
        let sources = session.graph.input_sources(saver);
        let (node, port) = sources[&0];
        (node.to_owned(), port)
    };
    session.run(&[&source]).map_err(|e| e.to_string())?;
    let value = session.executor.output(&source, port).unwrap().clone();
    hatchery_nodes::export::to_rgba8(&value, &session.ctx.gpu).map_err(|e| e.to_string())
}
