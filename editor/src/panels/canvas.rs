//! The node canvas: an egui-snarl view rebuilt from the document (see `rebuild_snarl`),
//! selection by the mouse, node moves written back, the wire refusal tooltip and the add-node
//! palette. The snarl viewer is in [`super::canvas_viewer`].

use super::Panel;
use super::canvas_viewer::Viewer;
use crate::app::{EditorApp, Refusal, pos};
use crate::preview::Shown;
use crate::render_worker::Port;
use crate::selection::SelectionChange;
use crate::settings::ViewChange;
use egui::{Color32, Id, Modifiers, Pos2, Ui};
use egui_snarl::Snarl;
use egui_snarl::ui::SnarlWidget;
use std::collections::BTreeMap;

/// How long a refusal tooltip stays up at most, seconds (the next click takes it down sooner).
const REFUSAL_SECONDS: f64 = 8.0;

/// The widest a refusal tooltip gets (points): a long reason wraps.
const REFUSAL_WIDTH: f32 = 320.0;

const SNARL_ID: &str = "hatchery-snarl";

/// The node canvas (the central panel beside the picture).
pub struct Canvas;

impl Panel for Canvas {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui) {
        if crate::groups::level_bar(&app.state, ui) {
            app.state.exit_group();
        }
        // Another graph or level: the view it had (left a group, reopened a file), else all of it.
        match app.canvas_views.update(
            &mut app.settings,
            app.state.path(),
            app.state.level(),
            app.canvas_transform,
        ) {
            Some(ViewChange::Restore(view)) => {
                app.restore_view = Some(view);
                app.frame_all = false;
                app.frame_all_again = false;
            }
            Some(ViewChange::FrameAll) => app.frame_all = true,
            None => {}
        }
        let widget = SnarlWidget::new()
            .id(Id::new(SNARL_ID))
            .style(super::canvas_zoom::snarl_style());
        let failed = app.preview.failed_node.clone();
        let frame_into =
            std::mem::take(&mut app.frame_all).then(|| ui.available_rect_before_wrap());
        // Node sizes as drawn last frame, for framing (before this frame's are recorded).
        let node_sizes = app.selecting.sizes();
        if frame_into.is_some() && node_sizes.len() < app.snarl_ids.len() {
            // Not all nodes drawn yet (the first frame): frame again once they are.
            app.frame_all_again = true;
        } else if frame_into.is_none() && std::mem::take(&mut app.frame_all_again) {
            app.frame_all = true;
        }
        let mut thumbnails: BTreeMap<Port, Result<(egui::TextureId, egui::Vec2), String>> = app
            .preview
            .thumbnails
            .iter()
            .map(|(port, shown)| (port.clone(), Ok((shown.id(), thumbnail_size(shown)))))
            .collect();
        for (port, e) in &app.preview.thumbnail_errors {
            thumbnails.insert(port.clone(), Err(e.clone()));
        }
        app.selecting.begin_frame();
        let mut frame_request = false;
        // The wheel over the canvas (not over a popup or the palette) zooms it.
        let pointer = ui.input(|i| i.pointer.latest_pos());
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        let wheel_zoom = pointer
            .filter(|&at| {
                scroll != 0.0
                    && !ui.input(|i| i.modifiers.shift || i.modifiers.command)
                    && ui.available_rect_before_wrap().contains(at)
                    && app.add_menu.is_none()
                    && ui
                        .ctx()
                        .layer_id_at(at)
                        .is_none_or(|l| l.order == egui::Order::Background)
            })
            .map(|at| (scroll, at));
        let mut viewer = Viewer {
            frame_into,
            node_sizes,
            transform: app.canvas_transform,
            selecting: &mut app.selecting,
            state: &mut app.state,
            add_menu: &mut app.add_menu,
            clipboard: &mut app.clipboard,
            preview: &mut app.preview.chosen,
            pins: &mut app.preview.pins,
            thumbnails,
            times: app.preview.show_times.then_some(&app.preview.times),
            refused: None,
            warnings: app.preview.warnings.clone(),
            failed,
            frame_request: &mut frame_request,
            wheel_zoom,
            restore: app.restore_view.take(),
            lod_text: &mut app.lod_text_px,
        };
        viewer.lod_text.clear();

