//! The context nodes execute in: the GPU, the frame size, cached pipelines, GPU timing.

use hatchery_gpu::{GpuContext, GpuError, GpuTimer};
use hatchery_graph::{ExecContext, NodeError};
use std::any::Any;
use std::collections::{BTreeMap, HashMap};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

/// The image file at `path`, read through [`hatchery_data::files`] (in the browser: a file the
/// page fetched), its format told by the name's ending as `image::open` tells it.
pub(crate) fn read_image(path: &Path) -> image::ImageResult<image::DynamicImage> {
    let bytes = hatchery_data::files::read(path).map_err(image::ImageError::IoError)?;
    image::load_from_memory_with_format(&bytes, image::ImageFormat::from_path(path)?)
}

pub struct RenderContext {
    pub gpu: GpuContext,
    width: u32,
    height: u32,
    /// Rendered pixels per pixel of the designed figure (see [`Self::set_pixel_scale`]).
    pixel_scale: f64,
    timer: Option<GpuTimer>,
    /// The node executing now (its submissions are timed under its id).
    current_node: Option<String>,
    /// Pipelines and other static GPU objects, built once per kind (not per execution).
    statics: HashMap<String, Arc<dyn Any + Send + Sync>>,
    /// Data a node derived from its parameters and keeps for its next run, one value per
    /// (node, slot), with the hash of what it was derived from (see [`Self::keep`]).
    kept: HashMap<String, (u64, Arc<dyn Any + Send + Sync>)>,
    /// The last execution's warning of each node that gave one (a constant volume, an iso value
    /// with no surface): shown on stderr and on the node in the editor.
    warnings: BTreeMap<String, String>,
    /// Data-relative parameters as the last execution of each node resolved them:
    /// node → parameter → "percentile(60) = 80" (the editor shows them).
    resolved: BTreeMap<String, BTreeMap<String, String>>,
    /// Fused image-space passes as fragment shaders or compute kernels (crate::fused_pass).
    image_kernel: crate::kernel::Kernel,
    /// Graph inputs given as data in memory, by key (see [`crate::memory_inputs`]).
    memory: HashMap<String, crate::memory_inputs::InputData>,
    /// Render streamed volumes from their preview level where the view's region is not read
    /// yet, noting the nodes that did (an interactive view's coarse first frame).
    coarse_first: bool,
    coarse_nodes: Vec<String>,
    /// Where passes report what they do and learn that they are no longer wanted.
    progress: Option<Arc<crate::progress::Progress>>,
}

impl RenderContext {
    pub fn new(gpu: GpuContext, width: u32, height: u32) -> Result<Self, GpuError> {
        gpu.check_2d_size("the frame", width, height)?;
        Ok(Self {
            width,
            height,
            pixel_scale: 1.0,
            timer: None,
            current_node: None,
            statics: HashMap::new(),
            kept: HashMap::new(),
            warnings: BTreeMap::new(),
            resolved: BTreeMap::new(),
            memory: HashMap::new(),
            coarse_first: false,
            coarse_nodes: Vec::new(),
            progress: None,
            image_kernel: crate::kernel::Kernel::choose(
                std::env::var("HATCHERY_IMAGE_KERNEL")
                    .ok()
                    .and_then(|k| crate::kernel::KernelChoice::from_name(&k))
                    .unwrap_or(crate::kernel::KernelChoice::Auto),
                &gpu,
            ),
            gpu,
        })
    }

    /// How fused image-space passes run: by default as fragment shaders, except on adapters
    /// whose graphics pipeline is a small part of the chip (as the ray caster's `auto`);
    /// `HATCHERY_IMAGE_KERNEL=fragment|compute` chooses (for measuring both on one machine).
    pub fn image_kernel(&self) -> crate::kernel::Kernel {
        self.image_kernel
    }

    /// Overrides [`Self::image_kernel`] (tests compare both paths on one adapter).
    pub fn set_image_kernel(&mut self, kernel: crate::kernel::Kernel) {
        self.image_kernel = kernel;
    }

    /// Whether ray casters render a streamed volume's preview level when the region a view
    /// needs has not been read yet (the editor: a coarse first frame, refined by the next pass
    /// with this off). Off by default: `render` waits for the region.
    pub fn set_coarse_first(&mut self, on: bool) {
        self.coarse_first = on;
    }

    pub fn coarse_first(&self) -> bool {
        self.coarse_first
    }

    /// Notes that the executing node rendered a coarser level than its view needs.
    pub fn note_coarse(&mut self) {
        if let Some(node) = self.current_node.clone() {
            self.coarse_nodes.push(node);
        }
    }

