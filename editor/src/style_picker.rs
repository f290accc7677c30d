//! The style picker of `StyleSet` nodes: each style of the set as its lit-sphere thumbnail with
//! its tint; clicking a thumbnail opens the gallery of every procedural style (drawn in that
//! tint) to pick from. PNG styles show their path. Styles can be added, removed and reordered
//! (their order is the style index the transfer functions refer to).

use egui::{TextureHandle, Ui, Vec2};
use hatchery_data::lit_sphere;
use hatchery_nodes::style_set::{DEFAULT_TINT, format_procedural, parse_procedural, split_entries};
use std::collections::HashMap;

/// Side of a thumbnail, pixels (and points); lit-sphere maps are powers of two.
const THUMB: u32 = 64;

/// Lit-sphere thumbnails drawn on the CPU, one texture per (style, tint).
#[derive(Default)]
pub struct Thumbnails {
    textures: HashMap<(String, [u32; 3]), TextureHandle>,
}

impl Thumbnails {
    fn get(&mut self, ctx: &egui::Context, name: &str, tint: [f32; 3]) -> Option<TextureHandle> {
        let key = (name.to_owned(), tint.map(f32::to_bits));
        if let Some(t) = self.textures.get(&key) {
            return Some(t.clone());
        }
        let sphere = lit_sphere::procedural(name, THUMB, tint)?;
        let pixels: Vec<egui::Color32> = sphere
            .texels
            .iter()
            .enumerate()
            .map(|(i, t)| {
                // Texels outside the disk repeat the rim; show the sphere on transparency.
                let (nx, ny) = lit_sphere::texel_normal(THUMB, i as u32 % THUMB, i as u32 / THUMB);
                let inside = nx * nx + ny * ny <= 1.0;
                let c = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
                let a = if inside { c(t[3]) } else { 0 };
                egui::Color32::from_rgba_unmultiplied(c(t[0]), c(t[1]), c(t[2]), a)
            })
            .collect();
        let image = egui::ColorImage {
            size: [THUMB as usize; 2],
            source_size: Vec2::splat(THUMB as f32),
            pixels,
        };
        let handle = ctx.load_texture(
            format!("lit sphere {name}"),
            image,
            egui::TextureOptions::LINEAR,
        );
        self.textures.insert(key, handle.clone());
        Some(handle)
    }
}

/// One entry of the `styles` text.
#[derive(Clone, Debug, PartialEq)]
enum Entry {
    Procedural {
        name: String,
        tint: [f32; 3],
    },
    /// A PNG path, or text the picker does not understand (kept as written).
    Other(String),
}

fn parse(text: &str) -> Vec<Entry> {
    split_entries(text)
        .into_iter()
        .map(|e| {
            let lower = e.to_ascii_lowercase();
            if [".png", ".jpg", ".jpeg"].iter().any(|x| lower.ends_with(x)) {
                return Entry::Other(e);
            }
            match parse_procedural(&e) {
                Ok((name, tint)) if lit_sphere::STYLES.contains(&name.as_str()) => {
                    Entry::Procedural { name, tint }
                }
                _ => Entry::Other(e),
            }
        })
        .collect()
}

fn format(entries: &[Entry]) -> String {
    entries
        .iter()
        .map(|e| match e {
            Entry::Procedural { name, tint } => format_procedural(name, *tint),
            Entry::Other(text) => text.clone(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Name and representative colour (the lit sphere at a normal facing the light) of each style
/// of a `StyleSet`'s `styles` text; PNG entries are grey.
pub fn style_looks(text: &str) -> Vec<(String, [f32; 3])> {
    parse(text)
        .into_iter()
        .map(|e| match e {
            Entry::Procedural { name, tint } => {
                let colour = lit_sphere::procedural(&name, 16, tint)
                    .map(|s| {
                        let t = s.texels[(5 * 16 + 10) as usize];
                        [t[0], t[1], t[2]]
                    })
                    .unwrap_or(tint);
                (name, colour)
            }
            Entry::Other(text) => (text, [0.6; 3]),
        })
        .collect()
}

/// Shows the styles of `text` and returns the new text when the user changed them.
pub fn style_picker(ui: &mut Ui, thumbnails: &mut Thumbnails, text: &str) -> Option<String> {
    let mut entries = parse(text);
    let mut changed = false;
    let mut remove = None;
    let mut swap = None;
    let count = entries.len();
    for (i, entry) in entries.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!("{i}"))
                .on_hover_text("style index (what transfer functions refer to)");
            match entry {
                Entry::Procedural { name, tint } => {
                    let button = match thumbnails.get(ui.ctx(), name, *tint) {
                        Some(t) => ui.add(egui::Button::image_and_text(
                            (t.id(), Vec2::splat(THUMB as f32)),
                            name.as_str(),
                        )),
                        None => ui.button(name.as_str()),
                    };
                    let button =
                        button.on_hover_text(format!("{name}: click to pick another style"));
                    egui::Popup::menu(&button)
                        .id(ui.id().with(("style gallery", i)))
                        .show(|ui| {
                            ui.label("Pick a style");
                            ui.set_max_width(4.0 * (THUMB as f32 + 70.0));
                            ui.horizontal_wrapped(|ui| {
                                for style in lit_sphere::STYLES {
                                    let Some(t) = thumbnails.get(ui.ctx(), style, *tint) else {
                                        continue;
                                    };
                                    let pick = ui
                                        .add(
                                            egui::Button::image_and_text(
                                                (t.id(), Vec2::splat(THUMB as f32)),
                                                *style,
                                            )
                                            .selected(style == name),
                                        )
                                        .clicked();
                                    if pick && style != name {
                                        *name = (*style).to_owned();
                                        changed = true;
                                        ui.close();
                                    }
                                }
                            });
                        });
                    // A copy: the colour button rounds the value through HSV every frame.
                    let mut edited = *tint;
                    if ui
                        .color_edit_button_rgb(&mut edited)
                        .on_hover_text("tint of the style")
                        .changed()
                    {
                        *tint = edited;
                        changed = true;
                    }
                }
                Entry::Other(text) => {
                    ui.label(text.as_str())
                        .on_hover_text("a PNG lit-sphere map");
                }
            }
            if i > 0 && ui.small_button("↑").on_hover_text("move up").clicked() {
                swap = Some(i);
            }
            if count > 1 && ui.small_button("✕").on_hover_text("remove").clicked() {
                remove = Some(i);
            }
        });
    }
    if let Some(i) = swap {
        entries.swap(i - 1, i);
        changed = true;
    }
    if let Some(i) = remove {
        entries.remove(i);
        changed = true;
    }
    if ui.button("+ Add style").clicked() {
        entries.push(Entry::Procedural {
            name: "shaded".into(),
            tint: DEFAULT_TINT,
        });
        changed = true;
    }
    changed.then(|| format(&entries))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn styles_text_round_trips_and_keeps_what_it_does_not_understand() {
        let text = "gooch:0.6,0.7,0.9, toon3:0.9,0.45,0.35, maps/ink.png";
        let entries = parse(text);
        assert_eq!(entries.len(), 3);
        assert_eq!(
            entries[0],
            Entry::Procedural {
                name: "gooch".into(),
                tint: [0.6, 0.7, 0.9]
            }
        );
        assert_eq!(entries[2], Entry::Other("maps/ink.png".into()));
        assert_eq!(format(&entries), text);
        // A name without a tint gets the default tint written out.
        assert_eq!(format(&parse("toon2")), "toon2:0.85,0.85,0.85");
    }
}