        // Dragging a node's title moves the node instead of selecting its text.
        ui.style_mut().interaction.selectable_labels = false;
        // Snarl sees no modifiers, so its own (Shift-click) selection never starts: the editor
        // owns selection (see crate::selection).
        let modifiers = ui.input(|i| i.modifiers);
        ui.ctx().input_mut(|i| i.modifiers = Modifiers::NONE);
        let canvas_rect = ui.available_rect_before_wrap();
        app.canvas_rect = canvas_rect;
        widget.show(&mut app.snarl, &mut viewer, ui);
        ui.ctx().input_mut(|i| i.modifiers = modifiers);
        app.canvas_transform = viewer.transform;
        let refused = viewer.refused.take();
        if frame_request {
            app.frame_selection();
        }
        let free = ui
            .input(|i| i.pointer.interact_pos())
            .is_some_and(|p| ui.ctx().layer_id_at(p).is_none_or(|l| l == ui.layer_id()));
        let over_canvas = ui
            .input(|i| i.pointer.interact_pos())
            .is_some_and(|p| free && canvas_rect.contains(p));
        let dragging_frame = app.drag_frames(ui.ctx(), over_canvas);
        let change = if dragging_frame {
            None
        } else {
            app.selecting
                .update(ui.ctx(), canvas_rect, free, app.canvas_transform, modifiers)
        };
        match change {
            Some(SelectionChange::Click { node, mode }) => app.state.select_click(&node, mode),
            Some(SelectionChange::ClickEmpty) if modifiers.is_none() => app.state.clear_selection(),
            Some(SelectionChange::Box { nodes, add }) => app.state.select_box(&nodes, add),
            _ => {}
        }
        if let Some(reason) = refused {
            let now = ui.input(|i| i.time);
            let at = ui
                .input(|i| i.pointer.latest_pos())
                .unwrap_or_else(|| ui.max_rect().center());
            app.refusal = Some(Refusal {
                reason,
                at,
                until: now + REFUSAL_SECONDS,
            });
        }
        refusal_tooltip(app, ui, canvas_rect);
        let clipboard = app.clipboard.clone();
        for (name, r) in
            crate::add_menu::show(ui.ctx(), &mut app.add_menu, &mut app.state, &clipboard)
        {
            app.layout.record(name, r);
        }
        let changed_by_viewer = app.synced_revision != Some(app.state.revision());

        // Node moves: written back to the document (one undo step per drag).
        if !changed_by_viewer {
            let moved: Vec<(String, Pos2)> = app
                .snarl
                .nodes_pos()
                .filter_map(|(p, id)| {
                    let old = *app.placed.get(id)?;
                    (old.distance(p) > 0.25).then(|| (id.clone(), p))
                })
                .collect();
            // Dragging one selected node carries the rest of the selection along.
            let mut moved = moved;
            if let [(dragged, to)] = moved.clone().as_slice()
                && app.state.selection.contains(dragged)
                && let Some(&from) = app.placed.get(dragged)
            {
                let delta = *to - from;
                for other in &app.state.selection {
                    if other == dragged {
                        continue;
                    }
                    let (Some(&n), Some(&at)) = (app.snarl_ids.get(other), app.placed.get(other))
                    else {
                        continue;
                    };
                    if let Some(info) = app.snarl.get_node_info_mut(n) {
                        info.pos = at + delta;
                        moved.push((other.clone(), at + delta));
                    }
                }
            }
            for (id, p) in moved {
                app.state.move_node(&id, pos(p));
                app.placed.insert(id, p);
            }
            // The canvas already shows these positions: no rebuild needed.
            app.synced_revision = Some(app.state.revision());
        }
    }
}

