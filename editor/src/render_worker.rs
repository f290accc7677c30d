//! Rendering off the UI thread. A worker thread owns the executor [`Session`]; the UI sends it
//! the validated graph with the ports to show and gets display pictures back, so the UI keeps
//! drawing while a frame renders. Only the newest request is rendered: a slider drag does not
//! queue up frames. The executor's cache makes a parameter change re-run only what depends on it.
//!
//! Pictures are display textures (`hatchery_nodes::display`). When the worker renders on the
//! window's own device they are handed to egui-wgpu as they are (no copy); on a device of its own
//! they come back as pixels.

use hatchery_gpu::{GpuContext, wgpu};
use hatchery_graph::Graph;
use hatchery_nodes::progress::{PassProgress, Progress};
use hatchery_nodes::value::TransferFunction;
use hatchery_nodes::{Session, SessionError, Value, display, registry};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::time::{Duration, Instant};

/// An output port: (node id, port name).
pub type Port = (String, String);

/// What to render.
#[derive(Clone)]
pub struct Request {
    /// Increases with every request; the answer carries it back.
    pub id: u64,
    pub graph: Graph,
    /// Frame size in pixels (the viewport's size).
    pub size: (u32, u32),
    /// The port shown in the viewport.
    pub viewport: Option<Port>,
    /// Ports pinned as thumbnails on their nodes, drawn to fit in `thumbnail_bound` pixels.
    pub thumbnails: Vec<Port>,
    pub thumbnail_bound: (u32, u32),
    /// Measure per-node GPU times (timestamp queries) as well as CPU times.
    pub timing: bool,
    /// G-buffer outputs whose depth to read back (the viewport's paint tool picks surfaces
    /// in it); empty when the tool is off.
    pub depth: Vec<Port>,
}

/// A display picture: a texture on the window's device, or pixels from a separate device.
pub enum Picture {
    Texture(wgpu::Texture),
    Pixels(image::RgbaImage),
}

/// How long a node took in the last request, or that its cached output was reused.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeTime {
    pub cpu: Duration,
    pub gpu: Option<Duration>,
    pub cached: bool,
    /// The node whose fused pass this one ran in (that node carries the pass's times).
    pub fused_into: Option<String>,
}

/// The answer to a [`Request`].
pub struct Rendered {
    pub id: u64,
    pub viewport: Option<Result<Picture, String>>,
    pub thumbnails: Vec<(Port, Result<Picture, String>)>,
    /// The node whose execution failed, with the message (shown on the node).
    pub failed_node: Option<(String, String)>,
    pub times: BTreeMap<String, NodeTime>,
    /// Warnings of the nodes the requested ports depend on (a constant volume, no surface).
    pub warnings: BTreeMap<String, String>,
    /// Data-relative parameters as the nodes resolved them: node → parameter → "otsu = 80".
    pub resolved: BTreeMap<String, BTreeMap<String, String>>,
    /// The value range each evaluated transfer function node spans (a `TransferFunction1D`'s
    /// presets follow the connected volume's range, which only the executed graph knows).
    pub tf_domains: BTreeMap<String, [f32; 2]>,
    /// The objects (id, name) of each evaluated node with a `labels` output (for the object
    /// table of ObjectStyles).
    pub object_names: BTreeMap<String, Vec<(u16, String)>>,
    /// Wall time of the whole request on the worker.
    pub elapsed: Duration,
    /// The adapter rendered on (for the times' caption).
    pub adapter: String,
    /// Nodes that drew a streamed volume's preview level: a refined answer follows.
    pub refining: Vec<String>,
    /// The nearest surface of the requested G-buffers (see [`Request::depth`]).
    pub depth: Option<crate::paint::DepthMap>,
}

impl Rendered {
    /// An answer carrying only an error.
    fn failed(id: u64, message: String) -> Self {
        Rendered {
            id,
            viewport: Some(Err(message)),
            thumbnails: Vec::new(),
            failed_node: None,
            times: BTreeMap::new(),
            warnings: BTreeMap::new(),
            resolved: BTreeMap::new(),
            tf_domains: BTreeMap::new(),
            object_names: BTreeMap::new(),
            elapsed: Duration::ZERO,
            adapter: String::new(),
            refining: Vec::new(),
            depth: None,
        }
    }
}

