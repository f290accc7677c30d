//! hatchery in the browser: a figure folder written by `hatchery export-web` (docs/web.md) opened
//! on a page's `<canvas>` and rendered with WebGPU by the same node library as the native build.
//!
//! The page (index.html of the export) calls [`Figure::open`] with the canvas and the URL of the
//! folder's `figure.json`, then [`Figure::render`] whenever the view or a control changed. The
//! whole graph runs in the page's one thread: the executor re-runs only the nodes a change
//! reaches, as natively. Nothing is read back from the GPU; the picture is drawn on the canvas
//! by the editor's display pass (the pixels a PNG export writes, over a checkerboard where the
//! figure is transparent).
#![cfg(target_arch = "wasm32")]

mod controls;
mod fetch;
mod orbit;

use std::path::Path;

use hatchery_gpu::GpuContext;
use hatchery_graph::{Graph, GraphDocument};
use hatchery_nodes::{Session, Value, registry};
use serde::Deserialize;
use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

/// `figure.json` of an exported folder: what to fetch and at which size to render.
#[derive(Deserialize)]
struct Manifest {
    /// The graph file, relative to the folder.
    graph: String,
    width: u32,
    height: u32,
    /// Rendered pixels per pixel of the designed figure (`export-web --scale`).
    #[serde(default = "one")]
    scale: f64,
    /// Data files the graph reads, relative to the folder (their paths as the graph names them).
    #[serde(default)]
    files: Vec<String>,
}

/// Where files dropped on the page are mounted.
const DROPPED: &str = "dropped";

fn one() -> f64 {
    1.0
}

/// Every shader program of the node library as `[{name, source}]` JSON, for the browser test
/// (tests/web/check.mjs) to compile with the browser's own WGSL compiler, which is stricter than
/// naga in places (operator precedence, uniformity).
#[wasm_bindgen]
pub fn shader_programs() -> String {
    let programs: Vec<serde_json::Value> = hatchery_nodes::kinds::programs()
        .iter()
        .map(|(name, _)| {
            serde_json::json!({
                "name": name,
                "source": hatchery_nodes::kinds::source(name).unwrap_or_default(),
            })
        })
        .collect();
    serde_json::Value::Array(programs).to_string()
}

/// An open figure: its graph session on the page's device and the canvas it draws on.
#[wasm_bindgen]
pub struct Figure {
    session: Session,
    surface: wgpu::Surface<'static>,
    /// The node and port whose picture is shown (what the graph's SaveImage writes).
    picture: (String, String),
    orbit: orbit::Orbit,
}

fn js_error(what: impl std::fmt::Display) -> JsError {
    JsError::new(&what.to_string())
}

