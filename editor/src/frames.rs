//! Frames: labelled, coloured boxes drawn behind the nodes of one level. Dragging a frame by its
//! title bar moves it and the nodes inside it (one undo step); right-clicking the title bar
//! renames (in a small window), recolours or deletes it.
//!
//! | input | effect |
//! |---|---|
//! | `Ctrl+J` (node menu *Frame selection*) | a new frame around the selected nodes |
//! | drag a frame's title bar | move the frame and the nodes inside it |
//! | right-click a frame's title bar | label, colour, delete |

use crate::state::EditorState;
use egui::emath::TSTransform;
use egui::{Color32, Pos2, Rect, Ui};
use hatchery_graph::{EditorPos, FrameDoc, GraphDocument, edit, organise};
use std::collections::BTreeMap;

/// Height of a frame's title bar (graph units).
pub const TITLE_HEIGHT: f32 = 32.0;
/// Room between a new frame and the nodes it surrounds (graph units).
const PADDING: f32 = 24.0;

/// A frame's rectangle in graph space.
pub fn frame_rect(f: &FrameDoc) -> Rect {
    Rect::from_min_size(Pos2::new(f.x, f.y), egui::vec2(f.w, f.h))
}

/// A frame's title bar in graph space.
pub fn title_rect(f: &FrameDoc) -> Rect {
    Rect::from_min_size(Pos2::new(f.x, f.y), egui::vec2(f.w, TITLE_HEIGHT))
}

fn color(f: &FrameDoc) -> Color32 {
    let [r, g, b, a] = f.color.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
    Color32::from_rgba_unmultiplied(r, g, b, a)
}

