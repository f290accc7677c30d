//! The viewport and the pin thumbnails: what to render (asked of the [`RenderWorker`] whenever
//! the document, the viewport size, the shown port or the pinned ports change) and the egui
//! textures showing the answers. On the window's device the worker's textures are registered
//! with egui-wgpu as they are; otherwise their pixels are uploaded as egui textures.

use crate::render_worker::{NodeTime, Picture, Port, RenderWorker, Rendered, Request};
use crate::state::EditorState;
use eframe::egui_wgpu;
use hatchery_gpu::{GpuContext, wgpu};
use hatchery_graph::GraphDocument;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Duration;

/// Largest thumbnail on a node, in pixels.
pub const THUMBNAIL_BOUND: (u32, u32) = (160, 120);

/// A picture egui can draw.
pub enum Shown {
    /// A texture on the window's device, registered with egui-wgpu (no copy).
    Native {
        id: egui::TextureId,
        size: [u32; 2],
        /// Kept alive while egui draws it.
        _texture: wgpu::Texture,
    },
    /// Pixels uploaded as an egui texture.
    Managed(egui::TextureHandle),
}

impl Shown {
    pub fn id(&self) -> egui::TextureId {
        match self {
            Shown::Native { id, .. } => *id,
            Shown::Managed(handle) => handle.id(),
        }
    }
    /// Size in pixels.
    pub fn size(&self) -> [u32; 2] {
        match self {
            Shown::Native { size, .. } => *size,
            Shown::Managed(handle) => {
                let [w, h] = handle.size();
                [w as u32, h as u32]
            }
        }
    }
    pub fn is_native(&self) -> bool {
        matches!(self, Shown::Native { .. })
    }
}

/// What a request was made for; a new request goes out when this changes.
#[derive(Clone, PartialEq)]
struct Key {
    revision: u64,
    size: (u32, u32),
    viewport: Option<Port>,
    pins: Vec<Port>,
    timing: bool,
    depth: Vec<Port>,
}

#[derive(Default)]
pub struct Preview {
    /// The port shown; `None` = the input of the graph's first `SaveImage` node.
    pub chosen: Option<Port>,
    /// Ports whose thumbnails are shown on their nodes.
    pub pins: BTreeSet<Port>,
    /// Show per-node times on the nodes (and measure GPU times).
    pub show_times: bool,
    /// The window's wgpu state, when the editor runs on eframe's wgpu renderer.
    render_state: Option<egui_wgpu::RenderState>,
    /// Render on the window's device so pictures are shown without copies.
    share_device: bool,
    worker: Option<RenderWorker>,
    next_id: u64,
    sent: Option<Key>,
    /// The request whose answer has not arrived yet.
    awaiting: Option<u64>,
    /// The picture shown is a streamed volume's preview level; the refined one is on its way.
    pub refining: bool,
    pub viewport: Option<Shown>,
    pub thumbnails: BTreeMap<Port, Shown>,
    /// Pinned ports that have no picture, and why (a mesh, a camera, a failed node).
    pub thumbnail_errors: BTreeMap<Port, String>,
    /// Why the last render (or the last thumbnail) failed.
    pub error: Option<String>,
    /// The node whose execution failed, with the message (shown on the node).
    pub failed_node: Option<(String, String)>,
    pub times: BTreeMap<String, NodeTime>,
    /// Warnings by node from the last answer.
    pub warnings: BTreeMap<String, String>,
    /// Data-relative parameters as the last render resolved them (node → parameter → text).
    pub resolved: BTreeMap<String, BTreeMap<String, String>>,
    /// Value ranges of the evaluated `TransferFunction1D` nodes.
    pub tf_domains: BTreeMap<String, [f32; 2]>,
    /// The objects of each node with a `labels` output, from the last render.
    pub object_names: BTreeMap<String, Vec<(u16, String)>>,
    /// Wall time of the last answered request on the render thread, and the adapter.
    pub last_render: Option<(Duration, String)>,
    /// How many answers have been shown (tests wait on this).
    pub answers: u64,
    /// The viewport's paint tool is on: answers carry the depth of the picture's surfaces.
    pub paint: bool,
    /// The nearest surface of the last picture, while the paint tool is on.
    pub depth: Option<crate::paint::DepthMap>,
}