/// Rebuilds the canvas from the document (Snarl is only a view of it) at the current level
/// (see [`crate::groups`]).
pub(crate) fn rebuild_snarl(app: &mut EditorApp) {
    let mut snarl = Snarl::new();
    let mut ids = BTreeMap::new();
    let mut placed = BTreeMap::new();
    let doc = app.state.doc();
    for (i, (id, at)) in crate::groups::shown_nodes(doc, app.state.level())
        .into_iter()
        .enumerate()
    {
        let at = at.map_or_else(
            || Pos2::new(240.0 * (i % 5) as f32, 160.0 * (i / 5) as f32),
            |p| Pos2::new(p.x, p.y),
        );
        placed.insert(id.clone(), at);
        ids.insert(id.clone(), snarl.insert_node(at, id));
    }
    for ((from, o), (to, i)) in
        crate::groups::shown_wires(doc, &app.state.registry, app.state.level())
    {
        if let (Some(&from), Some(&to)) = (ids.get(&from), ids.get(&to)) {
            snarl.connect(
                egui_snarl::OutPinId {
                    node: from,
                    output: o,
                },
                egui_snarl::InPinId { node: to, input: i },
            );
        }
    }
    app.snarl = snarl;
    app.snarl_ids = ids;
    app.placed = placed;
    app.synced_revision = Some(app.state.revision());
}

/// The reason of a refused wire, next to where it was dropped and inside the canvas, until the
/// next click (at most [`REFUSAL_SECONDS`]).
fn refusal_tooltip(app: &mut EditorApp, ui: &Ui, canvas: egui::Rect) {
    let Some(refusal) = &app.refusal else {
        return;
    };
    let now = ui.input(|i| i.time);
    // The drop that refused the wire is a release: a press is the next click.
    let clicked = ui.input(|i| i.pointer.any_pressed());
    if now > refusal.until || clicked {
        app.refusal = None;
        return;
    }
    // Right of and below the drop point, or left of / above it where the canvas ends.
    let room = canvas.max - refusal.at;
    let pivot = egui::Align2([
        if room.x < REFUSAL_WIDTH + 24.0 {
            egui::Align::Max
        } else {
            egui::Align::Min
        },
        if room.y < 80.0 {
            egui::Align::Max
        } else {
            egui::Align::Min
        },
    ]);
    let offset = egui::vec2(
        if pivot.x() == egui::Align::Max {
            -12.0
        } else {
            12.0
        },
        if pivot.y() == egui::Align::Max {
            -12.0
        } else {
            12.0
        },
    );
    egui::Area::new(Id::new("wire-refusal"))
        .order(egui::Order::Tooltip)
        .pivot(pivot)
        .fixed_pos(refusal.at + offset)
        .constrain_to(canvas)
        .interactable(false)
        .show(ui.ctx(), |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(REFUSAL_WIDTH.min(canvas.width() - 24.0));
                ui.colored_label(Color32::LIGHT_RED, format!("⛔ {}", refusal.reason));
            });
        });
    ui.ctx()
        .request_repaint_after(std::time::Duration::from_secs_f64(refusal.until - now));
}

/// A thumbnail's size on the canvas (points): its pixels, at most the thumbnail bound.
fn thumbnail_size(shown: &Shown) -> egui::Vec2 {
    let [w, h] = shown.size();
    egui::vec2(w as f32, h as f32)
}

/// The frame commands of the canvas and the menu (frames are drawn and hit-tested in
/// [`crate::frames`]).
impl EditorApp {
    /// A frame around the selected nodes (*Frame selection*, `Ctrl+J`).
    pub fn frame_selection(&mut self) {
        let rects = crate::frames::node_rects(&self.placed, &self.selecting.sizes());
        let _ = self.state.frame_selection(&rects);
    }

    /// This frame's frame drag (see [`crate::frames::drag_frames`]), after the canvas was drawn; `free`: the
    /// pointer is over the canvas and nothing covers it. True while a frame is dragged.
    pub(crate) fn drag_frames(&mut self, ctx: &egui::Context, free: bool) -> bool {
        let rects = crate::frames::node_rects(&self.placed, &self.selecting.sizes());
        let over_node = ctx
            .input(|i| i.pointer.interact_pos())
            .is_some_and(|p| self.node_at(p).is_some());
        let to_screen = self.canvas_transform;
        let dragging = crate::frames::drag_frames(
            &mut self.frame_drag,
            &mut self.state,
            ctx,
            to_screen,
            (free, over_node),
            &rects,
        );
        // The canvas holds still while a frame is dragged, as for a box selection.
        if let Some(drag) = &self.frame_drag {
            self.selecting.box_transform = Some(drag.transform);
        } else if !self.selecting.boxing() {
            self.selecting.box_transform = None;
        }
        dragging
    }
}
