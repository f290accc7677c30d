//! The snarl viewer of the canvas: node titles, pins, bodies, footers and menus, wires made and
//! removed, and the canvas transform (wheel zoom, *Frame all*, a kept view; the zoom itself and
//! the boxes drawn when zoomed out are in [`super::canvas_zoom`]).

use crate::app::port_color;
use crate::render_worker::{NodeTime, Port};
use crate::selection::CanvasSelection;
use crate::state::EditorState;
use egui::{Color32, Pos2, Ui};
use egui_snarl::ui::{AnyPins, PinInfo, SnarlPin, SnarlViewer};
use egui_snarl::{InPin, NodeId, OutPin, Snarl};
use hatchery_graph::PortType;
use std::collections::{BTreeMap, BTreeSet};

/// The widest an error or warning line makes a node's body (points at zoom 1); the body sits
/// between the input and output pins.
const NODE_MESSAGE_WIDTH: f32 = 120.0;

/// The snarl viewer: every change goes through the editor state (and so `edit`).
pub(crate) struct Viewer<'a> {
    /// "Frame all" requested: the canvas rectangle (screen space) to fit the nodes into.
    pub(crate) frame_into: Option<egui::Rect>,
    /// Node sizes as drawn last frame (graph units).
    pub(crate) node_sizes: BTreeMap<String, [f32; 2]>,
    pub(crate) transform: egui::emath::TSTransform,
    /// Where nodes are drawn (for selection by the mouse).
    pub(crate) selecting: &'a mut CanvasSelection,
    pub(crate) state: &'a mut EditorState,
    pub(crate) add_menu: &'a mut Option<crate::add_menu::Palette>,
    pub(crate) clipboard: &'a mut String,
    pub(crate) preview: &'a mut Option<(String, String)>,
    /// Ports shown as thumbnails on their nodes (clicking an output's name toggles it).
    pub(crate) pins: &'a mut BTreeSet<Port>,
    /// Pictures (or why there is none) of the pinned ports.
    pub(crate) thumbnails: BTreeMap<Port, Result<(egui::TextureId, egui::Vec2), String>>,
    /// Per-node times, when the user asked for them.
    pub(crate) times: Option<&'a BTreeMap<String, NodeTime>>,
    /// Why a wire drop was refused this frame.
    pub(crate) refused: Option<String>,
    /// Warnings of the last render, by node.
    pub(crate) warnings: BTreeMap<String, String>,
    pub(crate) failed: Option<(String, String)>,
    /// *Frame selection* was chosen in a node menu (done after the canvas is drawn).
    pub(crate) frame_request: &'a mut bool,
    /// The mouse wheel over the canvas this frame (points, pointer): it zooms about the
    /// pointer instead of scrolling (Shift+wheel still scrolls).
    pub(crate) wheel_zoom: Option<(f32, Pos2)>,
    /// A kept view to show (another graph or level is shown).
    pub(crate) restore: Option<egui::emath::TSTransform>,
    /// Nodes drawn as boxes: the screen size of their id's text.
    pub(crate) lod_text: &'a mut BTreeMap<String, f32>,
}

impl Viewer<'_> {
    fn schema(&self, id: &str) -> Option<hatchery_graph::NodeSchema> {
        let doc = self.state.doc();
        let n = doc.nodes.iter().find(|n| n.id == id)?;
        hatchery_graph::node_schema(&self.state.registry, doc, n).map(|s| (*s).clone())
    }

    /// The ports shown on canvas node `id` (a group's are its members' exposed ports).
    fn ports(&self, id: &str, output: bool) -> Vec<hatchery_graph::organise::PortInfo> {
        crate::groups::view_ports(self.state.doc(), &self.state.registry, id, output)
    }

    fn error(&self, id: &str) -> Option<String> {
        let mut text = self
            .state
            .node_error(id)
            .map(str::to_owned)
            .or_else(|| crate::groups::member_errors(self.state, id));
        if let Some((n, m)) = &self.failed
            && n == id
        {
            text = Some(match text {
                Some(t) => format!("{t}\n{m}"),
                None => m.clone(),
            });
        }
        text
    }

    fn pin(ty: Option<PortType>) -> PinInfo {
        match ty {
            Some(ty) => PinInfo::circle()
                .with_fill(port_color(ty))
                .with_wire_color(port_color(ty)),
            // A reroute that carries nothing yet takes any type.
            None => PinInfo::circle().with_fill(Color32::GRAY),
        }
    }

    /// Inside a group, a mark on a member's port wired to a node outside it.
    fn outside_mark(&self, ui: &mut Ui, p: &hatchery_graph::organise::PortInfo, output: bool) {
        let (doc, level) = (self.state.doc(), self.state.level());
        if let Some(note) = crate::groups::outside_note(doc, level, p, output) {
            ui.label(if output { "➡" } else { "⬅" }).on_hover_text(note);
        }
    }

    fn is_reroute(&self, id: &str) -> bool {
        hatchery_graph::reroute::is_reroute(self.state.doc(), id)
    }
}

