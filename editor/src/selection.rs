//! Node selection on the canvas by the mouse, owned by the editor.
//!
//! egui-snarl 0.12 selects a node only on Shift-click, keeps its selection in private
//! temporary data, and treats Shift/Ctrl as its own modifiers (rectangle select, wire
//! re-routing). A plain click therefore never selected anything (the bug behind "clicking a node
//! does not select it"). Here the editor decides: it records where every node was drawn this
//! frame (`SnarlViewer::final_node_rect`), reads the frame's pointer input itself, and keeps the
//! selection in [`crate::EditorState`]; snarl is shown with the modifiers hidden so its own
//! selection never starts. The selected nodes are drawn with a highlighted frame by the viewer.
//!
//! | input | effect |
//! |---|---|
//! | click a node (anywhere on it) | select only it |
//! | Shift-click a node | add it to the selection |
//! | Ctrl-click (⌘ on macOS) a node | toggle it |
//! | Shift-drag on empty canvas | box select (replaces; with Ctrl too: adds) |
//! | click on empty canvas, `Esc` | clear |

use egui::{Color32, Modifiers, Pos2, Rect, Stroke};

/// How a click changes the selection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClickMode {
    /// Select only the clicked node.
    Replace,
    /// Add the clicked node.
    Add,
    /// Toggle the clicked node.
    Toggle,
}

impl ClickMode {
    pub fn from_modifiers(m: Modifiers) -> Self {
        if m.command || m.ctrl {
            ClickMode::Toggle
        } else if m.shift {
            ClickMode::Add
        } else {
            ClickMode::Replace
        }
    }
}

/// What the canvas's pointer input did to the selection this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum SelectionChange {
    /// A click on a node.
    Click { node: String, mode: ClickMode },
    /// A click on empty canvas (clears, unless a modifier was held).
    ClickEmpty,
    /// A finished box: the nodes it touches; `add` keeps the old selection.
    Box { nodes: Vec<String>, add: bool },
}

/// The canvas's selection input state, carried between frames.
#[derive(Default)]
pub struct CanvasSelection {
    /// Node rectangles drawn this frame, in graph space and in draw order (last is on top).
    rects: Vec<(String, Rect)>,
    /// A box selection in progress: its start, in screen space.
    box_from: Option<Pos2>,
    /// The canvas transform when the box started (held still while the box is dragged).
    pub box_transform: Option<egui::emath::TSTransform>,
}

impl CanvasSelection {
    /// Forget last frame's node rectangles (called before the canvas is drawn).
    pub fn begin_frame(&mut self) {
        self.rects.clear();
    }

    /// Sizes (graph units) of the nodes drawn last frame.
    pub fn sizes(&self) -> std::collections::BTreeMap<String, [f32; 2]> {
        self.rects
            .iter()
            .map(|(id, r)| (id.clone(), [r.width(), r.height()]))
            .collect()
    }

    /// Records where node `id` was drawn (graph space).
    pub fn node_drawn(&mut self, id: &str, rect: Rect) {
        self.rects.push((id.to_owned(), rect));
    }

    /// The topmost node under a screen position.
    pub fn node_at(&self, to_screen: egui::emath::TSTransform, at: Pos2) -> Option<&str> {
        self.rects
            .iter()
            .rev()
            .find(|(_, r)| (to_screen * *r).contains(at))
            .map(|(id, _)| id.as_str())
    }

    /// Screen rectangle of a node as drawn this frame.
    pub fn node_rect(&self, to_screen: egui::emath::TSTransform, id: &str) -> Option<Rect> {
        self.rects
            .iter()
            .find(|(n, _)| n == id)
            .map(|(_, r)| to_screen * *r)
    }

    /// Whether a box selection is being dragged.
    pub fn boxing(&self) -> bool {
        self.box_from.is_some()
    }

    /// Reads this frame's pointer input over the canvas. `canvas` is the canvas's screen
    /// rectangle; `free` says whether the pointer is over the canvas itself (no menu, window or
    /// popup above it); `modifiers` are the real ones (snarl saw none).
    pub fn update(
        &mut self,
        ctx: &egui::Context,
        canvas: Rect,
        free: bool,
        to_screen: egui::emath::TSTransform,
        modifiers: Modifiers,
    ) -> Option<SelectionChange> {
        let (pressed, released, clicked, pos) = ctx.input(|i| {
            (
                i.pointer.primary_pressed(),
                i.pointer.primary_released(),
                i.pointer.primary_clicked(),
                i.pointer.interact_pos(),
            )
        });
        let pos = pos?;
        if let Some(from) = self.box_from {
            if released || !ctx.input(|i| i.pointer.primary_down()) {
                self.box_from = None;
                self.box_transform = None;
                let area = Rect::from_two_pos(from, pos);
                let nodes = self
                    .rects
                    .iter()
                    .filter(|(_, r)| area.intersects(to_screen * *r))
                    .map(|(id, _)| id.clone())
                    .collect();
                let add = modifiers.command || modifiers.ctrl;
                return Some(SelectionChange::Box { nodes, add });
            }
            self.paint_box(ctx, canvas, Rect::from_two_pos(from, pos));
            return None;
        }
        if !free || !canvas.contains(pos) {
            return None;
        }
        let under = self.node_at(to_screen, pos).map(str::to_owned);
        if pressed && modifiers.shift && under.is_none() {
            self.box_from = Some(pos);
            self.box_transform = Some(to_screen);
            return None;
        }
        if !clicked {
            return None;
        }
        Some(match under {
            Some(node) => SelectionChange::Click {
                node,
                mode: ClickMode::from_modifiers(modifiers),
            },
            None => SelectionChange::ClickEmpty,
        })
    }

    fn paint_box(&self, ctx: &egui::Context, canvas: Rect, area: Rect) {
        let layer = egui::LayerId::new(egui::Order::Foreground, egui::Id::new("box-select"));
        let painter = ctx.layer_painter(layer).with_clip_rect(canvas);
        let accent = ctx.global_style().visuals.selection.stroke.color;
        painter.rect(
            area,
            0.0,
            accent.gamma_multiply(0.15),
            Stroke::new(1.0, accent),
            egui::StrokeKind::Inside,
        );
    }
}

/// The frame stroke of a selected node.
pub fn selected_stroke() -> Stroke {
    Stroke::new(2.5, Color32::from_rgb(90, 170, 255))
}

/// The frame colour of the node the Inspector shows (the last clicked).
pub fn active_color() -> Color32 {
    Color32::from_rgb(255, 200, 80)
}
