//! The add-node palette: right-click on the canvas, or drop a wire on empty canvas, and type.
//!
//! Why not snarl's context menu itself: egui menus close on *any* click, including one in their
//! own search field, and nothing in a menu has the keyboard when it opens, so typing went
//! nowhere. Snarl's menu now only opens this palette at its place (and closes); the palette
//! keeps the keyboard in its search field, filters as the user types, moves with ↑/↓, adds the
//! highlighted kind with Enter, and closes on Escape, a pick, or a click outside it.

use crate::state::EditorState;
use egui::{Id, Key, Pos2, Rect, Ui};
use hatchery_graph::{EditorPos, PortType, SchemaLookup};

/// One end of a wire dropped on empty canvas: node, port, and whether it is an output.
#[derive(Clone, Debug)]
pub struct DroppedWire {
    pub ends: Vec<(String, String)>,
    /// The dragged pins are outputs (the new node takes the wire on an input).
    pub output: bool,
    /// The wire's type (`None`: a reroute that carries nothing yet; only *Reroute* fits).
    pub ty: Option<PortType>,
}

/// An open palette.
#[derive(Clone, Debug)]
pub struct Palette {
    /// Top-left corner on screen (points).
    pub screen: Pos2,
    /// Where a new node goes (graph units).
    pub at: Pos2,
    pub wire: Option<DroppedWire>,
    pub search: String,
    /// Index of the highlighted kind among the matches.
    pub highlight: usize,
    opened_pass: u64,
    /// The palette's rectangle last frame (a click outside closes it).
    rect: Option<Rect>,
}

impl Palette {
    pub fn new(ctx: &egui::Context, screen: Pos2, at: Pos2, wire: Option<DroppedWire>) -> Self {
        Palette {
            screen,
            at,
            wire,
            search: String::new(),
            highlight: 0,
            opened_pass: ctx.cumulative_pass_nr(),
            rect: None,
        }
    }
}

/// What the user chose.
enum Choice {
    Kind(&'static str),
    Reroute,
    Paste,
}

/// The kinds whose name contains `needle` (case-insensitive), names starting with it first, in
/// catalogue order otherwise.
pub fn matches(kinds: &[&'static str], needle: &str) -> Vec<&'static str> {
    let needle = needle.trim().to_lowercase();
    let mut starts: Vec<&'static str> = Vec::new();
    let mut inside: Vec<&'static str> = Vec::new();
    for &k in kinds {
        let lower = k.to_lowercase();
        if lower.starts_with(&needle) {
            starts.push(k);
        } else if lower.contains(&needle) {
            inside.push(k);
        }
    }
    starts.extend(inside);
    starts
}

fn search_id() -> Id {
    Id::new("hatchery-add-node-search")
}

/// Draws the open palette (if any) and applies what the user picks. Returns the screen
/// rectangles of the search field and of the listed kinds (for the scripted X11 check).
pub fn show(
    ctx: &egui::Context,
    open: &mut Option<Palette>,
    state: &mut EditorState,
    clipboard: &str,
) -> Vec<(String, Rect)> {
    let mut shown = Vec::new();
    let Some(p) = open.as_mut() else {
        return shown;
    };
    let kinds: Vec<&'static str> = match &p.wire {
        None => state.registry.kinds(),
        Some(DroppedWire {
            ty: Some(ty),
            output,
            ..
        }) => hatchery_graph::edit::compatible_kinds(&state.registry, *ty, *output),
        Some(_) => Vec::new(),
    };
    let found = matches(&kinds, &p.search);
    // Keys first, so the list drawn below shows their effect this frame.
    let (up, down, enter, escape) = ctx.input(|i| {
        (
            i.key_pressed(Key::ArrowUp),
            i.key_pressed(Key::ArrowDown),
            i.key_pressed(Key::Enter),
            i.key_pressed(Key::Escape),
        )
    });
    if down {
        p.highlight = (p.highlight + 1).min(found.len().saturating_sub(1));
    }
    if up {
        p.highlight = p.highlight.saturating_sub(1);
    }
    p.highlight = p.highlight.min(found.len().saturating_sub(1));

    let mut choice = enter
        .then(|| found.get(p.highlight).copied().map(Choice::Kind))
        .flatten();
    let area = egui::Area::new(Id::new("hatchery-add-node"))
        .order(egui::Order::Foreground)
        .fixed_pos(p.screen)
        .constrain(true)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(260.0);
                if p.wire.is_none() {
                    crate::frames::graph_menu(state, ui, p.at);
                }
                let field = ui.add(
                    egui::TextEdit::singleline(&mut p.search)
                        .id(search_id())
                        .hint_text("type to search")
                        .desired_width(240.0),
                );
                // The keyboard stays in the field while the palette is open.
                field.request_focus();
                if field.changed() {
                    p.highlight = 0;
                }
                shown.push(("add-node:search".to_owned(), field.rect));
                let heading = match &p.wire {
                    Some(DroppedWire { ty: Some(ty), .. }) => format!("Add a node taking {ty}"),
                    _ => "Add node".to_owned(),
                };
                ui.label(heading);
                egui::ScrollArea::vertical()
                    .max_height(300.0)
                    .show(ui, |ui| {
                        kind_list(ui, state, &found, p.highlight, &mut choice, &mut shown);
                    });
                ui.separator();
                if ui.button("Add reroute").clicked() {
                    choice = Some(Choice::Reroute);
                }
                if p.wire.is_none() && !clipboard.is_empty() && ui.button("Paste").clicked() {
                    choice = Some(Choice::Paste);
                }
            });
        });
    let rect = area.response.rect;
    let pressed_outside = ctx.cumulative_pass_nr() > p.opened_pass
        && ctx.input(|i| {
            i.pointer.any_pressed()
                && i.pointer
                    .interact_pos()
                    .is_some_and(|pos| !rect.contains(pos))
        });
    p.rect = Some(rect);
    let closed_inside = area.response.should_close();
    if let Some(choice) = choice {
        apply(state, p, choice, clipboard);
        *open = None;
    } else if escape || pressed_outside || closed_inside {
        *open = None;
    }
    if open.is_none() {
        ctx.memory_mut(|m| m.surrender_focus(search_id()));
    }
    shown
}