impl SnarlViewer<String> for Viewer<'_> {
    fn title(&mut self, node: &String) -> String {
        match self.state.doc().nodes.iter().find(|n| &n.id == node) {
            Some(n) => format!("{} ({})", n.id, n.kind),
            None if self.state.doc().group(node).is_some() => format!("{node} (Group)"),
            None => node.clone(),
        }
    }

    fn inputs(&mut self, node: &String) -> usize {
        self.ports(node, false).len()
    }

    fn outputs(&mut self, node: &String) -> usize {
        self.ports(node, true).len()
    }

    fn show_input(
        &mut self,
        pin: &InPin,
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) -> impl SnarlPin + 'static {
        let node = snarl.get_node(pin.id.node).cloned().unwrap_or_default();
        let port = self.ports(&node, false).get(pin.id.input).cloned();
        match &port {
            Some(p) => {
                let required = if p.required { "" } else { " (optional)" };
                let ty = p.ty.map_or("any type".into(), |t| t.to_string());
                ui.label(crate::groups::port_label(&node, p))
                    .on_hover_text(format!("{}: {ty}{required}\n{}", p.port, p.doc));
                self.outside_mark(ui, p, false);
            }
            None => {
                ui.label("?");
            }
        }
        Self::pin(port.and_then(|p| p.ty))
    }

    fn show_output(
        &mut self,
        pin: &OutPin,
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) -> impl SnarlPin + 'static {
        let node = snarl.get_node(pin.id.node).cloned().unwrap_or_default();
        let port = self.ports(&node, true).get(pin.id.output).cloned();
        // Room for the pin right of the label. egui-snarl 0.12 reserves it on the wrong side of
        // this right-to-left row (right of the row's start), so the pin covered the label's end
        // ("ligh", "piston_surface.me"), and each row starts that much further right than the
        // one above: row k starts k pins right of the pin column.
        let pin_size = ui.spacing().interact_size.y * 0.6;
        ui.add_space(pin_size * (pin.id.output + 1) as f32);
        match &port {
            // Thumbnails are for a node's own outputs (not a group's or a reroute's).
            Some(p) if p.node == node && p.ty.is_some() && !self.is_reroute(&node) => {
                let key = (node, p.port.clone());
                let pinned = self.pins.contains(&key);
                let text = if pinned {
                    egui::RichText::new(format!("{} 👁", p.port)).strong()
                } else {
                    egui::RichText::new(&p.port)
                };
                let response = ui
                    .add(egui::Label::new(text).sense(egui::Sense::click()))
                    .on_hover_text(format!(
                        "{}: {}\n{}\nClick to {} its thumbnail on the node",
                        p.port,
                        p.ty.map_or(String::new(), |t| t.to_string()),
                        p.doc,
                        if pinned { "hide" } else { "show" }
                    ));
                if response.clicked() && !self.pins.remove(&key) {
                    self.pins.insert(key);
                }
                self.outside_mark(ui, p, true);
            }
            Some(p) => {
                let ty = p.ty.map_or("any type".into(), |t| t.to_string());
                ui.label(crate::groups::port_label(&node, p))
                    .on_hover_text(format!("{}: {ty}\n{}", p.port, p.doc));
            }
            None => {
                ui.label("?");
            }
        }
        Self::pin(port.and_then(|p| p.ty))
    }

    fn has_body(&mut self, node: &String) -> bool {
        self.error(node).is_some() || self.warnings.contains_key(node)
    }

    fn has_footer(&mut self, node: &String) -> bool {
        self.pins.iter().any(|(n, _)| n == node) || self.times.is_some_and(|t| t.contains_key(node))
    }

    fn show_body(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        // At most NODE_MESSAGE_WIDTH wide, cut with "…" (the whole text on hover): a long
        // message used to stretch a new node past the canvas edge.
        let message = |ui: &mut Ui, color: Color32, text: String, whole: &str| {
            let label = egui::Label::new(egui::RichText::new(text).color(color)).truncate();
            ui.add_sized(egui::vec2(NODE_MESSAGE_WIDTH, 0.0), label)
                .on_hover_text(whole);
        };
        if let Some(e) = self.error(&id) {
            let first = e.lines().next().unwrap_or_default().to_owned();
            message(ui, Color32::LIGHT_RED, format!("⚠ {first}"), &e);
        }
        if let Some(w) = self.warnings.get(&id).cloned() {
            message(ui, Color32::YELLOW, format!("⚠ {w}"), &w);
        }
    }

    /// Below the pins: the node's times (on request) and its pinned thumbnails.
    fn show_footer(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        if let Some(time) = self.times.and_then(|t| t.get(&id)) {
            ui.label(egui::RichText::new(format_time(time)).monospace().small())
                .on_hover_text(
                    "CPU: encoding the node's GPU work or doing its CPU work; GPU: its \
                     submissions between timestamps (where the adapter has them). On a \
                     software driver both are CPU time.",
                );
        }
        let pinned: Vec<Port> = self
            .pins
            .iter()
            .filter(|(n, _)| *n == id)
            .cloned()
            .collect();
        for port in pinned {
            match self.thumbnails.get(&port) {
                Some(Ok((texture, size))) => {
                    let name = format!("{}.{}", port.0, port.1);
                    ui.add(egui::Image::new((*texture, *size)).alt_text(&name))
                        .on_hover_text(name);
                }
                Some(Err(e)) => {
                    ui.colored_label(Color32::LIGHT_RED, format!("{}: no picture", port.1))
                        .on_hover_text(e);
                }
                None => {
                    ui.label(format!("{}: rendering…", port.1));
                }
            }
        }
    }

    fn connect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<String>) {
        let (Some(f), Some(t)) = (
            snarl.get_node(from.id.node).cloned(),
            snarl.get_node(to.id.node).cloned(),
        ) else {
            return;
        };
        let (Some(op), Some(ip)) = (
            self.ports(&f, true).get(from.id.output).cloned(),
            self.ports(&t, false).get(to.id.input).cloned(),
        ) else {
            self.state.status = "cannot connect nodes of unknown kinds".into();
            return;
        };
        match self
            .state
            .connect((&op.node, &op.port), (&ip.node, &ip.port))
        {
            Ok(_) => {
                snarl.drop_inputs(to.id);
                snarl.connect(from.id, to.id);
                self.state.status = format!(
                    // ASCII: the editor's default font has no arrow glyph (it drew a box).
                    "connected {}.{} -> {}.{}",
                    op.node, op.port, ip.node, ip.port
                );
            }
            Err(reason) => self.refused = Some(reason),
        }
    }

    fn disconnect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<String>) {
        let (Some(f), Some(t)) = (
            snarl.get_node(from.id.node).cloned(),
            snarl.get_node(to.id.node).cloned(),
        ) else {
            return;
        };
        let (Some(op), Some(ip)) = (
            self.ports(&f, true).get(from.id.output).cloned(),
            self.ports(&t, false).get(to.id.input).cloned(),
        ) else {
            return;
        };
        if self
            .state
            .disconnect((&op.node, &op.port), (&ip.node, &ip.port))
        {
            snarl.disconnect(from.id, to.id);
        }
    }

    fn drop_inputs(&mut self, pin: &InPin, snarl: &mut Snarl<String>) {
        for remote in pin.remotes.clone() {
            let from = snarl.out_pin(remote);
            self.disconnect(&from, pin, snarl);
        }
    }

    fn drop_outputs(&mut self, pin: &OutPin, snarl: &mut Snarl<String>) {
        for remote in pin.remotes.clone() {
            let to = snarl.in_pin(remote);
            self.disconnect(pin, &to, snarl);
        }
    }

    fn has_graph_menu(&mut self, _pos: Pos2, _snarl: &mut Snarl<String>) -> bool {
        true
    }

    fn show_graph_menu(&mut self, at: Pos2, ui: &mut Ui, _snarl: &mut Snarl<String>) {
        // Snarl's menu only opens the palette, which takes typing (see crate::add_menu).
        let screen = ui.cursor().min;
        *self.add_menu = Some(crate::add_menu::Palette::new(ui.ctx(), screen, at, None));
        ui.close();
    }

    fn has_dropped_wire_menu(&mut self, _src: AnyPins, _snarl: &mut Snarl<String>) -> bool {
        true
    }

    fn show_dropped_wire_menu(
        &mut self,
        at: Pos2,
        ui: &mut Ui,
        src: AnyPins,
        snarl: &mut Snarl<String>,
    ) {
        // The dragged pins' node and port names, and their type.
        // The dragged pins' real node and port names (a member's, for a group), and types.
        let (ends, output): (Vec<(String, String, Option<PortType>)>, bool) = match src {
            AnyPins::Out(pins) => (
                pins.iter()
                    .filter_map(|p| {
                        let id = snarl.get_node(p.node)?.clone();
                        let port = self.ports(&id, true).get(p.output)?.clone();
                        Some((port.node, port.port, port.ty))
                    })
                    .collect(),
                true,
            ),
            AnyPins::In(pins) => (
                pins.iter()
                    .filter_map(|p| {
                        let id = snarl.get_node(p.node)?.clone();
                        let port = self.ports(&id, false).get(p.input)?.clone();
                        Some((port.node, port.port, port.ty))
                    })
                    .collect(),
                false,
            ),
        };
        if ends.is_empty() {
            ui.close();
            return;
        }
        let wire = crate::add_menu::DroppedWire {
            ty: ends.first().and_then(|e| e.2),
            ends: ends.into_iter().map(|(id, port, _)| (id, port)).collect(),
            output,
        };
        let screen = ui.cursor().min;
        *self.add_menu = Some(crate::add_menu::Palette::new(
            ui.ctx(),
            screen,
            at,
            Some(wire),
        ));
        ui.close();
    }

    fn current_transform(
        &mut self,
        to_global: &mut egui::emath::TSTransform,
        snarl: &mut Snarl<String>,
    ) {
        // The canvas holds still while a box selection is dragged (the drag would pan it).
        if let Some(held) = self.selecting.box_transform {
            *to_global = held;
        }
        // The wheel zooms about the pointer: undo the scroll the canvas took (from last
        // frame's transform) and scale about the point under the pointer instead, so the graph
        // stays where it is under the mouse (a few notches used to scroll it off-screen).
        if let Some((scroll, at)) = self.wheel_zoom.take() {
            *to_global = super::canvas_zoom::wheel_zoom(self.transform, scroll, at);
        }
        if let Some(view) = self.restore.take() {
            *to_global = view;
        }
        self.transform = *to_global;
        let Some(rect) = self.frame_into.take() else {
            return;
        };
        // Node positions are top-left corners; sizes as drawn (or typical, before drawing).
        let mut bounds = egui::Rect::NOTHING;
        for (p, id) in snarl.nodes_pos() {
            let [w, h] = self
                .node_sizes
                .get(id)
                .copied()
                .unwrap_or(crate::arrange::DEFAULT_SIZE);
            bounds = bounds.union(egui::Rect::from_min_size(p, egui::vec2(w, h)));
        }
        bounds = bounds.union(crate::frames::bounds(self.state.doc(), self.state.level()));
        if !bounds.is_positive() {
            return;
        }
        // All of it, however small (zoomed out, nodes are drawn as boxes with legible ids).
        *to_global = super::canvas_zoom::frame_all(rect, bounds);
        self.transform = *to_global;
    }

    fn has_node_menu(&mut self, _node: &String) -> bool {
        true
    }

    fn draw_background(
        &mut self,
        background: Option<&egui_snarl::ui::BackgroundPattern>,
        viewport: &egui::Rect,
        snarl_style: &egui_snarl::ui::SnarlStyle,
        style: &egui::Style,
        painter: &egui::Painter,
        _snarl: &Snarl<String>,
    ) {
        if let Some(background) = background {
            background.draw(viewport, snarl_style, style, painter);
        }
        // Frames lie between the grid and the nodes.
        crate::frames::paint(painter, self.state.doc(), self.state.level());
    }

    fn node_frame(
        &mut self,
        default: egui::Frame,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        snarl: &Snarl<String>,
    ) -> egui::Frame {
        let Some(id) = snarl.get_node(node) else {
            return default;
        };
        if !self.state.selection.contains(id) {
            return default;
        }
        let mut stroke = crate::selection::selected_stroke();
        if self.state.inspected() == Some(id.as_str()) {
            stroke.color = crate::selection::active_color();
        }
        default.stroke(stroke)
    }

    fn final_node_rect(
        &mut self,
        node: NodeId,
        rect: egui::Rect,
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        self.selecting.node_drawn(&id, rect);
        let scaling = self.transform.scaling;
        if super::canvas_zoom::boxes(scaling) {
            // Coloured as its first output (a sink: its first input); outlined as selected or
            // failed.
            let ports = self.ports(&id, true);
            let ports = if ports.is_empty() {
                self.ports(&id, false)
            } else {
                ports
            };
            let color = ports
                .iter()
                .find_map(|p| p.ty)
                .map_or(Color32::GRAY, port_color);
            let mut stroke = egui::Stroke::new(1.0 / scaling, Color32::from_gray(90));
            if self.error(&id).is_some() {
                stroke = egui::Stroke::new(2.0 / scaling, Color32::LIGHT_RED);
            }
            if self.state.selection.contains(&id) {
                stroke = crate::selection::selected_stroke();
                if self.state.inspected() == Some(id.as_str()) {
                    stroke.color = crate::selection::active_color();
                }
                stroke.width /= scaling;
            }
            let name = self.title(&id);
            let px = super::canvas_zoom::paint_box(ui, rect, &id, color, stroke, scaling);
            self.lod_text.insert(id.clone(), px.unwrap_or(0.0));
            ui.interact(rect, ui.id().with(("lod", &id)), egui::Sense::hover())
                .on_hover_text(name);
        }
    }

    fn show_node_menu(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        let selected: BTreeSet<String> = if self.state.selection.contains(&id) {
            self.state.selection.clone()
        } else {
            BTreeSet::from([id.clone()])
        };
        let ids: Vec<&str> = selected.iter().map(String::as_str).collect();
        crate::groups::node_menu(self.state, ui, &id, &selected);
        if ui.button("Frame selection").clicked() {
            *self.frame_request = true;
            ui.close();
        }
        if let Some(schema) = self.schema(&id) {
            for out in &schema.outputs {
                if ui.button(format!("Preview {}", out.name)).clicked() {
                    *self.preview = Some((id.clone(), out.name.to_owned()));
                    ui.close();
                }
            }
        }
        if ui.button("Duplicate").clicked() {
            let _ = self.state.duplicate(&ids);
            ui.close();
        }
        if ui.button("Copy").clicked() {
            *self.clipboard = self.state.copy(&ids);
            ui.ctx().copy_text(self.clipboard.clone());
            ui.close();
        }
        if ui.button("Delete").clicked() {
            let owned: Vec<String> = selected.into_iter().collect();
            let _ = self.state.remove_nodes(&owned);
            ui.close();
        }
    }
}

/// "12.3 ms cpu · 4.5 ms gpu", "cached" when the last pass reused the node's outputs, or the
/// node whose fused pass it ran in (that node shows the pass's time).
fn format_time(time: &NodeTime) -> String {
    if time.cached {
        return "⏱ cached".into();
    }
    if let Some(carrier) = &time.fused_into {
        return format!("⏱ in {carrier}'s pass");
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    match time.gpu {
        Some(gpu) => format!("⏱ {:.1} ms cpu · {:.1} ms gpu", ms(time.cpu), ms(gpu)),
        None => format!("⏱ {:.1} ms cpu", ms(time.cpu)),
    }
}
