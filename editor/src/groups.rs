//! Node groups and reroutes in the editor: which nodes the canvas shows at the current level
//! (the top level, or inside one group), the ports each shown node has, and the group commands.
//!
//! | input | effect |
//! |---|---|
//! | `Ctrl+G` (node menu *Group*) | group the selected nodes into one group node |
//! | `Ctrl+Shift+G` (*Ungroup*) | dissolve the selected groups |
//! | `Tab` (*Enter group*) | with one group selected: show its inside; inside: back out |
//! | wire dropped on empty canvas → *Reroute* | a waypoint carrying that wire |
//!
//! The graph model is in [`hatchery_graph::organise`] and [`hatchery_graph::reroute`].

use crate::state::EditorState;
use egui::{Key, Modifiers, Pos2, Ui};
use hatchery_graph::organise::{self, PortInfo};
use hatchery_graph::{EditorPos, GraphDocument, SchemaLookup, edit};
use std::collections::{BTreeMap, BTreeSet};

/// A wire as the canvas draws it: (shown node, output index) → (shown node, input index).
pub type ViewWire = ((String, usize), (String, usize));

/// The ports of a node shown on the canvas: a group's exposed ports, or a node's own.
pub fn view_ports(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    id: &str,
    output: bool,
) -> Vec<PortInfo> {
    if doc.group(id).is_some() {
        organise::exposed_ports(doc, schemas, id, output)
    } else {
        organise::node_ports(doc, schemas, id, output)
    }
}

/// The label of a port on shown node `id`: a member's port on a group says whose it is.
pub fn port_label(id: &str, p: &PortInfo) -> String {
    if p.node == id {
        p.port.clone()
    } else {
        format!("{}.{}", p.node, p.port)
    }
}

/// Inside a group: where member port `p` is wired to nodes outside the group (those wires are
/// not drawn inside), e.g. "wired to shaded.mesh outside the group".
pub fn outside_note(
    doc: &GraphDocument,
    level: Option<&str>,
    p: &PortInfo,
    output: bool,
) -> Option<String> {
    let level = level?;
    let end = (p.node.clone(), p.port.clone());
    let outside: Vec<String> = doc
        .edges
        .iter()
        .filter_map(|e| {
            let (near, far) = if output {
                (&e.from, &e.to)
            } else {
                (&e.to, &e.from)
            };
            let far_group = doc.node(&far.0).and_then(|n| n.group.as_deref());
            (*near == end && far_group != Some(level)).then(|| format!("{}.{}", far.0, far.1))
        })
        .collect();
    (!outside.is_empty()).then(|| format!("wired to {} outside the group", outside.join(", ")))
}

/// The shown node that stands for graph node `node` at `level`: itself, its group (on the top
/// level), or none (outside the entered group).
fn owner<'a>(doc: &'a GraphDocument, level: Option<&str>, node: &'a str) -> Option<&'a str> {
    let group = doc.node(node)?.group.as_deref();
    match level {
        None => Some(group.unwrap_or(node)),
        Some(l) => (group == Some(l)).then_some(node),
    }
}

/// The nodes shown at `level` with their stored positions: top level: ungrouped nodes and the
/// groups; inside a group: its members.
pub fn shown_nodes(doc: &GraphDocument, level: Option<&str>) -> Vec<(String, Option<EditorPos>)> {
    let mut out: Vec<(String, Option<EditorPos>)> = doc
        .nodes
        .iter()
        .filter(|n| n.group.as_deref() == level)
        .map(|n| (n.id.clone(), n.editor))
        .collect();
    if level.is_none() {
        out.extend(doc.groups.iter().map(|g| (g.id.clone(), g.editor)));
    }
    out
}