/// A render running this long is cancelled by a newer request (at its next node) instead of
/// finishing a picture nobody wants: long CPU-driver renders of volumes. Shorter ones finish,
/// so a slider drag over a fast graph keeps showing frames.
pub const CANCEL_AFTER: Duration = Duration::from_secs(1);

/// The worker thread's handle. Dropping it ends the thread after its current frame.
pub struct RenderWorker {
    requests: Sender<Request>,
    answers: Receiver<Rendered>,
    /// Whether pictures come back as textures on the window's device.
    pub shared_device: bool,
    /// What the render thread is doing (and its cancel flag).
    progress: Arc<Progress>,
}

impl RenderWorker {
    /// Starts the worker. With `gpu`, it renders on that device (the window's, so pictures are
    /// shown without copies); without, it opens a device of its own. `repaint` is asked to
    /// redraw the UI when a picture is ready.
    pub fn spawn(gpu: Option<GpuContext>, repaint: egui::Context) -> std::io::Result<Self> {
        let (requests, inbox) = channel::<Request>();
        let (outbox, answers) = channel::<Rendered>();
        let shared_device = gpu.is_some();
        // The picture's progress caption is redrawn when a node starts or ends.
        let notify = repaint.clone();
        let progress = Arc::new(Progress::notifying(move || notify.request_repaint()));
        let watched = progress.clone();
        std::thread::Builder::new()
            .name("hatchery-render".into())
            .spawn(move || {
                let mut worker = Worker {
                    gpu,
                    session: None,
                    copy_back: !shared_device,
                    progress: watched,
                };
                // A request to render after a streamed volume's coarse first frame.
                let mut next: Option<Request> = None;
                loop {
                    let mut request = match next.take() {
                        Some(r) => r,
                        None => match inbox.recv() {
                            Ok(r) => r,
                            Err(_) => return,
                        },
                    };
                    // Skip to the newest request: older ones are out of date.
                    loop {
                        match inbox.try_recv() {
                            Ok(newer) => request = newer,
                            Err(TryRecvError::Empty) => break,
                            Err(TryRecvError::Disconnected) => return,
                        }
                    }
                    let again = request.clone();
                    let answer = worker.render_caught(request);
                    if worker.progress.is_cancelled() {
                        // A newer request superseded it (and is in the inbox): no answer;
                        // the nodes that ran stay cached for the newer one.
                        continue;
                    }
                    if outbox.send(answer).is_err() {
                        return;
                    }
                    repaint.request_repaint();
                    // Nodes that drew a streamed volume's preview level because the region
                    // their view needs was not read yet: read it and draw again, unless the
                    // view changed meanwhile (then the newer request comes first).
                    let coarse = worker.take_coarse_nodes();
                    if coarse.is_empty() {
                        continue;
                    }
                    match inbox.try_recv() {
                        Ok(newer) => {
                            next = Some(newer);
                            continue;
                        }
                        Err(TryRecvError::Disconnected) => return,
                        Err(TryRecvError::Empty) => {}
                    }
                    let refined = worker.refine(again, &coarse);
                    if worker.progress.is_cancelled() {
                        continue;
                    }
                    if outbox.send(refined).is_err() {
                        return;
                    }
                    repaint.request_repaint();
                }
            })?;
        Ok(Self {
            requests,
            answers,
            shared_device,
            progress,
        })
    }

    /// What the render thread is doing now: `None` when idle, else how long the request has
    /// been rendering and its current pass.
    pub fn progress(&self) -> Option<(Duration, PassProgress)> {
        let busy = self.progress.busy_for()?;
        Some((busy, self.progress.snapshot()))
    }

    /// Queues a request (the worker drops it if a newer one arrives first). A render running
    /// for [`CANCEL_AFTER`] or longer stops at its next node.
    pub fn send(&self, request: Request) -> Result<(), String> {
        if self
            .progress
            .busy_for()
            .is_some_and(|busy| busy >= CANCEL_AFTER)
        {
            self.progress.cancel();
        }
        self.requests
            .send(request)
            .map_err(|_| "the render thread has stopped".to_owned())
    }

