//! The editor's model, free of egui: the document, undo/redo, selection, validation errors and
//! the autosave recovery file.
//!
//! Over 600 lines: the document, undo/redo, selection and the recovery file are one model that
//! every edit goes through (a split would hand the undo history between files).

use hatchery_graph::document::Source;
use hatchery_graph::{EdgeDoc, EditorPos, FORMAT_VERSION, Graph, GraphDocument, ParamValue, edit};
use hatchery_nodes::Registry;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How long the editor waits between two autosaves of a dirty document.
pub const AUTOSAVE_INTERVAL: Duration = Duration::from_secs(2);

/// How many steps undo goes back: the oldest is dropped past it, so that a long session (a
/// parameter nudged thousands of times) does not hold every version of the graph in memory.
/// A graph document is a few kB to ~100 kB, so this is at most tens of MB.
pub const UNDO_LIMIT: usize = 500;

pub struct EditorState {
    pub registry: Registry,
    doc: GraphDocument,
    path: Option<PathBuf>,
    dirty: bool,
    undo: Vec<GraphDocument>,
    redo: Vec<GraphDocument>,
    /// Key of the edit that is still going on (a parameter drag, a node move): further changes
    /// with the same key do not push another undo step.
    open_group: Option<String>,
    pub selection: BTreeSet<String>,
    /// The node the Inspector shows: the last one clicked (if still selected).
    active: Option<String>,
    /// Validation errors by node id (several joined by newlines).
    errors: BTreeMap<String, String>,
    /// Errors that concern no single node.
    graph_errors: Vec<String>,
    /// The last message for the status line (a refused wire, a failed save, ...).
    pub status: String,
    /// Where recovery files of unsaved graphs go (the temp dir unless set).
    pub scratch_dir: PathBuf,
    last_autosave: Instant,
    /// Increases on every change of the document: views rebuild when it moves.
    revision: u64,
    /// The group whose inside the canvas shows (`None`: the top level); see `crate::groups`.
    pub(crate) level: Option<String>,
    /// Files custom shader nodes read, with their stamps at the last look.
    watched: BTreeMap<PathBuf, Option<hatchery_nodes::custom_shader::Stamp>>,
}

impl Default for EditorState {
    fn default() -> Self {
        Self::new()
    }
}

impl EditorState {
    /// An empty, unsaved graph.
    pub fn new() -> Self {
        let mut s = EditorState {
            registry: hatchery_nodes::registry(),
            doc: GraphDocument {
                version: FORMAT_VERSION,
                ..Default::default()
            },
            path: None,
            dirty: false,
            undo: Vec::new(),
            redo: Vec::new(),
            open_group: None,
            selection: BTreeSet::new(),
            active: None,
            errors: BTreeMap::new(),
            graph_errors: Vec::new(),
            status: String::new(),
            scratch_dir: std::env::temp_dir(),
            last_autosave: Instant::now(),
            revision: 0,
            level: None,
            watched: BTreeMap::new(),
        };
        s.validate();
        s
    }

    /// Opens a graph file. Files with validation errors open (the errors are attached to their
    /// nodes); only unreadable or unparsable files are refused, leaving the state unchanged.
    pub fn open(&mut self, path: &Path) -> Result<(), String> {
        let (doc, _) = GraphDocument::load(path).map_err(|e| e.to_string())?;
        self.doc = doc;
        self.path = Some(path.to_path_buf());
        self.dirty = false;
        self.undo.clear();
        self.redo.clear();
        self.open_group = None;
        self.selection.clear();
        self.level = None;
        self.last_autosave = Instant::now();
        self.revision += 1;
        self.validate();
        self.status = format!("opened {}", path.display());
        Ok(())
    }

