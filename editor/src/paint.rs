//! Volume painting in the viewport (VolumeShop §6.1): with the paint tool on, a drag over the
//! picture adds brush dabs to a `PaintLabels` node where the pointer meets the first visible
//! surface. The surface comes from the depth of the G-buffers the shown picture is made from
//! (the render worker reads them back while the tool is on); a dab is written into the node's
//! `strokes` parameter, so the painting is saved with the graph and one drag is one undo step.

use crate::state::EditorState;
use glam::{Mat4, Vec3, Vec4};
use hatchery_graph::{GraphDocument, ParamValue};

/// An output port: (node id, port name), as `render_worker::Port` (not imported: the render
/// worker reads [`DepthMap`] from here).
type Port = (String, String);

/// Window-space depth of a rendered frame and the camera that unprojects it.
#[derive(Clone)]
pub struct DepthMap {
    pub width: u32,
    pub height: u32,
    /// Per pixel (row-major, y down), in [0, 1]; 1 where no surface.
    pub depth: Vec<f32>,
    pub inv_view_proj: Mat4,
}

impl DepthMap {
    /// The world position of the surface seen at pixel (x, y) of the frame, if any.
    pub fn world_at(&self, x: f32, y: f32) -> Option<Vec3> {
        let (px, py) = (x.floor() as i64, y.floor() as i64);
        if px < 0 || py < 0 || px >= i64::from(self.width) || py >= i64::from(self.height) {
            return None;
        }
        let d = self.depth[py as usize * self.width as usize + px as usize];
        if !(0.0..1.0).contains(&d) {
            return None;
        }
        let ndc = Vec4::new(
            (px as f32 + 0.5) / self.width as f32 * 2.0 - 1.0,
            1.0 - (py as f32 + 0.5) / self.height as f32 * 2.0,
            d,
            1.0,
        );
        let p = self.inv_view_proj * ndc;
        Some(p.truncate() / p.w)
    }

    /// The nearest surface of several maps of one frame (per pixel, the smallest depth).
    pub fn nearest(maps: Vec<DepthMap>) -> Option<DepthMap> {
        let mut maps = maps.into_iter();
        let mut first = maps.next()?;
        for map in maps {
            if map.width == first.width && map.height == first.height {
                for (a, b) in first.depth.iter_mut().zip(&map.depth) {
                    *a = a.min(*b);
                }
            }
        }
        Some(first)
    }
}

/// The `PaintLabels` node the paint tool paints into: a selected one, else the first by id.
pub fn painter(state: &EditorState) -> Option<String> {
    let doc = state.doc();
    let painters = || doc.nodes.iter().filter(|n| n.kind == "PaintLabels");
    painters()
        .find(|n| state.selection.contains(&n.id))
        .or_else(|| painters().min_by(|a, b| a.id.cmp(&b.id)))
        .map(|n| n.id.clone())
}

/// The G-buffer outputs upstream of the shown port (the ray casters and rasterisers whose
/// pictures it is made from), nearest first.
pub fn depth_sources(state: &EditorState, shown: &Port) -> Vec<Port> {
    let doc: &GraphDocument = state.doc();
    let mut found = Vec::new();
    let mut queue = std::collections::VecDeque::from([shown.0.clone()]);
    let mut seen = std::collections::BTreeSet::new();
    while let Some(id) = queue.pop_front() {
        if !seen.insert(id.clone()) {
            continue;
        }
        let Some(node) = doc.nodes.iter().find(|n| n.id == id) else {
            continue;
        };
        let has_gbuffer = hatchery_graph::node_schema(&state.registry, doc, node)
            .is_some_and(|s| s.outputs.iter().any(|o| o.name == "gbuffer"));
        if has_gbuffer {
            found.push((id.clone(), "gbuffer".to_owned()));
        }
        for edge in doc.edges.iter().filter(|e| e.to.0 == id) {
            queue.push_back(edge.from.0.clone());
        }
    }
    found
}

/// A node parameter's value as the graph uses it.
fn param(state: &EditorState, node: &str, name: &str) -> Option<ParamValue> {
    let doc = state.doc();
    let n = doc.nodes.iter().find(|n| n.id == node)?;
    let schema = hatchery_graph::node_schema(&state.registry, doc, n)?;
    let spec = schema.param(name)?;
    match n.params.get(name) {
        Some(raw) => spec.convert(raw).ok(),
        None => Some(spec.default.clone()),
    }
}

/// Adds a dab at `at` (world) to `node`'s strokes with its brush radius and id (`erase`: id 0),
/// merged into the undo step of the current drag. Returns the brush radius.
pub fn add_dab(state: &mut EditorState, node: &str, at: Vec3, erase: bool) -> Result<f32, String> {
    let radius = match param(state, node, "radius") {
        Some(ParamValue::Float(r)) => r as f32,
        _ => 4.0,
    };
    let id = match (erase, param(state, node, "id")) {
        (true, _) => 0,
        (false, Some(ParamValue::Int(id))) => id.clamp(0, 65535) as u16,
        _ => 1,
    };
    let mut strokes = match param(state, node, "strokes") {
        Some(ParamValue::Text(t)) => t,
        _ => String::new(),
    };
    let dab = hatchery_data::paint::Dab {
        center: at,
        radius,
        id,
    };
    if !strokes.trim().is_empty() {
        strokes.push_str("; ");
    }
    strokes.push_str(&hatchery_data::paint::format_dabs(&[dab]));
    state.set_params(
        node,
        &[("strokes", ParamValue::Text(strokes))],
        "viewport paint",
    )?;
    Ok(radius)
}