/// The port feeding the first `SaveImage` node (by id order).
pub fn default_target(doc: &GraphDocument) -> Option<Port> {
    let mut saves: Vec<&str> = doc
        .nodes
        .iter()
        .filter(|n| n.kind == "SaveImage")
        .map(|n| n.id.as_str())
        .collect();
    saves.sort_unstable();
    saves.iter().find_map(|id| {
        doc.edges
            .iter()
            .find(|e| e.to.0 == *id && e.to.1 == "image")
            .map(|e| e.from.clone())
    })
}

/// Whether the worker should share the window's device. Lavapipe runs a device's submissions
/// one after another, so on a CPU adapter a long ray cast on the shared queue would hold up the
/// window's own frames: there the worker gets a device of its own unless
/// `HATCHERY_EDITOR_SHARED_DEVICE=1` says otherwise (`=0` forces a separate device anywhere).
pub fn share_device_by_default(adapter: &wgpu::AdapterInfo) -> bool {
    match std::env::var("HATCHERY_EDITOR_SHARED_DEVICE").as_deref() {
        Ok("1") => true,
        Ok("0") => false,
        _ => adapter.device_type != wgpu::DeviceType::Cpu,
    }
}

impl Preview {
    /// Uses the window's wgpu state; `share_device` renders on its device (zero-copy display).
    pub fn set_render_state(&mut self, render_state: egui_wgpu::RenderState, share_device: bool) {
        self.render_state = Some(render_state);
        self.share_device = share_device;
        self.worker = None;
    }

    /// Whether the worker renders on the window's device.
    pub fn shares_device(&self) -> bool {
        self.worker.as_ref().is_some_and(|w| w.shared_device)
    }

    /// The port that will be rendered.
    pub fn target(&self, doc: &GraphDocument) -> Option<Port> {
        self.chosen
            .clone()
            .filter(|(n, _)| doc.nodes.iter().any(|m| &m.id == n))
            .or_else(|| default_target(doc))
    }

    /// A request is out and its answer has not been shown yet.
    pub fn is_busy(&self) -> bool {
        self.awaiting.is_some()
    }

    /// Shows any answer that arrived, then asks for a new render if the document, the size,
    /// the shown port or the pins changed. Never blocks on rendering and never panics on a bad
    /// graph: failures land in `error` and on the failing node.
    pub fn update(
        &mut self,
        ctx: &egui::Context,
        state: &mut EditorState,
        width: u32,
        height: u32,
    ) {
        if let Some(answer) = self.worker.as_ref().and_then(RenderWorker::newest) {
            self.show(ctx, answer);
        }
        let size = (width.clamp(16, 4096), height.clamp(16, 4096));
        let doc = state.doc();
        // Pins of removed nodes go away with them.
        self.pins
            .retain(|(n, _)| doc.nodes.iter().any(|m| &m.id == n));
        let viewport = self.target(doc);
        let depth = match (&viewport, self.paint) {
            (Some(shown), true) => crate::paint::depth_sources(state, shown),
            _ => Vec::new(),
        };
        let key = Key {
            revision: state.revision(),
            size,
            viewport,
            pins: self.pins.iter().cloned().collect(),
            timing: self.show_times,
            depth,
        };
        if self.sent.as_ref() == Some(&key) {
            return;
        }
        self.sent = Some(key.clone());
        if key.viewport.is_none() && key.pins.is_empty() {
            self.error = Some("nothing to preview: connect a SaveImage or pick an output".into());
            return;
        }
        let Some(graph) = state.validate() else {
            self.error = Some("the graph has errors (see the nodes)".into());
            return;
        };
        if let Err(e) = self.ensure_worker(ctx) {
            self.error = Some(e);
            return;
        }
        self.next_id += 1;
        let request = Request {
            id: self.next_id,
            graph,
            size,
            viewport: key.viewport,
            thumbnails: key.pins,
            thumbnail_bound: THUMBNAIL_BOUND,
            timing: key.timing,
            depth: key.depth,
        };
        match self.worker.as_ref().map(|w| w.send(request)) {
            Some(Ok(())) => self.awaiting = Some(self.next_id),
            Some(Err(e)) => {
                // The thread ended (it should not): start a new one next time.
                self.worker = None;
                self.sent = None;
                self.error = Some(e);
            }
            None => {}
        }
    }

    /// While a render is on its way: how long it has been running and its current pass
    /// (the node running, the steps planned and done).
    pub fn progress(&self) -> Option<(Duration, hatchery_nodes::progress::PassProgress)> {
        if !self.is_busy() {
            return None;
        }
        self.worker.as_ref()?.progress()
    }