/// The wires shown at `level`: edges between shown nodes, ending at the ports that stand for
/// their ends (edges inside a collapsed group are not drawn).
pub fn shown_wires(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    level: Option<&str>,
) -> Vec<ViewWire> {
    let mut ports: BTreeMap<(String, bool), Vec<PortInfo>> = BTreeMap::new();
    let mut index = |shown: &str, node: &str, port: &str, output: bool| {
        ports
            .entry((shown.to_owned(), output))
            .or_insert_with(|| view_ports(doc, schemas, shown, output))
            .iter()
            .position(|p| p.node == node && p.port == port)
    };
    let mut wires = Vec::new();
    for e in &doc.edges {
        let (Some(f), Some(t)) = (owner(doc, level, &e.from.0), owner(doc, level, &e.to.0)) else {
            continue;
        };
        if f == t && f != e.from.0 {
            continue; // inside a collapsed group
        }
        if let (Some(o), Some(i)) = (
            index(f, &e.from.0, &e.from.1, true),
            index(t, &e.to.0, &e.to.1, false),
        ) {
            wires.push(((f.to_owned(), o), (t.to_owned(), i)));
        }
    }
    wires
}

/// The document as the current level shows it (groups as nodes, wires between shown nodes),
/// for commands that work on what is on screen (*Arrange*).
pub fn shown_doc(
    doc: &GraphDocument,
    schemas: &dyn SchemaLookup,
    level: Option<&str>,
) -> GraphDocument {
    let nodes = shown_nodes(doc, level)
        .into_iter()
        .map(|(id, editor)| hatchery_graph::NodeDoc {
            id,
            kind: String::new(),
            params: Default::default(),
            editor,
            group: None,
        })
        .collect();
    let edges = shown_wires(doc, schemas, level)
        .into_iter()
        .map(|((f, o), (t, i))| hatchery_graph::EdgeDoc {
            from: (f, o.to_string()),
            to: (t, i.to_string()),
        })
        .collect();
    GraphDocument {
        version: doc.version,
        nodes,
        edges,
        ..Default::default()
    }
}

/// Validation errors of a group's members, for the group node's badge.
pub fn member_errors(state: &EditorState, group: &str) -> Option<String> {
    let lines: Vec<String> = organise::members(state.doc(), group)
        .into_iter()
        .filter_map(|m| state.node_error(m).map(|e| format!("{m}: {e}")))
        .collect();
    (!lines.is_empty()).then(|| lines.join("\n"))
}

impl EditorState {
    /// The group whose inside the canvas shows, or `None` on the top level.
    pub fn level(&self) -> Option<&str> {
        self.level.as_deref()
    }

    /// Groups the selected nodes (one undo step); the new group becomes the selection.
    pub fn group_selection(&mut self) -> Result<String, String> {
        let ids: Vec<String> = self.selection.iter().cloned().collect();
        let group = self.apply(None, |d, _| {
            edit::group_nodes(d, &ids).map_err(|e| e.to_string())
        })?;
        self.select_click(&group, crate::selection::ClickMode::Replace);
        self.status = format!("grouped {} nodes into {group}", ids.len());
        Ok(group)
    }

    /// Dissolves the selected groups (one undo step); their members become the selection.
    pub fn ungroup_selection(&mut self) -> Result<(), String> {
        let groups = self.selected_groups();
        if groups.is_empty() {
            self.status = "select a group to ungroup".into();
            return Err(self.status.clone());
        }
        let freed = self.apply(None, |d, _| {
            let mut freed = Vec::new();
            for g in &groups {
                freed.extend(edit::ungroup(d, g).map_err(|e| e.to_string())?);
            }
            Ok(freed)
        })?;
        self.clear_selection();
        self.selection.extend(freed);
        Ok(())
    }

    /// The selected groups.
    pub fn selected_groups(&self) -> Vec<String> {
        let doc = self.doc();
        let selected = self.selection.iter();
        selected
            .filter(|id| doc.group(id).is_some())
            .cloned()
            .collect()
    }

    /// Shows the inside of group `group` (not an edit: no undo step).
    pub fn enter_group(&mut self, group: &str) -> bool {
        if self.doc().group(group).is_none() {
            return false;
        }
        self.level = Some(group.to_owned());
        self.clear_selection();
        self.touch_view();
        true
    }

    /// Back to the top level; the group left becomes the selection.
    pub fn exit_group(&mut self) -> bool {
        let Some(group) = self.level.take() else {
            return false;
        };
        self.select_click(&group, crate::selection::ClickMode::Replace);
        self.touch_view();
        true
    }