    /// The oldest answer not taken yet, if any (one at a time, unlike [`Self::newest`]).
    pub fn next_answer(&self) -> Option<Rendered> {
        self.answers.try_recv().ok()
    }

    /// The newest answer that arrived since the last call, if any.
    pub fn newest(&self) -> Option<Rendered> {
        let mut newest = None;
        while let Ok(answer) = self.answers.try_recv() {
            newest = Some(answer);
        }
        newest
    }
}

struct Worker {
    /// The device sessions are opened on (opened on first use when not given).
    gpu: Option<GpuContext>,
    session: Option<Session>,
    /// Read pictures back as pixels (the worker's device is not the window's).
    copy_back: bool,
    /// Shared with the session's context and the [`RenderWorker`].
    progress: Arc<Progress>,
}

impl Worker {
    /// [`Self::render`], a panic in a node reported as an error (and the session started
    /// afresh) instead of ending the previews.
    fn render_caught(&mut self, request: Request) -> Rendered {
        let id = request.id;
        self.progress.begin_request();
        let rendered =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.render(request)));
        self.progress.end_request();
        rendered.unwrap_or_else(|panic| {
            self.session = None;
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("unknown");
            Rendered::failed(id, format!("internal error while rendering: {what}"))
        })
    }

    /// The nodes the last render drew coarse (see `Ctx::take_coarse_nodes`).
    fn take_coarse_nodes(&mut self) -> Vec<String> {
        self.session
            .as_mut()
            .map(|s| s.ctx.take_coarse_nodes())
            .unwrap_or_default()
    }

    /// Renders `request` again with the `coarse` nodes re-run at the level their views need
    /// (their regions read now).
    fn refine(&mut self, request: Request, coarse: &[String]) -> Rendered {
        if let Some(s) = self.session.as_mut() {
            for node in coarse {
                s.executor.invalidate(node);
            }
            s.ctx.set_coarse_first(false);
        }
        let answer = self.render_caught(request);
        if let Some(s) = self.session.as_mut() {
            s.ctx.set_coarse_first(true);
        }
        answer
    }

    fn session(&mut self, graph: Graph, size: (u32, u32)) -> Result<&mut Session, SessionError> {
        match &mut self.session {
            Some(session) => {
                session.graph = graph;
                if session.ctx.size() != size {
                    session.ctx.set_size(size.0, size.1)?;
                }
            }
            None => {
                // The device is kept: a new session (after a failure) renders on the same one,
                // so textures still belong to the window's device when it is shared.
                let gpu = match &self.gpu {
                    Some(gpu) => gpu.clone(),
                    None => self.gpu.insert(GpuContext::new()?).clone(),
                };
                let mut session = Session::with_gpu(registry(), graph, gpu, size.0, size.1)?;
                // Interactive: a streamed volume shows its preview first, then refines; fused
                // passes keep every member's output, so an edit re-runs only what follows it.
                session.ctx.set_coarse_first(true);
                session.executor.set_keep_fused(true);
                session.ctx.set_progress(self.progress.clone());
                self.session = Some(session);
            }
        }
        Ok(self.session.as_mut().expect("made above"))
    }

    fn render(&mut self, request: Request) -> Rendered {
        let started = Instant::now();
        let mut answer = Rendered::failed(request.id, String::new());
        answer.viewport = None;
        let copy_back = self.copy_back;
        let session = match self.session(request.graph, request.size) {
            Ok(session) => session,
            Err(e) => {
                answer.viewport = Some(Err(e.to_string()));
                answer.elapsed = started.elapsed();
                return answer;
            }
        };
        answer.adapter = session.ctx.gpu.describe();
        if request.timing {
            session.ctx.enable_gpu_timing();
        }
        // Nodes that ran in this request, and nodes whose cached outputs it reused.
        let mut executed = BTreeSet::new();
        let mut reused = BTreeSet::new();
        // Every shown port in one pass first: image-space nodes run fused, and a fused pass
        // writes only what is asked for — one node at a time would re-run the shared part for
        // each thumbnail. A failure here is reported port by port below.
        let shown: Vec<&str> = request
            .viewport
            .iter()
            .chain(&request.thumbnails)
            .map(|(node, _)| node.as_str())
            .collect();
        // (An empty list would mean "every sink": saving files.)
        if !shown.is_empty()
            && let Ok(report) = session.run(&shown)
        {
            executed.extend(report.executed);
            reused.extend(report.cached);
        }
        let mut picture = |port: &Port, bound: (u32, u32), answer: &mut Rendered| {
            let (node, name) = port;
            let result = session
                .run(&[node.as_str()])
                .map(|report| {
                    executed.extend(report.executed);
                    reused.extend(report.cached);
                })
                .and_then(|()| session.output(node, name).cloned());
            let value = match result {
                Ok(value) => value,
                Err(e) => {
                    if let SessionError::Exec(exec) = &e {
                        answer.failed_node = Some((exec.node.clone(), exec.message.clone()));
                    }
                    return Err(e.to_string());
                }
            };
            let texture = display::display_texture(&mut session.ctx, &value, bound)
                .map_err(|e| format!("{node}.{name}: {e}"))?;
            if copy_back {
                let data = session
                    .ctx
                    .gpu
                    .read_texture(&texture)
                    .map_err(|e| e.to_string())?;
                Ok(Picture::Pixels(image::RgbaImage::from_fn(
                    data.width,
                    data.height,
                    |x, y| {
                        let t = data.texel(x, y);
                        image::Rgba([0, 1, 2, 3].map(|c| (t[c] * 255.0).round() as u8))
                    },
                )))
            } else {
                Ok(Picture::Texture(texture))
            }
        };
        if let Some(port) = &request.viewport {
            answer.viewport = Some(picture(port, request.size, &mut answer));
        }
        for port in &request.thumbnails {
            let shown = picture(port, request.thumbnail_bound, &mut answer);
            answer.thumbnails.push((port.clone(), shown));
        }
        answer.depth = read_depths(session, &request.depth);
        // Times of every node the requested ports depend on (those that ran or were reused).
        let session = self.session.as_ref().expect("made above");
        for (node, stats) in session.executor.stats() {
            if !executed.contains(node) && !reused.contains(node) {
                continue;
            }
            answer.times.insert(
                node.clone(),
                NodeTime {
                    cpu: stats.cpu_time,
                    gpu: stats.gpu_time,
                    cached: !executed.contains(node),
                    fused_into: stats
                        .fused_with
                        .last()
                        .filter(|last| *last != node)
                        .cloned(),
                },
            );
        }
        for node in answer.times.keys() {
            if let Some(w) = session.ctx.warnings().get(node) {
                answer.warnings.insert(node.clone(), w.clone());
            }
            if let Some(r) = session.ctx.resolved().get(node) {
                answer.resolved.insert(node.clone(), r.clone());
            }
            if let Ok(Value::TransferFunction(tf)) = session.output(node, "tf") {
                let domain = match tf.as_ref() {
                    TransferFunction::Color(f) => f.domain,
                    TransferFunction::Style { function, .. } => function.domain,
                    TransferFunction::TwoD(f) => f.domain,
                };
                answer.tf_domains.insert(node.clone(), domain);
            }
            if let Ok(Value::Labels(labels)) = session.output(node, "labels") {
                let names = labels
                    .data
                    .objects
                    .iter()
                    .map(|(id, name)| (*id, name.clone()))
                    .collect();
                answer.object_names.insert(node.clone(), names);
            }
        }
        answer.refining = session.ctx.coarse_nodes().to_vec();
        answer.elapsed = started.elapsed();
        answer
    }
}

/// The nearest surface of the G-buffers at `ports` (already rendered with the picture), read
/// back for the paint tool; `None` when there is none.
fn read_depths(session: &mut Session, ports: &[Port]) -> Option<crate::paint::DepthMap> {
    let mut maps = Vec::new();
    for (node, name) in ports {
        if session.run(&[node.as_str()]).is_err() {
            continue;
        }
        let Ok(Value::GBuffer(g)) = session.output(node, name) else {
            continue;
        };
        let Ok(data) = session.ctx.gpu.read_texture(&g.depth) else {
            continue;
        };
        maps.push(crate::paint::DepthMap {
            width: data.width,
            height: data.height,
            depth: data.data,
            inv_view_proj: g.camera.view_proj().inverse(),
        });
    }
    crate::paint::DepthMap::nearest(maps)
}