    fn ensure_worker(&mut self, ctx: &egui::Context) -> Result<(), String> {
        if self.worker.is_some() {
            return Ok(());
        }
        let gpu = match (&self.render_state, self.share_device) {
            (Some(rs), true) => Some(GpuContext::from_device(
                rs.adapter.get_info(),
                rs.device.clone(),
                rs.queue.clone(),
            )),
            _ => None,
        };
        let worker = RenderWorker::spawn(gpu, ctx.clone())
            .map_err(|e| format!("cannot start the render thread: {e}"))?;
        self.worker = Some(worker);
        Ok(())
    }

    fn show(&mut self, ctx: &egui::Context, answer: Rendered) {
        // A coarse first frame keeps the request out: its refined answer follows.
        self.refining = !answer.refining.is_empty();
        if self.awaiting == Some(answer.id) && !self.refining {
            self.awaiting = None;
        }
        self.answers += 1;
        self.failed_node = answer.failed_node;
        self.times = answer.times;
        self.warnings = answer.warnings;
        self.resolved.extend(answer.resolved);
        self.tf_domains.extend(answer.tf_domains);
        self.object_names.extend(answer.object_names);
        self.last_render = Some((answer.elapsed, answer.adapter));
        self.depth = answer.depth;
        self.error = None;
        match answer.viewport {
            Some(Ok(picture)) => {
                let old = self.viewport.take();
                match self.install(ctx, old, picture, "viewport") {
                    Ok(shown) => self.viewport = Some(shown),
                    Err(e) => self.error = Some(e),
                }
            }
            Some(Err(e)) => self.error = Some(e),
            None => {}
        }
        let mut kept = BTreeMap::new();
        self.thumbnail_errors.clear();
        for (port, result) in answer.thumbnails {
            let old = self.thumbnails.remove(&port);
            match result {
                Ok(picture) => {
                    let name = format!("thumbnail {}.{}", port.0, port.1);
                    match self.install(ctx, old, picture, &name) {
                        Ok(shown) => {
                            kept.insert(port, shown);
                        }
                        Err(e) => {
                            self.error.get_or_insert(e);
                        }
                    }
                }
                Err(e) => {
                    self.release(old);
                    self.thumbnail_errors.insert(port, e);
                }
            }
        }
        // Thumbnails no longer pinned.
        for (_, old) in std::mem::replace(&mut self.thumbnails, kept) {
            self.release(Some(old));
        }
    }

    /// Shows `picture` in place of `old` (reusing its texture id where it can).
    fn install(
        &mut self,
        ctx: &egui::Context,
        old: Option<Shown>,
        picture: Picture,
        name: &str,
    ) -> Result<Shown, String> {
        Ok(match picture {
            Picture::Texture(texture) => {
                let Some(rs) = &self.render_state else {
                    return Err("a texture came back without a window device to show it".into());
                };
                let view = texture.create_view(&Default::default());
                let size = [texture.width(), texture.height()];
                let mut renderer = rs.renderer.write();
                let id = match old {
                    Some(Shown::Native { id, .. }) => {
                        renderer.update_egui_texture_from_wgpu_texture(
                            &rs.device,
                            &view,
                            wgpu::FilterMode::Linear,
                            id,
                        );
                        id
                    }
                    _ => renderer.register_native_texture(
                        &rs.device,
                        &view,
                        wgpu::FilterMode::Linear,
                    ),
                };
                Shown::Native {
                    id,
                    size,
                    _texture: texture,
                }
            }
            Picture::Pixels(pixels) => {
                let color = egui::ColorImage::from_rgba_premultiplied(
                    [pixels.width() as usize, pixels.height() as usize],
                    pixels.as_raw(),
                );
                match old {
                    Some(Shown::Managed(mut handle)) => {
                        handle.set(color, egui::TextureOptions::LINEAR);
                        Shown::Managed(handle)
                    }
                    other => {
                        self.release(other);
                        Shown::Managed(ctx.load_texture(name, color, egui::TextureOptions::LINEAR))
                    }
                }
            }
        })
    }

    /// Frees a picture's texture (egui frees managed ones when their handle drops).
    fn release(&self, shown: Option<Shown>) {
        if let (Some(Shown::Native { id, .. }), Some(rs)) = (shown, &self.render_state) {
            rs.renderer.write().free_texture(&id);
        }
    }
}
