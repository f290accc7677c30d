//! The viewport: the rendered picture, its placement and zoom, and the Camera node driven by
//! dragging and scrolling in it.

use super::{Panel, node_param};
use crate::app::EditorApp;
use crate::state::EditorState;
use egui::{Color32, Ui};
use hatchery_graph::ParamValue;

/// The viewport (beside the canvas, instead of it, or filling the window).
pub struct Viewport;

impl Panel for Viewport {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui) {
        use crate::picture::Placement;
        let target = app.preview.target(app.state.doc());
        ui.horizontal(|ui| {
            ui.heading("Viewport");
            let placement = &mut app.picture.placement;
            let maximised = *placement == Placement::Maximised;
            if ui
                .selectable_label(maximised, "⛶ Maximise")
                .on_hover_text("the picture instead of the canvas")
                .clicked()
            {
                *placement = if maximised {
                    Placement::Beside
                } else {
                    Placement::Maximised
                };
            }
            if ui
                .selectable_label(*placement == Placement::FullWindow, "Full window (F11)")
                .on_hover_text("the picture fills the window; Esc or F11 leaves")
                .clicked()
            {
                *placement = if *placement == Placement::FullWindow {
                    Placement::Beside
                } else {
                    Placement::FullWindow
                };
            }
            paint_toggle(app, ui);
            if app.picture.is_zoomed() {
                ui.label(format!("picture {:.1}×", app.picture.zoom));
                if ui.button("Fit").clicked() {
                    app.picture.fit();
                }
            }
        });
        ui.label(match &target {
            Some((n, p)) => format!("showing {n}.{p}"),
            None => "nothing to show".into(),
        })
        .on_hover_text(
            "drag: orbit the camera; right/middle/Shift-drag: pan it; wheel: its distance. \
             Alt+wheel / Alt+drag: zoom / move the picture itself (the camera stays)",
        );
        if app.preview.chosen.is_some() && ui.button("Show the SaveImage input").clicked() {
            app.preview.chosen = None;
        }
        ui.horizontal(|ui| {
            ui.checkbox(&mut app.preview.show_times, "Node times")
                .on_hover_text("Show each node's last CPU and GPU time on the canvas");
            if app.preview.refining {
                ui.label("refining…").on_hover_text(
                    "a streamed volume is shown at its preview level while the region this \
                     view needs is read at full resolution",
                );
            } else if app.preview.is_busy() {
                // No spinner: it would repaint the UI all the time the frame renders.
                ui.label("rendering…");
            } else if let Some((elapsed, adapter)) = &app.preview.last_render {
                ui.label(format!("{:.1} ms", elapsed.as_secs_f64() * 1e3))
                    .on_hover_text(format!(
                        "wall time of the last render on the render thread, on {adapter}"
                    ));
            }
        });
        // The picture fills the space left (its size follows the panel).
        let size = ui.available_size().max(egui::vec2(64.0, 48.0));
        if app.preview_enabled {
            let ppp = ui.ctx().pixels_per_point();
            let (w, h) = ((size.x * ppp) as u32, (size.y * ppp) as u32);
            app.preview.update(ui.ctx(), &mut app.state, w, h);
        }
        if let Some(e) = &app.preview.error {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        let sense = egui::Sense::drag();
        let response = match &app.preview.viewport {
            Some(shown) => {
                let mut image = egui::Image::new((shown.id(), size)).uv(app.picture.uv_rect());
                if app.picture.is_zoomed() {
                    // Pixels as squares when inspecting hatching up close.
                    image = image.texture_options(egui::TextureOptions::NEAREST);
                }
                ui.add(image.sense(sense))
            }
            None => ui.allocate_response(size, sense),
        };
        app.viewport_rect = response.rect;
        // While a newer picture renders, the one shown is dimmed and says so on itself (a small
        // label beside the checkbox went unnoticed during 8–18 s CPU renders).
        app.picture_stale = app.preview.is_busy();
        if app.picture_stale {
            crate::render_progress::draw(ui, response.rect, app.preview.progress());
        }
        // Alt: the picture's own zoom and pan; otherwise the camera.
        if ui.input(|i| i.modifiers.alt) {
            if response.dragged() {
                app.picture.pan(response.drag_delta(), response.rect);
            }
            if let Some(at) = response.hover_pos() {
                let scroll = ui.input(|i| i.smooth_scroll_delta.y + i.smooth_scroll_delta.x);
                if scroll != 0.0 {
                    app.picture
                        .zoom_at((scroll * 0.004).exp(), at, response.rect);
                }
            }
        } else if app.preview.paint {
            paint_on_picture(app, ui, &response);
        } else {
            orbit_camera(app, ui, &response);
        }
    }
}