    /// Adds a reroute at `at` on the current level; returns its id.
    pub fn add_reroute(&mut self, at: EditorPos) -> Result<String, String> {
        let level = self.level.clone();
        self.apply(None, |d, _| {
            let id = edit::add_reroute(d, at);
            if let Some(n) = d.nodes.iter_mut().find(|n| n.id == id) {
                n.group = level;
            }
            Ok(id)
        })
    }
}

/// Group shortcuts (see the module comment); `typing` says a text field has the keyboard.
pub fn shortcuts(state: &mut EditorState, ui: &mut Ui, typing: bool) -> bool {
    if typing {
        return false;
    }
    let (ungroup, group, tab) = ui.input_mut(|i| {
        let ungroup = i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::G);
        let group = i.consume_key(Modifiers::COMMAND, Key::G);
        let tab = i.consume_key(Modifiers::NONE, Key::Tab);
        (ungroup, group, tab)
    });
    if ungroup {
        let _ = state.ungroup_selection();
    } else if group {
        let _ = state.group_selection();
    }
    if tab {
        // Tab also moves egui's keyboard focus (to a text field, which would then take every
        // key): here it means the group, not the focus.
        ui.memory_mut(|m| m.move_focus(egui::FocusDirection::None));
        toggle_level(state);
    }
    ungroup || group || tab
}

/// Enters the selected group, or leaves the one entered.
fn toggle_level(state: &mut EditorState) -> bool {
    if state.level().is_some() {
        return state.exit_group();
    }
    match state.selected_groups().as_slice() {
        [one] => state.enter_group(one),
        _ => {
            state.status = "select one group to enter it".into();
            false
        }
    }
}

/// The bar above the canvas while inside a group; true when the user asked to leave.
pub fn level_bar(state: &EditorState, ui: &mut Ui) -> bool {
    let Some(group) = state.level() else {
        return false;
    };
    let mut leave = false;
    ui.horizontal(|ui| {
        leave = ui
            .button("⬅ Exit group")
            .on_hover_text("back to the whole graph (Tab)")
            .clicked();
        ui.label(format!("Inside group {group}"));
        ui.weak("⬅ ➡ mark ports wired to nodes outside the group (hover: where)");
    });
    leave
}

/// The Inspector of a group or a reroute; false if `id` is neither.
pub fn inspector(state: &mut EditorState, ui: &mut Ui, id: &str) -> bool {
    if hatchery_graph::reroute::is_reroute(state.doc(), id) {
        let ty = hatchery_graph::reroute::reroute_type(state.doc(), &state.registry, id)
            .map_or("nothing yet".into(), |t| t.to_string());
        ui.label(format!("{id} (Reroute)"));
        ui.label(format!("A waypoint for a wire; it carries {ty}."));
        return true;
    }
    if state.doc().group(id).is_none() {
        return false;
    }
    let members: Vec<String> = organise::members(state.doc(), id)
        .into_iter()
        .map(str::to_owned)
        .collect();
    ui.label(format!("{id} (Group of {} nodes)", members.len()));
    ui.weak(members.join(", "));
    ui.horizontal(|ui| {
        if ui.button("Enter group").on_hover_text("Tab").clicked() {
            state.enter_group(id);
        }
        if ui.button("Ungroup").on_hover_text("Ctrl+Shift+G").clicked() {
            let _ = state.ungroup_selection();
        }
    });
    true
}

/// The group entries of a node's context menu; `selected` is what the menu acts on.
pub fn node_menu(state: &mut EditorState, ui: &mut Ui, id: &str, selected: &BTreeSet<String>) {
    if state.doc().group(id).is_some() {
        if ui.button("Enter group").clicked() {
            state.enter_group(id);
            ui.close();
        }
        if ui.button("Ungroup").clicked() {
            state.selection = selected.clone();
            let _ = state.ungroup_selection();
            ui.close();
        }
    } else if state.level().is_none() && ui.button("Group").clicked() {
        state.selection = selected.clone();
        let _ = state.group_selection();
        ui.close();
    }
}

/// Where a reroute goes when a wire is dropped at `at` (graph space): centred on the pointer.
pub fn reroute_pos(at: Pos2) -> EditorPos {
    EditorPos {
        x: at.x - 20.0,
        y: at.y - 12.0,
    }
}
