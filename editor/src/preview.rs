//! The viewport's renderer: runs the graph through a [`Session`] (on the calling thread for
//! now; the executor's cache makes a parameter change re-run only what depends on it) and reads
//! the previewed output back as an RGBA picture.

use crate::state::EditorState;
use hatchery_graph::GraphDocument;
use hatchery_nodes::{Session, SessionError, export};

/// What was last rendered: the document revision, the size and the port.
type Key = (u64, (u32, u32), (String, String));

#[derive(Default)]
pub struct Preview {
    session: Option<Session>,
    /// The port shown; `None` = the input of the graph's first `SaveImage` node.
    pub chosen: Option<(String, String)>,
    last: Option<Key>,
    /// The last picture (kept when a later render fails).
    pub image: Option<image::RgbaImage>,
    /// Why the last render failed.
    pub error: Option<String>,
    /// The node whose execution failed, with the message (shown on the node).
    pub failed_node: Option<(String, String)>,
}

/// The port feeding the first `SaveImage` node (by id order).
pub fn default_target(doc: &GraphDocument) -> Option<(String, String)> {
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

impl Preview {
    /// The port that will be rendered.
    pub fn target(&self, doc: &GraphDocument) -> Option<(String, String)> {
        self.chosen
            .clone()
            .filter(|(n, _)| doc.nodes.iter().any(|m| &m.id == n))
            .or_else(|| default_target(doc))
    }

    /// Re-renders if the document, the size or the target changed. Returns whether a new
    /// picture is available. Never panics on a bad graph: failures land in `error`.
    pub fn update(&mut self, state: &mut EditorState, width: u32, height: u32) -> bool {
        let (width, height) = (width.clamp(16, 4096), height.clamp(16, 4096));
        let Some(target) = self.target(state.doc()) else {
            self.error = Some("nothing to preview: connect a SaveImage or pick an output".into());
            self.last = None;
            return false;
        };
        let key = (state.revision(), (width, height), target.clone());
        if self.last.as_ref() == Some(&key) {
            return false;
        }
        self.last = Some(key);
        self.failed_node = None;
        let Some(graph) = state.validate() else {
            self.error = Some("the graph has errors (see the nodes)".into());
            return false;
        };
        let result = (|| -> Result<image::RgbaImage, SessionError> {
            let session = match &mut self.session {
                Some(s) => {
                    s.graph = graph;
                    if s.ctx.size() != (width, height) {
                        s.ctx.set_size(width, height)?;
                    }
                    s
                }
                None => self.session.insert(Session::with_graph(
                    hatchery_nodes::registry(),
                    graph,
                    width,
                    height,
                )?),
            };
            let value = session.evaluate(&target.0, &target.1)?;
            export::to_rgba8(&value, &session.ctx.gpu).map_err(SessionError::Other)
        })();
        match result {
            Ok(picture) => {
                self.image = Some(picture);
                self.error = None;
                true
            }
            Err(e) => {
                if let SessionError::Exec(exec) = &e {
                    self.failed_node = Some((exec.node.clone(), exec.message.clone()));
                }
                tracing::warn!("preview failed: {e}");
                self.error = Some(e.to_string());
                false
            }
        }
    }
}