    /// The nodes that rendered coarse since the last [`Self::take_coarse_nodes`].
    pub fn coarse_nodes(&self) -> &[String] {
        &self.coarse_nodes
    }

    /// The nodes that rendered coarse since the last call (to re-run for the refined frame).
    pub fn take_coarse_nodes(&mut self) -> Vec<String> {
        std::mem::take(&mut self.coarse_nodes)
    }

    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The id of the node executing now (None between executions).
    pub fn current_node(&self) -> Option<&str> {
        self.current_node.as_deref()
    }

    pub fn set_size(&mut self, width: u32, height: u32) -> Result<(), GpuError> {
        self.gpu.check_2d_size("the frame", width, height)?;
        self.width = width;
        self.height = height;
        Ok(())
    }

    /// Reports each pass's steps to `progress` and stops a pass between steps once it is
    /// cancelled there (the editor's render thread: a newer edit supersedes a long render).
    /// Each node's GPU work is then waited for before the next starts.
    pub fn set_progress(&mut self, progress: Arc<crate::progress::Progress>) {
        self.progress = Some(progress);
    }

    /// Renders the figure as designed at `scale` times its resolution: every parameter that
    /// is a length in pixels (hatching cells, line widths, label sizes; `unit(pixels)` in its
    /// declaration) is multiplied by `scale` (> 0; 1 = as written). The frame size is set
    /// separately ([`Self::set_size`]): `hatchery render --scale 2` doubles both.
    pub fn set_pixel_scale(&mut self, scale: f64) {
        debug_assert!(scale.is_finite() && scale > 0.0);
        self.pixel_scale = scale;
    }

    pub fn pixel_scale(&self) -> f64 {
        self.pixel_scale
    }

    /// A value the executing node derives from its parameters (a pre-integration table), kept
    /// for its next run: `build` runs only when `key` — a hash of what the value depends on —
    /// differs from the kept one's, which is then dropped, so a slot holds one value however
    /// often the parameters change (unlike [`Self::cached`], which keeps every key).
    pub fn keep<T: Any + Send + Sync>(
        &mut self,
        slot: &str,
        key: u64,
        build: impl FnOnce() -> T,
    ) -> Arc<T> {
        let slot = format!(
            "{}.{slot}",
            self.current_node.as_deref().unwrap_or_default()
        );
        if let Some((kept_key, value)) = self.kept.get(&slot)
            && *kept_key == key
            && let Ok(value) = value.clone().downcast::<T>()
        {
            return value;
        }
        let value = Arc::new(build());
        self.kept.insert(slot, (key, value.clone()));
        value
    }

    /// A warning about the executing node's result: one line on stderr (through `tracing`),
    /// kept until the node runs again (see [`Self::warnings`]).
    pub fn warn(&mut self, message: impl Into<String>) {
        let message = message.into();
        let node = self.current_node.clone().unwrap_or_default();
        tracing::warn!("{node}: {message}");
        self.warnings.insert(node, message);
    }

    /// Records how the executing node resolved a data-relative parameter.
    pub fn note_resolved(&mut self, param: &str, text: String) {
        let node = self.current_node.clone().unwrap_or_default();
        self.resolved
            .entry(node)
            .or_default()
            .insert(param.to_owned(), text);
    }

    /// Resolved data-relative parameters by node id, from each node's last execution.
    pub fn resolved(&self) -> &BTreeMap<String, BTreeMap<String, String>> {
        &self.resolved
    }

    /// The in-memory data a parameter's text names, when it is a key (`memory:NAME#N`).
    pub fn memory(&self, text: &str) -> Option<&crate::memory_inputs::InputData> {
        self.memory.get(text)
    }

    /// Keeps `data` under `key`, dropping what was kept under keys starting with `drop_prefix`
    /// (the input's earlier data).
    pub fn put_memory(
        &mut self,
        key: String,
        data: crate::memory_inputs::InputData,
        drop_prefix: &str,
    ) {
        self.memory.retain(|k, _| !k.starts_with(drop_prefix));
        self.memory.insert(key, data);
    }

    /// Drops the in-memory data under keys starting with `prefix`.
    pub fn drop_memory(&mut self, prefix: &str) {
        self.memory.retain(|k, _| !k.starts_with(prefix));
    }

    /// Warnings by node id, from each node's last execution.
    pub fn warnings(&self) -> &BTreeMap<String, String> {
        &self.warnings
    }

    /// Turns per-node GPU timestamps on (where the adapter has them). Returns whether they are on.
    pub fn enable_gpu_timing(&mut self) -> bool {
        if self.timer.is_none() {
            self.timer = GpuTimer::new(&self.gpu, 512);
        }
        self.timer.is_some()
    }