/// The paint tool's switch, where the graph has a `PaintLabels` node to paint into.
fn paint_toggle(app: &mut EditorApp, ui: &mut Ui) {
    let Some(node) = crate::paint::painter(&app.state) else {
        app.preview.paint = false;
        return;
    };
    let on = app.preview.paint;
    if ui
        .selectable_label(on, "✏ Paint")
        .on_hover_text(format!(
            "drag over the picture to paint into {node} where the pointer meets the first \
             visible surface (Ctrl-drag erases); brush radius and id are {node}'s parameters. \
             Off: dragging orbits the camera again"
        ))
        .clicked()
    {
        app.preview.paint = !on;
    }
}

/// A drag with the paint tool on: a dab wherever the pointer meets a surface, spaced by half
/// the brush radius; one drag is one undo step.
fn paint_on_picture(app: &mut EditorApp, ui: &Ui, response: &egui::Response) {
    if response.drag_stopped() {
        app.state.end_group();
        app.last_dab = None;
    }
    if !response.dragged_by(egui::PointerButton::Primary) {
        return;
    }
    let (Some(at), Some(depth), Some(node)) = (
        response.interact_pointer_pos(),
        app.preview.depth.as_ref(),
        crate::paint::painter(&app.state),
    ) else {
        return;
    };
    // The pointer in the frame's pixels, through the picture's own zoom and pan.
    let uv = app.picture.uv_rect();
    let rect = response.rect;
    let u = uv.min.x + (at.x - rect.min.x) / rect.width() * uv.width();
    let v = uv.min.y + (at.y - rect.min.y) / rect.height() * uv.height();
    let Some(world) = depth.world_at(u * depth.width as f32, v * depth.height as f32) else {
        return;
    };
    let erase = ui.input(|i| i.modifiers.command);
    let spaced = app
        .last_dab
        .is_none_or(|(last, radius)| last.distance(world) >= 0.5 * radius);
    if spaced && let Ok(radius) = crate::paint::add_dab(&mut app.state, &node, world, erase) {
        app.last_dab = Some((world, radius));
    }
}

/// Dragging in the viewport orbits the graph's Camera node (azimuth, elevation), dragging
/// with the right or middle button (or with Shift) pans its target, the wheel zooms
/// (distance); one drag or one burst of scrolling is one undo step. A camera that frames
/// its data (issue 25) keeps framing: the pan moves `pan_x`/`pan_y` (fractions of the
/// frame) and the wheel scales `fill`, so the view survives a change of data.
fn orbit_camera(app: &mut EditorApp, ui: &Ui, response: &egui::Response) {
    let Some(camera) = viewport_camera(app.state.doc()) else {
        return;
    };
    let current = |state: &EditorState, name: &str| camera_param(state, &camera, name);
    let framing = camera_choice(&app.state, &camera, "framing").as_deref() != Some("fixed")
        && app.state.doc().edges.iter().any(|e| e.to.0 == camera);
    let panning = response.dragged_by(egui::PointerButton::Secondary)
        || response.dragged_by(egui::PointerButton::Middle)
        || (response.dragged_by(egui::PointerButton::Primary) && ui.input(|i| i.modifiers.shift));
    let delta = response.drag_delta();
    if panning && delta != egui::Vec2::ZERO {
        let values = if framing {
            // The scene follows the pointer: the target moves the other way, in frame sizes.
            let across = response.rect.size().min_elem().max(1.0) as f64;
            let pan = |name: &str, by: f64| {
                ParamValue::Float((current(&app.state, name) + by).clamp(-10.0, 10.0))
            };
            vec![
                ("pan_x", pan("pan_x", -delta.x as f64 / across)),
                ("pan_y", pan("pan_y", delta.y as f64 / across)),
            ]
        } else {
            let target = pan_target(&app.state, &camera, delta, response.rect.size());
            vec![("target", ParamValue::Vec3(target))]
        };
        let _ = app.state.set_params(&camera, &values, "viewport pan");
    } else if !panning && response.dragged() && delta != egui::Vec2::ZERO {
        orbit_by(&mut app.state, &camera, delta);
    }
    if response.drag_stopped() {
        app.state.end_group();
    }
    let scroll = ui.input(|i| i.smooth_scroll_delta.y);
    if response.hovered() && scroll != 0.0 {
        let zoom = (scroll as f64 * 0.002).exp();
        let value = if framing {
            (
                "fill",
                (current(&app.state, "fill") * zoom).clamp(0.05, 20.0),
            )
        } else {
            (
                "distance",
                (current(&app.state, "distance") / zoom).max(1e-3),
            )
        };
        let values = [(value.0, ParamValue::Float(value.1))];
        let _ = app.state.set_params(&camera, &values, "viewport zoom");
    }
}