#[wasm_bindgen]
impl Figure {
    /// Fetches `manifest_url` (an export's figure.json), its graph and data files, opens a WebGPU
    /// device for `canvas` and validates the graph. Errors (one line each): no WebGPU, a file
    /// that cannot be fetched, a graph error naming the file, line and node.
    pub async fn open(canvas: HtmlCanvasElement, manifest_url: String) -> Result<Figure, JsError> {
        console_error_panic_hook::set_once();
        let manifest: Manifest = serde_json::from_str(&fetch::text(&manifest_url).await?)
            .map_err(|e| js_error(format!("{manifest_url}: {e}")))?;
        if !(1..=16384).contains(&manifest.width) || !(1..=16384).contains(&manifest.height) {
            return Err(js_error(format!(
                "{manifest_url}: a frame of {}×{} pixels (1 to 16384 per side)",
                manifest.width, manifest.height
            )));
        }
        let base = fetch::folder_of(&manifest_url);
        for file in &manifest.files {
            let bytes = fetch::bytes(&format!("{base}{}", fetch::encode_path(file))).await?;
            hatchery_data::files::mount(Path::new(file), bytes);
        }
        let graph_text =
            fetch::text(&format!("{base}{}", fetch::encode_path(&manifest.graph))).await?;

        canvas.set_width(manifest.width);
        canvas.set_height(manifest.height);
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::BROWSER_WEBGPU;
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
            .map_err(|e| js_error(format!("this browser gives no WebGPU canvas: {e}")))?;
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: Some(&surface),
                apply_limit_buckets: false,
            })
            .await
            .map_err(|e| js_error(format!("this browser gives no WebGPU adapter: {e}")))?;
        let gpu = GpuContext::from_adapter_async(&adapter)
            .await
            .map_err(js_error)?;
        surface.configure(
            &gpu.device,
            &wgpu::SurfaceConfiguration {
                usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::RENDER_ATTACHMENT,
                format: hatchery_nodes::display::DISPLAY_FORMAT,
                width: manifest.width,
                height: manifest.height,
                present_mode: wgpu::PresentMode::Fifo,
                desired_maximum_frame_latency: 2,
                alpha_mode: wgpu::CompositeAlphaMode::Opaque,
                view_formats: vec![],
                color_space: Default::default(),
            },
        );

        let registry = registry();
        let path = Path::new(&manifest.graph);
        let (doc, source) = GraphDocument::parse(&graph_text, Some(path)).map_err(js_error)?;
        let graph = Graph::from_document(&doc, &source, &registry, Some(Path::new("")))
            .map_err(js_error)?;
        let orbit = orbit::Orbit::of(&graph);
        let mut session = Session::with_gpu(registry, graph, gpu, manifest.width, manifest.height)
            .map_err(js_error)?;
        session.ctx.set_pixel_scale(manifest.scale);
        let picture = session.picture_port(None, None).map_err(js_error)?;
        Ok(Figure {
            session,
            surface,
            picture,
            orbit,
        })
    }

    /// Starts a new picture: read-backs of the last one are forgotten (see [`Self::render`]).
    pub fn begin(&mut self) {
        self.session.ctx.gpu.forget_readbacks();
    }

    /// Runs what changed since the last picture and draws it on the canvas; `true` when drawn.
    /// `false`: a node reads GPU results back (AnnotationLayout), which in the browser arrive
    /// between passes: await [`Self::settle`] and call this again (hatchery_gpu::web_readback).
    /// Errors: a node that failed (one line naming it), e.g. one that cannot run in the browser.
    pub fn render(&mut self) -> Result<bool, JsError> {
        let (node, port) = self.picture.clone();
        let value = match self.session.evaluate(&node, &port) {
            Ok(value) => value,
            Err(_) if self.session.ctx.gpu.readbacks_pending() => return Ok(false),
            Err(e) => return Err(js_error(e)),
        };
        if !matches!(value, Value::Image(_) | Value::Mask(_) | Value::GBuffer(_)) {
            return Err(js_error(format!(
                "{node}.{port} is a {} value, not a picture",
                value.port_type()
            )));
        }
        let (width, height) = self.session.ctx.size();
        let shown = hatchery_nodes::display::display_texture(
            &mut self.session.ctx,
            &value,
            (width, height),
        )
        .map_err(js_error)?;
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            other => {
                return Err(js_error(format!(
                    "the canvas gave no frame ({:?}); render again",
                    std::mem::discriminant(&other)
                )));
            }
        };
        let gpu = &self.session.ctx.gpu;
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_texture(
            shown.as_image_copy(),
            frame.texture.as_image_copy(),
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit([encoder.finish()]);
        gpu.queue.present(frame);
        Ok(true)
    }

    /// Resolves once the read-backs the last [`Self::render`] asked for have arrived. Errors: a
    /// failed mapping (a lost device).
    pub fn settle(&self) -> js_sys::Promise {
        let gpu = self.session.ctx.gpu.clone();
        wasm_bindgen_futures::future_to_promise(async move {
            while !gpu
                .collect_readbacks()
                .map_err(|e| JsValue::from(js_error(e)))?
            {
                fetch::sleep_ms(1).await?;
            }
            Ok(JsValue::UNDEFINED)
        })
    }

    /// GPU errors reported since the last call (WebGPU reports them after the pass), joined on
    /// one line; empty when there were none.
    pub fn gpu_errors(&mut self) -> String {
        let errors = self.session.ctx.gpu.take_uncaptured_errors();
        if !errors.is_empty() {
            self.session.executor.clear();
        }
        errors.join(" | ")
    }

    /// Turns the view: `dx`, `dy` in CSS pixels of a drag (a drag across the canvas's width
    /// turns it by 180°). Every Camera node of the graph turns alike.
    pub fn drag(&mut self, dx: f64, dy: f64) -> Result<(), JsError> {
        let (width, _) = self.session.ctx.size();
        self.orbit
            .drag(&mut self.session, dx, dy, width)
            .map_err(js_error)
    }

    /// Moves the view closer (`steps` > 0, one wheel notch = 1) or away.
    pub fn zoom(&mut self, steps: f64) -> Result<(), JsError> {
        self.orbit.zoom(&mut self.session, steps).map_err(js_error)
    }

    /// The graph's controls (its `controls` section) as JSON: `[{node, param, label, type, value,
    /// min, max, choices}]`, for the page to build its sliders, toggles and menus.
    pub fn controls(&self) -> String {
        controls::describe(&self.session)
    }

    /// Sets `node.param` from text as `hatchery render --set` takes it. Errors: a value out of
    /// range or of the wrong type, naming the parameter.
    pub fn set(&mut self, node: &str, param: &str, text: &str) -> Result<(), JsError> {
        self.session
            .set_param_text(node, param, text)
            .map_err(js_error)
    }

    /// Shows `node.port` instead (its first output when `port` is empty): a look inside the
    /// graph, as the editor's viewport gives. Errors: no such node or port.
    pub fn show(&mut self, node: &str, port: &str) -> Result<(), JsError> {
        let port = (!port.is_empty()).then_some(port);
        self.picture = self
            .session
            .picture_port(Some(node), port)
            .map_err(js_error)?;
        Ok(())
    }

    /// The graph's inputs (the data files it reads, by name) as JSON `[{name, type, doc}]`: the
    /// page offers to replace them with files dropped on it.
    pub fn inputs(&self) -> String {
        let inputs: Vec<serde_json::Value> = self
            .session
            .graph
            .inputs()
            .iter()
            .map(|i| serde_json::json!({ "name": i.name, "type": i.kind.name(), "doc": i.doc }))
            .collect();
        serde_json::Value::Array(inputs).to_string()
    }

    /// The graph input a file named `file_name` goes to when dropped on the figure (the first
    /// input of its kind: a volume file to a volume input, else to a label map's; a mesh, a
    /// names table likewise); `undefined` where no input takes its kind.
    pub fn input_for(&self, file_name: &str) -> Option<String> {
        hatchery_nodes::graph_inputs::input_for(self.session.graph.inputs(), Path::new(file_name))
            .map(str::to_owned)
    }

    /// Makes `bytes` the file `dropped/<file_name>` (a file dropped on the page, or a companion
    /// of one: a MetaImage's voxels beside its header).
    pub fn mount(&mut self, file_name: &str, bytes: Vec<u8>) {
        hatchery_data::files::mount(&Path::new(DROPPED).join(file_name), bytes);
    }

    /// Gives graph input `name` the mounted file `file_name` (see [`Self::mount`]). Errors: no
    /// such input, or a file of another kind (a mesh for a volume), in one line.
    pub fn set_input(&mut self, name: &str, file_name: &str) -> Result<(), JsError> {
        self.session
            .set_input(name, &Path::new(DROPPED).join(file_name))
            .map_err(js_error)
    }

    /// The adapter, for the page's status line.
    pub fn adapter(&self) -> String {
        let info = &self.session.ctx.gpu.adapter_info;
        if info.name.is_empty() {
            // Browsers keep the adapter's name to themselves unless asked.
            format!("WebGPU ({:?} adapter)", info.device_type)
        } else {
            format!("WebGPU on {}", info.name)
        }
    }
}