    /// Submits a node's GPU work (timed when GPU timing is on). Nodes submit through this.
    pub fn submit(&mut self, work: wgpu::CommandBuffer) {
        match (&mut self.timer, &self.current_node) {
            (Some(timer), Some(node)) => timer.submit(&self.gpu, node, work),
            _ => {
                self.gpu.queue.submit([work]);
            }
        }
    }

    /// A 1×1 white texture, bound where a shader's optional texture is unused.
    pub fn blank_texture(&mut self) -> wgpu::Texture {
        let texture = self
            .cached("blank_texture", |gpu| {
                let texture = gpu.render_target("blank", 1, 1, wgpu::TextureFormat::Rgba8Unorm);
                gpu.queue.write_texture(
                    texture.as_image_copy(),
                    &[255, 255, 255, 255],
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(4),
                        rows_per_image: None,
                    },
                    wgpu::Extent3d {
                        width: 1,
                        height: 1,
                        depth_or_array_layers: 1,
                    },
                );
                Ok(texture)
            })
            .expect("creating a 1×1 texture cannot fail validation");
        (*texture).clone()
    }

    /// An image file as an Rgba8Unorm texture, read once per path and modification time.
    /// Errors: the file cannot be read or decoded, or is larger than the GPU allows.
    pub fn file_texture(&mut self, path: &Path) -> Result<wgpu::Texture, NodeError> {
        let modified = match std::fs::metadata(path).and_then(|m| m.modified()) {
            Ok(time) => Some(time),
            // The browser has no file system: a file the page mounted is read once.
            Err(_) if hatchery_data::files::is_file(path) => None,
            Err(e) => {
                return Err(NodeError::new(format!(
                    "cannot read {}: {e}",
                    path.display()
                )));
            }
        };
        let key = format!("file_texture:{}:{modified:?}", path.display());
        let texture = self
            .cached(&key, |gpu| {
                let picture = read_image(path)
                    .map_err(|e| GpuError::Validation {
                        what: format!("{}", path.display()),
                        message: e.to_string(),
                    })?
                    .to_rgba8();
                let (w, h) = picture.dimensions();
                gpu.check_2d_size(&path.display().to_string(), w, h)?;
                let texture =
                    gpu.render_target("file texture", w, h, wgpu::TextureFormat::Rgba8Unorm);
                gpu.queue.write_texture(
                    texture.as_image_copy(),
                    picture.as_raw(),
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(4 * w),
                        rows_per_image: None,
                    },
                    wgpu::Extent3d {
                        width: w,
                        height: h,
                        depth_or_array_layers: 1,
                    },
                );
                Ok(texture)
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok((*texture).clone())
    }

    /// A static GPU object (pipeline, layout, sampler) built once under `key`.
    pub fn cached<T: Any + Send + Sync>(
        &mut self,
        key: &str,
        build: impl FnOnce(&GpuContext) -> Result<T, GpuError>,
    ) -> Result<Arc<T>, GpuError> {
        if let Some(existing) = self
            .statics
            .get(key)
            .and_then(|v| v.clone().downcast::<T>().ok())
        {
            return Ok(existing);
        }
        let built = Arc::new(build(&self.gpu)?);
        self.statics.insert(key.to_owned(), built.clone());
        Ok(built)
    }
}

impl ExecContext for RenderContext {
    fn frame_key(&self) -> u64 {
        let mut h = DefaultHasher::new();
        (self.width, self.height).hash(&mut h);
        h.finish()
    }
    fn pixel_scale(&self) -> f64 {
        self.pixel_scale
    }
    fn begin_pass(&mut self, planned: &[&str]) {
        if let Some(progress) = &self.progress {
            progress.begin_pass(planned);
        }
    }
    fn cancelled(&self) -> bool {
        self.progress.as_ref().is_some_and(|p| p.is_cancelled())
    }
    fn begin_node(&mut self, node: &str) {
        if let Some(progress) = &self.progress {
            progress.begin_node(node);
        }
        self.current_node = Some(node.to_owned());
        self.warnings.remove(node);
        self.resolved.remove(node);
    }
    fn end_node(&mut self, node: &str) {
        if let Some(progress) = &self.progress {
            // Submitted GPU work runs after `execute` returns: wait for it, so the node shown
            // running is the one the GPU works on and a cancel takes effect after it (the
            // editor only; it costs the overlap of recording the next node with this one's
            // GPU work).
            self.gpu.wait_idle();
            progress.end_node(node);
        }
        self.current_node = None;
    }
    fn finish_pass(&mut self) -> Vec<(String, Duration)> {
        match &mut self.timer {
            Some(timer) => timer.finish(&self.gpu),
            None => Vec::new(),
        }
    }
}