/// The Camera target after panning by `delta` screen points in a viewport of `size` points:
/// the scene follows the pointer (at the target's depth; the field of view spans the shorter
/// side).
fn pan_target(state: &EditorState, camera: &str, delta: egui::Vec2, size: egui::Vec2) -> [f64; 3] {
    let get = |name: &str| camera_param(state, camera, name) as f32;
    let up_z = camera_choice(state, camera, "up").as_deref() == Some("z");
    let orbit = hatchery_nodes::camera::Camera::orbit(
        glam::Vec3::ZERO,
        get("azimuth"),
        get("elevation"),
        get("distance"),
        get("fov"),
        false,
        0.1,
        10.0,
        up_z,
        1,
        1,
    );
    // Rows of the view matrix are the camera's right and up axes in world space.
    let right = orbit.view.row(0).truncate();
    let up = orbit.view.row(1).truncate();
    let world_per_point =
        2.0 * get("distance") * (get("fov").to_radians() / 2.0).tan() / size.min_elem().max(1.0);
    let shift = (-right * delta.x + up * delta.y) * world_per_point;
    let target = camera_target(state, camera);
    [0, 1, 2].map(|i| target[i] + shift[i] as f64)
}

/// The Camera node the viewport drives: the first one by id.
fn viewport_camera(doc: &hatchery_graph::GraphDocument) -> Option<String> {
    let mut cameras: Vec<&str> = doc
        .nodes
        .iter()
        .filter(|n| n.kind == "Camera")
        .map(|n| n.id.as_str())
        .collect();
    cameras.sort();
    cameras.first().map(|id| id.to_string())
}

/// A Camera parameter as the graph will use it.
fn camera_value(state: &EditorState, camera: &str, name: &str) -> Option<ParamValue> {
    let node = state.doc().nodes.iter().find(|n| n.id == camera)?;
    node_param(state, node, name)
}

/// Turns the camera by a viewport drag of `delta` points (0.4° a point; one undo group).
fn orbit_by(state: &mut EditorState, camera: &str, delta: egui::Vec2) {
    // Rounded to 1/1000 degree, so the file says `elevation: 9.0`, not 8.999999999999995.
    let round = |x: f64| (x * 1000.0).round() / 1000.0;
    let azimuth = round(
        (camera_param(state, camera, "azimuth") - delta.x as f64 * 0.4 + 180.0).rem_euclid(360.0)
            - 180.0,
    );
    let elevation =
        round((camera_param(state, camera, "elevation") + delta.y as f64 * 0.4).clamp(-89.0, 89.0));
    let values = [
        ("azimuth", ParamValue::Float(azimuth)),
        ("elevation", ParamValue::Float(elevation)),
    ];
    let _ = state.set_params(camera, &values, "viewport orbit");
}

fn camera_param(state: &EditorState, camera: &str, name: &str) -> f64 {
    match camera_value(state, camera, name) {
        Some(ParamValue::Float(x)) => x,
        _ => 0.0,
    }
}

fn camera_choice(state: &EditorState, camera: &str, name: &str) -> Option<String> {
    match camera_value(state, camera, name) {
        Some(ParamValue::Choice(c)) => Some(c),
        _ => None,
    }
}

fn camera_target(state: &EditorState, camera: &str) -> [f64; 3] {
    match camera_value(state, camera, "target") {
        Some(ParamValue::Vec3(v)) => v,
        _ => [0.0; 3],
    }
}