fn kind_list(
    ui: &mut Ui,
    state: &EditorState,
    found: &[&'static str],
    highlight: usize,
    choice: &mut Option<Choice>,
    shown: &mut Vec<(String, Rect)>,
) {
    if found.is_empty() {
        ui.weak("no node kind matches");
    }
    for (i, &kind) in found.iter().enumerate() {
        let doc = state.registry.schema(kind).map_or("", |s| s.doc);
        let r = ui.selectable_label(i == highlight, kind);
        if i == highlight {
            r.scroll_to_me(None);
        }
        shown.push((format!("add-node:{kind}"), r.rect));
        if r.on_hover_text(doc).clicked() {
            *choice = Some(Choice::Kind(kind));
        }
    }
}

fn editor_pos(p: Pos2) -> EditorPos {
    EditorPos { x: p.x, y: p.y }
}

/// Adds what was chosen; a node added from a dropped wire is wired to it on its first port of
/// the wire's type.
fn apply(state: &mut EditorState, p: &Palette, choice: Choice, clipboard: &str) {
    let at = editor_pos(p.at);
    match choice {
        Choice::Paste => {
            let _ = state.paste(clipboard, at);
        }
        Choice::Reroute => {
            let Ok(r) = state.add_reroute(crate::groups::reroute_pos(p.at)) else {
                return;
            };
            if let Some(wire) = &p.wire {
                for (id, name) in &wire.ends {
                    let _ = if wire.output {
                        state.connect((id, name), (&r, hatchery_graph::reroute::IN))
                    } else {
                        state.connect((&r, hatchery_graph::reroute::OUT), (id, name))
                    };
                }
            }
        }
        Choice::Kind(kind) => {
            let Ok(new) = state.add_node(kind, at) else {
                return;
            };
            let Some(wire) = &p.wire else {
                return;
            };
            let (Some(ty), Some(schema)) = (wire.ty, state.registry.schema(kind).cloned()) else {
                return;
            };
            let ports = if wire.output {
                &schema.inputs
            } else {
                &schema.outputs
            };
            if let Some(port) = ports.iter().find(|port| port.ty == ty) {
                for (id, name) in &wire.ends {
                    let _ = if wire.output {
                        state.connect((id, name), (&new, port.name))
                    } else {
                        state.connect((&new, port.name), (id, name))
                    };
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::matches;

    #[test]
    fn names_starting_with_the_search_come_first() {
        let kinds = [
            "GBuffer",
            "Silhouette",
            "SilhouetteHull",
            "PerturbedSilhouette",
        ];
        assert_eq!(
            matches(&kinds, "SILH"),
            ["Silhouette", "SilhouetteHull", "PerturbedSilhouette"]
        );
        assert_eq!(matches(&kinds, " "), kinds);
        assert!(matches(&kinds, "zzz").is_empty());
    }
}