    pub fn doc(&self) -> &GraphDocument {
        &self.doc
    }
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }
    pub fn is_dirty(&self) -> bool {
        self.dirty
    }
    pub fn revision(&self) -> u64 {
        self.revision
    }
    /// Makes views rebuild without changing the document (entering or leaving a group).
    pub(crate) fn touch_view(&mut self) {
        self.revision += 1;
    }
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
    pub fn errors(&self) -> &BTreeMap<String, String> {
        &self.errors
    }
    pub fn graph_errors(&self) -> &[String] {
        &self.graph_errors
    }
    pub fn node_error(&self, id: &str) -> Option<&str> {
        self.errors.get(id).map(String::as_str)
    }
    /// The window title: file name and a `*` when there are unsaved changes.
    pub fn title(&self) -> String {
        let name = self
            .path
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or("untitled".into(), |n| n.to_string_lossy().into_owned());
        format!(
            "{}{name} — hatchery editor",
            if self.dirty { "*" } else { "" }
        )
    }

    /// The folder relative paths in the graph resolve against.
    pub fn base_dir(&self) -> Option<PathBuf> {
        self.path
            .as_deref()
            .map(hatchery_graph::document::folder_of)
    }

    /// Files the graph's nodes read their ports from (custom shaders), resolved.
    pub fn watched_files(&self) -> Vec<PathBuf> {
        self.shader_files().into_iter().map(|(_, p)| p).collect()
    }

    /// (node id, resolved shader file) of every custom shader node.
    fn shader_files(&self) -> Vec<(String, PathBuf)> {
        let base = self.base_dir();
        self.doc
            .nodes
            .iter()
            .filter(|n| n.kind == "CustomShader")
            .filter_map(|n| match n.params.get("shader") {
                Some(ron::Value::String(s)) if !s.is_empty() => {
                    Some((n.id.clone(), PathBuf::from(s)))
                }
                _ => None,
            })
            .map(|(id, p)| match &base {
                Some(base) if p.is_relative() => (id, base.join(p)),
                _ => (id, p),
            })
            .collect()
    }

    /// Looks at the files the graph's custom shaders come from; when one changed on disk since
    /// the last look, the views rebuild (ports may have changed), the graph is validated again
    /// and the picture re-rendered — a shader error then shows on its node while the last good
    /// picture stays. Returns whether anything changed. Cheap (one `stat` per file).
    pub fn poll_watched_files(&mut self) -> bool {
        let stamps: BTreeMap<PathBuf, Option<hatchery_nodes::custom_shader::Stamp>> = self
            .watched_files()
            .into_iter()
            .map(|p| {
                let stamp = crate::file_watch::stamp(&p);
                (p, stamp)
            })
            .collect();
        // Only files seen before count as changed: a newly added node is validated anyway.
        let changed: Vec<&PathBuf> = stamps
            .iter()
            .filter(|(p, stamp)| self.watched.get(*p).is_some_and(|old| old != *stamp))
            .map(|(p, _)| p)
            .collect();
        let changed_nodes: Vec<String> = self
            .shader_files()
            .into_iter()
            .filter(|(_, p)| changed.contains(&p))
            .map(|(id, _)| id)
            .collect();
        let any = !changed.is_empty();
        self.watched = stamps;
        if any {
            self.revision += 1;
            self.validate();
            // Say what is wrong here too: the node may be off the visible canvas.
            let broken = changed_nodes
                .iter()
                .find_map(|id| Some((id.clone(), self.errors.get(id)?.clone())));
            self.status = match broken {
                Some((id, error)) => {
                    let line = first_line(&error);
                    let prefix = format!("node `{id}`: ");
                    let message = line.strip_prefix(&prefix).unwrap_or(line);
                    format!("shader of `{id}`: {message}")
                }
                None => "a shader file changed: read it again".into(),
            };
        }
        any
    }

    /// The watched files with the stamps [`Self::poll_watched_files`] last saw.
    pub fn watched_stamps(&self) -> Vec<(PathBuf, Option<hatchery_nodes::custom_shader::Stamp>)> {
        self.watched.iter().map(|(p, s)| (p.clone(), *s)).collect()
    }

    /// Validates the document; on success returns the runtime graph.
    pub fn validate(&mut self) -> Option<Graph> {
        self.errors.clear();
        self.graph_errors.clear();
        let source = Source {
            path: self.path.clone(),
            text: String::new(),
        };
        match Graph::from_document(
            &self.doc,
            &source,
            &self.registry,
            self.base_dir().as_deref(),
        ) {
            Ok(graph) => Some(graph),
            Err(errors) => {
                for e in &errors.0 {
                    let message = e.kind.to_string();
                    match e.node() {
                        Some(node) => {
                            let slot = self.errors.entry(node.to_owned()).or_default();
                            if !slot.is_empty() {
                                slot.push('\n');
                            }
                            slot.push_str(&message);
                        }
                        None => self.graph_errors.push(message),
                    }
                }
                None
            }
        }
    }

    /// Applies an edit to a copy of the document; on success it becomes the document and the
    /// previous one goes on the undo stack (unless `group` continues the edit that pushed last).
    pub fn apply<T>(
        &mut self,
        group: Option<&str>,
        f: impl FnOnce(&mut GraphDocument, &Registry) -> Result<T, String>,
    ) -> Result<T, String> {
        let mut next = self.doc.clone();
        match f(&mut next, &self.registry) {
            Ok(value) => {
                let continues = group.is_some() && self.open_group.as_deref() == group;
                if !continues {
                    let prev = std::mem::replace(&mut self.doc, next);
                    self.push_undo(prev);
                } else {
                    self.doc = next;
                }
                self.open_group = group.map(str::to_owned);
                self.redo.clear();
                self.dirty = true;
                self.revision += 1;
                self.validate();
                Ok(value)
            }
            Err(message) => {
                self.status = message.clone();
                Err(message)
            }
        }
    }

    /// Pushes an undo step, dropping the oldest past [`UNDO_LIMIT`].
    fn push_undo(&mut self, doc: GraphDocument) {
        if self.undo.len() >= UNDO_LIMIT {
            self.undo.remove(0);
        }
        self.undo.push(doc);
    }

    /// Ends the edit a drag was grouping: the next change is a new undo step.
    pub fn end_group(&mut self) {
        self.open_group = None;
    }

    pub fn undo(&mut self) -> bool {
        let Some(prev) = self.undo.pop() else {
            return false;
        };
        self.status = format!("Undid {}", crate::history_text::describe(&prev, &self.doc));
        self.redo.push(std::mem::replace(&mut self.doc, prev));
        self.after_history_step();
        true
    }

    pub fn redo(&mut self) -> bool {
        let Some(next) = self.redo.pop() else {
            return false;
        };
        self.status = format!("Redid {}", crate::history_text::describe(&self.doc, &next));
        let prev = std::mem::replace(&mut self.doc, next);
        self.push_undo(prev);
        self.after_history_step();
        true
    }

    fn after_history_step(&mut self) {
        // A document from before a Save as resolves paths against the file's folder now.
        self.doc.base_dir = self.base_dir();
        self.open_group = None;
        self.dirty = true;
        self.revision += 1;
        let doc = &self.doc;
        self.selection
            .retain(|id| doc.node(id).is_some() || doc.group(id).is_some());
        // Undoing the grouping of the group shown takes the canvas back to the top level.
        if self.level.as_ref().is_some_and(|g| doc.group(g).is_none()) {
            self.level = None;
        }
        self.validate();
    }

    // Selection (by the mouse: see `crate::selection`).

    /// The node the Inspector shows: the last clicked if still selected, else the first.
    pub fn inspected(&self) -> Option<&str> {
        self.active
            .as_deref()
            .filter(|a| self.selection.contains(*a))
            .or_else(|| self.selection.iter().next().map(String::as_str))
    }

    /// A click on node `id`.
    pub fn select_click(&mut self, id: &str, mode: crate::selection::ClickMode) {
        use crate::selection::ClickMode;
        match mode {
            ClickMode::Replace => self.selection = BTreeSet::from([id.to_owned()]),
            ClickMode::Add => {
                self.selection.insert(id.to_owned());
            }
            ClickMode::Toggle => {
                if !self.selection.remove(id) {
                    self.selection.insert(id.to_owned());
                }
            }
        }
        self.active = self.selection.contains(id).then(|| id.to_owned());
    }

    /// A finished box selection.
    pub fn select_box(&mut self, ids: &[String], add: bool) {
        if !add {
            self.selection.clear();
        }
        self.selection.extend(ids.iter().cloned());
        if let Some(last) = ids.last() {
            self.active = Some(last.clone());
        }
    }

    pub fn clear_selection(&mut self) {
        self.selection.clear();
        self.active = None;
    }

    // Edits: thin wrappers over `hatchery_graph::edit` with undo.

    pub fn add_node(&mut self, kind: &str, at: EditorPos) -> Result<String, String> {
        let level = self.level.clone();
        let id = self.apply(None, |d, r| {
            let id = edit::add_node(d, r, kind, at).map_err(|e| e.to_string())?;
            join(d, std::slice::from_ref(&id), level);
            Ok(id)
        })?;
        self.selection = BTreeSet::from([id.clone()]);
        Ok(id)
    }

    /// Adds a node with some parameters set, as one undo step (a dropped data file).
    pub fn add_node_with(
        &mut self,
        kind: &str,
        at: EditorPos,
        params: &[(&str, ParamValue)],
    ) -> Result<String, String> {
        let level = self.level.clone();
        let id = self.apply(None, |d, r| {
            let id = edit::add_node(d, r, kind, at).map_err(|e| e.to_string())?;
            join(d, std::slice::from_ref(&id), level);
            for (name, value) in params {
                edit::set_param(d, r, &id, name, value.clone()).map_err(|e| e.to_string())?;
            }
            Ok(id)
        })?;
        self.selection = BTreeSet::from([id.clone()]);
        Ok(id)
    }

    pub fn remove_nodes(&mut self, ids: &[String]) -> Result<(), String> {
        self.apply(None, |d, _| {
            for id in ids {
                if d.group(id).is_some() {
                    hatchery_graph::edit::remove_group(d, id).map_err(|e| e.to_string())?;
                    continue;
                }
                edit::remove_node(d, id).ok_or_else(|| format!("no node `{id}`"))?;
            }
            Ok(())
        })?;
        for id in ids {
            self.selection.remove(id);
        }
        Ok(())
    }

    pub fn connect(
        &mut self,
        from: (&str, &str),
        to: (&str, &str),
    ) -> Result<Option<EdgeDoc>, String> {
        self.apply(None, |d, r| {
            edit::connect(d, r, from, to).map_err(|e| e.to_string())
        })
    }

    pub fn disconnect(&mut self, from: (&str, &str), to: (&str, &str)) -> bool {
        self.apply(None, |d, _| {
            if edit::disconnect(d, from, to) {
                Ok(())
            } else {
                Err("no such wire".into())
            }
        })
        .is_ok()
    }

    /// Sets a parameter. While `dragging`, changes of the same parameter are one undo step.
    pub fn set_param(
        &mut self,
        node: &str,
        name: &str,
        value: ParamValue,
        dragging: bool,
    ) -> Result<(), String> {
        let key = format!("param:{node}.{name}");
        let group = dragging.then_some(key.as_str());
        self.apply(group, |d, r| {
            edit::set_param(d, r, node, name, value).map_err(|e| e.to_string())
        })
    }

    /// Sets several parameters of one node as one edit; edits with the same `group` (a viewport
    /// drag) merge into one undo step.
    pub fn set_params(
        &mut self,
        node: &str,
        values: &[(&str, ParamValue)],
        group: &str,
    ) -> Result<(), String> {
        self.apply(Some(group), |d, r| {
            for (name, value) in values {
                edit::set_param(d, r, node, name, value.clone()).map_err(|e| e.to_string())?;
            }
            Ok(())
        })
    }

    /// Moves many nodes as one undo step (*Arrange*).
    pub fn move_nodes(&mut self, positions: &BTreeMap<String, EditorPos>) {
        let _ = self.apply(None, |d, _| {
            for (id, p) in positions {
                edit::move_node(d, id, *p);
            }
            Ok(())
        });
    }

    /// Moves a node; every move during one drag (of one node or of a selection) is one undo
    /// step.
    pub fn move_node(&mut self, id: &str, at: EditorPos) {
        let _ = self.apply(Some("move"), |d, _| {
            if edit::move_node(d, id, at) {
                Ok(())
            } else {
                Err(format!("no node `{id}`"))
            }
        });
    }

    pub fn copy(&self, ids: &[&str]) -> String {
        edit::copy_nodes(&self.doc, ids)
    }

    pub fn paste(&mut self, text: &str, offset: EditorPos) -> Result<Vec<String>, String> {
        let level = self.level.clone();
        let ids = self.apply(None, |d, _| {
            let ids = edit::paste_nodes(d, text, offset).map_err(|e| e.to_string())?;
            join(d, &ids, level);
            Ok(ids)
        })?;
        self.selection = ids.iter().cloned().collect();
        Ok(ids)
    }

    pub fn duplicate(&mut self, ids: &[&str]) -> Result<Vec<String>, String> {
        let text = self.copy(ids);
        self.paste(&text, EditorPos { x: 40.0, y: 40.0 })
    }

    // Files.

    /// Saves to the current path.
    pub fn save(&mut self) -> Result<(), String> {
        let path = self
            .path
            .clone()
            .ok_or_else(|| "the graph has no file yet: use Save as".to_string())?;
        self.save_as(&path)
    }

    /// Saves (atomically) to `path`, which becomes the current file.
    /// Relative data paths are rewritten to name the same files from the new folder, in the
    /// undo history too (undoing must not bring back paths relative to the old folder).
    pub fn save_as(&mut self, path: &Path) -> Result<(), String> {
        let old_recovery = self.recovery_path();
        let folder = hatchery_graph::document::folder_of(path);
        let old_folder = self.base_dir();
        let mut doc = self.doc.clone();
        doc.base_dir.clone_from(&old_folder);
        hatchery_graph::rebase::rebase_paths(&mut doc, &self.registry, &folder);
        doc.save(path)
            .map_err(|e| format!("cannot save {}: {e}", path.display()))?;
        for past in self.undo.iter_mut().chain(self.redo.iter_mut()) {
            past.base_dir.clone_from(&old_folder);
            hatchery_graph::rebase::rebase_paths(past, &self.registry, &folder);
        }
        self.doc = doc;
        let _ = std::fs::remove_file(old_recovery);
        self.path = Some(path.to_path_buf());
        self.doc.base_dir = self.base_dir();
        let _ = std::fs::remove_file(self.recovery_path());
        self.dirty = false;
        self.status = format!("saved {}", path.display());
        self.validate();
        Ok(())
    }

    /// `<graph>.ron.recovery` next to the file, or a file in the scratch dir for unsaved graphs.
    pub fn recovery_path(&self) -> PathBuf {
        match &self.path {
            Some(p) => {
                let name = p
                    .file_name()
                    .map_or("graph.ron".into(), |n| n.to_string_lossy().into_owned());
                p.with_file_name(format!("{name}.recovery"))
            }
            None => self.scratch_dir.join("hatchery-untitled.ron.recovery"),
        }
    }

    /// Writes the recovery file if the document is dirty and the last autosave is at least
    /// [`AUTOSAVE_INTERVAL`] before `now`. Returns whether it wrote.
    pub fn autosave_at(&mut self, now: Instant) -> bool {
        if !self.dirty || now.saturating_duration_since(self.last_autosave) < AUTOSAVE_INTERVAL {
            return false;
        }
        self.last_autosave = now;
        match self.doc.save(&self.recovery_path()) {
            Ok(()) => true,
            Err(e) => {
                self.status = format!("autosave failed: {e}");
                false
            }
        }
    }

    pub fn autosave(&mut self) -> bool {
        self.autosave_at(Instant::now())
    }

    /// Whether a recovery file newer than... any recovery file exists for the current graph.
    pub fn has_recovery(&self) -> bool {
        self.recovery_path().is_file()
    }

    /// Replaces the document with the recovery file's (as an undoable, unsaved edit).
    pub fn restore_recovery(&mut self) -> Result<(), String> {
        let path = self.recovery_path();
        let (mut doc, _) = GraphDocument::load(&path).map_err(|e| e.to_string())?;
        // Its paths are the graph's (the recovery file lives elsewhere).
        doc.base_dir = self.base_dir();
        self.apply(None, |d, _| {
            *d = doc;
            Ok(())
        })?;
        self.status = format!("restored {}", path.display());
        Ok(())
    }

    /// Forgets the recovery file.
    pub fn discard_recovery(&mut self) {
        let _ = std::fs::remove_file(self.recovery_path());
    }
}

fn first_line(text: &str) -> &str {
    text.lines().next().unwrap_or("")
}

/// Puts new nodes into the group shown (they were added on its inside).
fn join(doc: &mut GraphDocument, ids: &[String], level: Option<String>) {
    for n in doc.nodes.iter_mut().filter(|n| ids.contains(&n.id)) {
        n.group = level.clone();
    }
}