/// The frames shown at `level`, with their indices in the document (later ones on top).
fn shown<'a>(
    doc: &'a GraphDocument,
    level: Option<&'a str>,
) -> impl DoubleEndedIterator<Item = (usize, &'a FrameDoc)> + 'a {
    doc.frames
        .iter()
        .enumerate()
        .filter(move |(_, f)| f.group.as_deref() == level)
}

/// The rectangle around every frame shown at `level` (graph space; `Rect::NOTHING` if none).
pub fn bounds(doc: &GraphDocument, level: Option<&str>) -> Rect {
    shown(doc, level).fold(Rect::NOTHING, |r, (_, f)| r.union(frame_rect(f)))
}

/// The topmost frame whose title bar contains `at` (graph space).
pub fn title_at(doc: &GraphDocument, level: Option<&str>, at: Pos2) -> Option<usize> {
    shown(doc, level)
        .rev()
        .find(|(_, f)| title_rect(f).contains(at))
        .map(|(i, _)| i)
}

/// Paints the frames of `level` (graph-space painter, called before nodes are drawn).
pub fn paint(painter: &egui::Painter, doc: &GraphDocument, level: Option<&str>) {
    for (_, f) in shown(doc, level) {
        let fill = color(f);
        let rect = frame_rect(f);
        painter.rect_filled(rect, 6.0, fill.gamma_multiply(0.6));
        painter.rect_filled(title_rect(f), 6.0, fill);
        painter.rect_stroke(
            rect,
            6.0,
            egui::Stroke::new(1.5, fill.to_opaque()),
            egui::StrokeKind::Inside,
        );
        painter.text(
            Pos2::new(f.x + 10.0, f.y + TITLE_HEIGHT / 2.0),
            egui::Align2::LEFT_CENTER,
            &f.label,
            egui::FontId::proportional(18.0),
            Color32::WHITE,
        );
    }
}

/// A frame being dragged: where it and its nodes were when the drag started.
pub struct FrameDrag {
    index: usize,
    /// Pointer at the start (screen).
    from: Pos2,
    frame_at: EditorPos,
    nodes: BTreeMap<String, EditorPos>,
    /// The canvas holds still during the drag (else the drag would pan it too).
    pub transform: TSTransform,
}

/// Node rectangles in graph space: where the canvas placed them, at their drawn sizes.
pub fn node_rects(
    placed: &BTreeMap<String, Pos2>,
    sizes: &BTreeMap<String, [f32; 2]>,
) -> BTreeMap<String, Rect> {
    placed
        .iter()
        .map(|(id, p)| {
            let [w, h] = sizes
                .get(id)
                .copied()
                .unwrap_or(crate::arrange::DEFAULT_SIZE);
            (id.clone(), Rect::from_min_size(*p, egui::vec2(w, h)))
        })
        .collect()
}

/// Reads this frame's pointer input for frame drags. `over_node`: a node is under the pointer
/// (nodes are above frames); `free`: nothing (a menu, a popup) covers the canvas there. Returns
/// true while a frame is being dragged, so the canvas ignores the pointer otherwise.
pub fn drag_frames(
    drag: &mut Option<FrameDrag>,
    state: &mut EditorState,
    ctx: &egui::Context,
    to_screen: TSTransform,
    (free, over_node): (bool, bool),
    nodes: &BTreeMap<String, Rect>,
) -> bool {
    let (pressed, down, pos) = ctx.input(|i| {
        (
            i.pointer.primary_pressed(),
            i.pointer.primary_down(),
            i.pointer.interact_pos(),
        )
    });
    let Some(pos) = pos else {
        return drag.is_some();
    };
    if let Some(d) = drag {
        let delta = (pos - d.from) / d.transform.scaling;
        let index = d.index;
        let frame_at = d.frame_at;
        let moved: Vec<(String, EditorPos)> = d
            .nodes
            .iter()
            .map(|(id, p)| (id.clone(), shift(*p, delta)))
            .collect();
        if delta.length() > 0.0 {
            let _ = state.apply(Some("frame-move"), |doc, _| {
                let f = doc.frames.get_mut(index).ok_or("the frame is gone")?;
                (f.x, f.y) = (frame_at.x + delta.x, frame_at.y + delta.y);
                for (id, p) in &moved {
                    hatchery_graph::edit::move_node(doc, id, *p);
                }
                Ok(())
            });
        }
        if !down {
            *drag = None;
            state.end_group();
        }
        return true;
    }
    if !pressed || !free || over_node {
        return false;
    }
    let at = to_screen.inverse() * pos;
    let Some(index) = title_at(state.doc(), state.level(), at) else {
        return false;
    };
    let f = &state.doc().frames[index];
    let area = frame_rect(f);
    *drag = Some(FrameDrag {
        index,
        from: pos,
        frame_at: EditorPos { x: f.x, y: f.y },
        nodes: nodes
            .iter()
            .filter(|(_, r)| area.contains(r.center()))
            .map(|(id, r)| {
                (
                    id.clone(),
                    EditorPos {
                        x: r.min.x,
                        y: r.min.y,
                    },
                )
            })
            .collect(),
        transform: to_screen,
    });
    true
}

fn shift(p: EditorPos, by: egui::Vec2) -> EditorPos {
    EditorPos {
        x: p.x + by.x,
        y: p.y + by.y,
    }
}

impl EditorState {
    /// A new frame around the selected nodes shown (`rects`: shown nodes in graph space), one
    /// undo step; returns its index.
    pub fn frame_selection(&mut self, rects: &BTreeMap<String, Rect>) -> Result<usize, String> {
        let area = self
            .selection
            .iter()
            .filter_map(|id| rects.get(id))
            .fold(Rect::NOTHING, |a, r| a.union(*r));
        if !area.is_positive() {
            self.status = "select the nodes to frame first".into();
            return Err(self.status.clone());
        }
        let min = EditorPos {
            x: area.min.x - PADDING,
            y: area.min.y - PADDING - TITLE_HEIGHT,
        };
        let max = EditorPos {
            x: area.max.x + PADDING,
            y: area.max.y + PADDING,
        };
        let level = self.level.clone();
        self.apply(None, |d, _| {
            Ok(edit::add_frame(d, min, max, level.as_deref()))
        })
    }
}

/// Where the frame being renamed is remembered between frames (egui temporary data).
fn rename_id() -> egui::Id {
    egui::Id::new("hatchery-frame-rename")
}

/// The frame entries of the canvas menu when it was opened on a frame's title bar at `at`.
/// (A context menu closes on any click, so the label is typed in a little window of its own.)
pub fn graph_menu(state: &mut EditorState, ui: &mut Ui, at: Pos2) {
    let Some(index) = title_at(state.doc(), state.level(), at) else {
        return;
    };
    ui.strong(&state.doc().frames[index].label);
    if ui.button("Rename frame…").clicked() {
        ui.ctx().data_mut(|d| d.insert_temp(rename_id(), index));
        ui.close();
    }
    ui.horizontal(|ui| {
        for c in organise::FRAME_COLORS {
            let [r, g, b, _] = c.map(|v| (v * 255.0) as u8);
            let swatch = egui::Button::new("  ").fill(Color32::from_rgb(r, g, b));
            if ui.add(swatch).on_hover_text("frame colour").clicked() {
                let _ = state.apply(None, |d, _| {
                    d.frames[index].color = c;
                    Ok(())
                });
            }
        }
    });
    if ui.button("Delete frame").clicked() {
        let _ = state.apply(None, |d, _| {
            d.frames.remove(index);
            Ok(())
        });
        ui.close();
    }
    ui.separator();
}

/// The *Frame label* window, while a frame is being renamed; typing is one undo step.
pub fn rename_window(ctx: &egui::Context, state: &mut EditorState) {
    let Some(index) = ctx.data(|d| d.get_temp::<usize>(rename_id())) else {
        return;
    };
    let Some(mut label) = state.doc().frames.get(index).map(|f| f.label.clone()) else {
        ctx.data_mut(|d| d.remove::<usize>(rename_id()));
        return;
    };
    let mut open = true;
    let mut done = false;
    egui::Window::new("Frame label")
        .collapsible(false)
        .resizable(false)
        .open(&mut open)
        .show(ctx, |ui| {
            let field = ui.text_edit_singleline(&mut label);
            if field.changed() {
                let key = format!("frame-label:{index}");
                let _ = state.apply(Some(&key), |d, _| {
                    d.frames[index].label = label;
                    Ok(())
                });
            }
            done = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            done |= ui.button("Done").clicked();
        });
    if !open || done {
        ctx.data_mut(|d| d.remove::<usize>(rename_id()));
        state.end_group();
    }
}
