//! VolumeShop's visual conventions (Bruckner & Gröller 2005, §6.3): the geometry of the arrows,
//! fans and bounding boxes that show how a selection relates to its ghost (the `Arrow`, `Fan`
//! and `BoundingBox` nodes, arrow.rs, fan.rs, bounding_box.rs, draw it with the overlay renderer
//! [`crate::overlay::Canvas`]; SaveSvg writes it as paths).
//!
//! Each node reads the first two anchors of its `annotations` input: anchor 0 is the ghost (the
//! object's original place), anchor 1 the selection (where it is now), with their world boxes
//! as bounds (`SelectionRender` makes such annotations). Points are projected with the camera
//! to the image's pixels (top-left origin, y down).

use crate::annotations::Annotations;
use crate::camera::Camera;
use crate::overlay::Canvas;
use crate::value::Image;
use crate::{Ctx, Value};
use glam::{Mat4, Vec2, Vec3, Vec4};
use hatchery_annotation::{box_corners, convex_hull};
use hatchery_graph::{NodeError, NodeInputs, PortSpec, PortType};
use std::sync::Arc;

/// Anchor 0 is the ghost, anchor 1 the selection.
const ROLES: [&str; 2] = ["ghost", "selection"];

/// The three inputs every convention node takes: image, annotations, camera.
type Inputs = (Arc<Image>, Arc<Annotations>, Arc<Camera>);

pub(crate) fn inputs_of(inputs: &NodeInputs<Value>) -> Result<Inputs, NodeError> {
    Ok((
        inputs.require("image")?.image("image")?.clone(),
        inputs
            .require("annotations")?
            .annotations("annotations")?
            .clone(),
        inputs.require("camera")?.camera("camera")?.clone(),
    ))
}

pub(crate) fn ports(doc_annotations: &'static str) -> Vec<PortSpec> {
    vec![
        PortSpec::input("image", PortType::Image, "the picture to draw over"),
        PortSpec::input("annotations", PortType::Annotations, doc_annotations),
        PortSpec::input(
            "camera",
            PortType::Camera,
            "the view the picture was rendered with",
        ),
    ]
}

pub(crate) fn output() -> Vec<PortSpec> {
    vec![PortSpec::output(
        "image",
        PortType::Image,
        "the picture with the drawing",
    )]
}

/// The world position of anchor `i` (0 ghost, 1 selection), or an error naming the port.
fn anchor_position(annotations: &Annotations, i: usize) -> Result<Vec3, NodeError> {
    annotations
        .anchors
        .get(i)
        .map(|a| a.position)
        .ok_or_else(|| {
            NodeError::at_port(
                "annotations",
                format!(
                    "needs anchor {i} (the {}), there are {} anchors",
                    ROLES[i],
                    annotations.anchors.len()
                ),
            )
        })
}

/// The world box of anchor `i`, or an error naming the port.
fn anchor_box(annotations: &Annotations, i: usize) -> Result<[Vec3; 2], NodeError> {
    anchor_position(annotations, i)?;
    annotations.bounds.get(i).copied().flatten().ok_or_else(|| {
        NodeError::at_port(
            "annotations",
            format!("anchor {i} (the {}) has no world box", ROLES[i]),
        )
    })
}

/// World to pixels for an image of `frame` pixels: NDC (−1…1, y up) to (0…w, 0…h, y down).
struct Projector {
    view: Mat4,
    view_proj: Mat4,
    frame: Vec2,
}

impl Projector {
    fn new(camera: &Camera, width: u32, height: u32) -> Self {
        Self {
            view: camera.view,
            view_proj: camera.view_proj(),
            frame: Vec2::new(width as f32, height as f32),
        }
    }

    fn clip(&self, p: Vec3) -> Vec4 {
        self.view_proj * p.extend(1.0)
    }

    fn to_pixels(&self, clip: Vec4) -> Vec2 {
        let ndc = clip.truncate() / clip.w;
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * self.frame.x,
            (1.0 - ndc.y) * 0.5 * self.frame.y,
        )
    }

    /// Pixels of a point in front of the near plane, else `None`.
    fn pixels(&self, p: Vec3) -> Option<Vec2> {
        let c = self.clip(p);
        (c.z >= 0.0 && c.w > f32::EPSILON).then(|| self.to_pixels(c))
    }

    /// The segment a–b clipped to the near plane (clip z ≥ 0) in pixels, or `None` when it
    /// lies wholly behind it.
    fn segment(&self, a: Vec3, b: Vec3) -> Option<[Vec2; 2]> {
        let (mut ca, mut cb) = (self.clip(a), self.clip(b));
        if ca.z < 0.0 && cb.z < 0.0 {
            return None;
        }
        if ca.z < 0.0 || cb.z < 0.0 {
            let t = ca.z / (ca.z - cb.z);
            let on_plane = ca.lerp(cb, t);
            if ca.z < 0.0 {
                ca = on_plane;
            } else {
                cb = on_plane;
            }
        }
        (ca.w > f32::EPSILON && cb.w > f32::EPSILON)
            .then(|| [self.to_pixels(ca), self.to_pixels(cb)])
    }

    /// View-space z (world units, larger is nearer the viewer).
    fn view_z(&self, p: Vec3) -> f32 {
        (self.view * p.extend(1.0)).z
    }

    /// Pixels per world unit in the plane facing the viewer through `p`.
    fn pixels_per_unit(&self, p: Vec3) -> Option<f32> {
        let right = self.view.row(0).truncate().normalize_or_zero();
        let (a, b) = (self.pixels(p)?, self.pixels(p + right)?);
        Some(a.distance(b))
    }

    /// The screen rectangle (min, max) around the projected corners of a world box in front of
    /// the near plane; `None` when no corner is.
    fn rect(&self, [lo, hi]: [Vec3; 2]) -> Option<(Vec2, Vec2)> {
        let points: Vec<Vec2> = box_corners(lo, hi)
            .iter()
            .filter_map(|&c| self.pixels(c))
            .collect();
        let min = points.iter().copied().reduce(Vec2::min)?;
        let max = points.iter().copied().reduce(Vec2::max)?;
        Some((min, max))
    }
}

pub(crate) fn draw(
    ctx: &mut Ctx,
    canvas: Canvas,
    image: &Arc<Image>,
) -> Result<Vec<Value>, NodeError> {
    Ok(vec![canvas.draw_over(ctx, image, "image")?])
}

/// The arrow's centre line from `from` to `to`, pixels: a cubic Bézier whose control points are
/// both moved by `bulge / 0.75` pixels to the left of the direction of travel (on screen), so
/// that the curve's greatest distance from the chord is `bulge` (negative: to the right). Where
/// the chord is shorter than that, the control points also spread apart along the chord, so an
/// arrow between nearby points becomes a visible loop instead of a stub.
pub fn arrow_path(from: Vec2, to: Vec2, bulge: f32, samples: usize) -> Vec<Vec2> {
    let chord = to - from;
    let length = chord.length();
    let along = if length > 1e-3 {
        chord / length
    } else {
        Vec2::X
    };
    // Left of travel with y down: the direction rotated by −90° on screen.
    let left = Vec2::new(along.y, -along.x);
    let offset = bulge / 0.75;
    let spread = (offset.abs() - length).max(0.0) * 0.5;
    let c1 = from + left * offset - along * spread;
    let c2 = to + left * offset + along * spread;
    (0..=samples)
        .map(|i| {
            let t = i as f32 / samples as f32;
            let s = 1.0 - t;
            from * (s * s * s) + c1 * (3.0 * s * s * t) + c2 * (3.0 * s * t * t) + to * (t * t * t)
        })
        .collect()
}

/// An arrow on screen (pixels): its shaft polyline and its head triangle (tip first).
pub type ArrowShape = (Vec<Vec2>, [Vec2; 3]);

/// The arrow from the ghost (anchor 0) to the selection (anchor 1) in a `frame` of pixels seen
/// by `camera`: its shaft (a polyline, `width` px wide when drawn) and its head (a triangle with
/// the tip at the selection), bent by `curvature` × the depth difference in pixels (see
/// `Arrow`'s doc). `None` when either anchor is behind the camera; an error when the anchors are
/// missing.
pub fn arrow_shape(
    annotations: &Annotations,
    camera: &Camera,
    (w, h): (u32, u32),
    width: f32,
    curvature: f32,
) -> Result<Option<ArrowShape>, NodeError> {
    let (ghost, selection) = (
        anchor_position(annotations, 0)?,
        anchor_position(annotations, 1)?,
    );
    let view = Projector::new(camera, w, h);
    let (Some(from), Some(to), Some(scale)) = (
        view.pixels(ghost),
        view.pixels(selection),
        view.pixels_per_unit((ghost + selection) * 0.5),
    ) else {
        return Ok(None);
    };
    let depth_pixels = (view.view_z(selection) - view.view_z(ghost)) * scale;
    // Bounded so that a degenerate camera cannot send the curve to infinity.
    let limit = 2.0 * (w.max(h) as f32);
    let bulge = (curvature * depth_pixels).clamp(-limit, limit);
    let path = arrow_path(from, to, bulge, 64);
    // The head: tip at the selection, along the curve's end tangent.
    let head_length = 3.0 * width + 6.0;
    let tangent = path
        .iter()
        .rev()
        .find(|q| q.distance(to) >= head_length * 0.5)
        .map_or(Vec2::ZERO, |q| (to - *q).normalize_or_zero());
    let tangent = if tangent == Vec2::ZERO {
        (to - from).normalize_or(Vec2::X)
    } else {
        tangent
    };
    let side = Vec2::new(-tangent.y, tangent.x) * head_length * 0.5;
    let base = to - tangent * head_length;
    let mut shaft: Vec<Vec2> = path
        .iter()
        .copied()
        .take_while(|q| q.distance(to) > head_length * 0.7 || q.distance(from) < 1e-3)
        .collect();
    shaft.push(to - tangent * head_length * 0.5);
    Ok(Some((shaft, [to, base + side, base - side])))
}

/// The connecting lines of a fan: the edges of the convex hull of both rectangles' corners that
/// join a corner of one rectangle to a corner of the other (the outer common tangents). Two when
/// the rectangles are apart or overlap partly; none when one contains the other.
pub fn fan_bridges(a: (Vec2, Vec2), b: (Vec2, Vec2)) -> (Vec<Vec2>, Vec<[Vec2; 2]>) {
    let corners = |(lo, hi): (Vec2, Vec2)| [lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)];
    let (ca, cb) = (corners(a), corners(b));
    let all: Vec<Vec2> = ca.iter().chain(&cb).copied().collect();
    let hull = convex_hull(&all);
    let near = |set: &[Vec2; 4], p: Vec2| set.iter().any(|c| c.distance_squared(p) < 1e-6);
    let owner = |p: Vec2| (near(&ca, p), near(&cb, p));
    let mut bridges = Vec::new();
    for i in 0..hull.len() {
        let (u, v) = (hull[i], hull[(i + 1) % hull.len()]);
        let (ou, ov) = (owner(u), owner(v));
        let a_to_b = ou == (true, false) && ov == (false, true);
        let b_to_a = ou == (false, true) && ov == (true, false);
        if hull.len() > 2 && (a_to_b || b_to_a) {
            bridges.push([u, v]);
        }
    }
    (hull, bridges)
}

/// A fan's screen geometry (pixels): the ghost's and the selection's rectangles, the convex hull
/// of their corners (the filled part, less the rectangles) and the connecting lines.
pub struct FanShape {
    pub rects: [(Vec2, Vec2); 2],
    pub hull: Vec<Vec2>,
    pub bridges: Vec<[Vec2; 2]>,
}

/// The fan between the ghost's (anchor 0) and the selection's (anchor 1) world boxes in a
/// `frame` of pixels seen by `camera`; `None` when either box is wholly behind the camera.
pub fn fan_shape(
    annotations: &Annotations,
    camera: &Camera,
    (w, h): (u32, u32),
) -> Result<Option<FanShape>, NodeError> {
    let boxes = [anchor_box(annotations, 0)?, anchor_box(annotations, 1)?];
    let view = Projector::new(camera, w, h);
    let (Some(ghost), Some(selection)) = (view.rect(boxes[0]), view.rect(boxes[1])) else {
        return Ok(None);
    };
    let (hull, bridges) = fan_bridges(ghost, selection);
    Ok(Some(FanShape {
        rects: [ghost, selection],
        hull,
        bridges,
    }))
}

/// The 12 edges of the world boxes of anchors `which` (0 ghost, 1 selection) in a `frame` of
/// pixels seen by `camera`, clipped at the near plane.
pub fn box_edges(
    annotations: &Annotations,
    camera: &Camera,
    (w, h): (u32, u32),
    which: &[usize],
) -> Result<Vec<[Vec2; 2]>, NodeError> {
    let view = Projector::new(camera, w, h);
    let mut edges = Vec::new();
    for &i in which {
        let [lo, hi] = anchor_box(annotations, i)?;
        let corners = box_corners(lo, hi);
        for a in 0..8 {
            for bit in [1, 2, 4] {
                let b = a | bit;
                if b == a {
                    continue;
                }
                edges.extend(view.segment(corners[a], corners[b]));
            }
        }
    }
    Ok(edges)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrow_paths_are_straight_without_bulge_and_bend_left_with_it() {
        let (a, b) = (Vec2::new(10.0, 50.0), Vec2::new(110.0, 50.0));
        let straight = arrow_path(a, b, 0.0, 32);
        assert!(straight.iter().all(|p| (p.y - 50.0).abs() < 1e-4));
        let bent = arrow_path(a, b, 12.0, 64);
        let top = bent.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        // Travelling right, left is up on screen (smaller y); the bulge is 12 px.
        assert!((50.0 - top - 12.0).abs() < 0.1, "{top}");
        assert_eq!(bent[0], a);
        assert!(bent[64].distance(b) < 1e-3);
        let looped = arrow_path(a, a, 20.0, 64);
        let reach = looped.iter().map(|p| p.distance(a)).fold(0.0, f32::max);
        assert!(reach > 10.0, "a zero chord still draws a loop: {reach}");
    }

    #[test]
    fn fans_bridge_separate_rectangles_twice_and_nested_ones_never() {
        let a = (Vec2::new(0.0, 0.0), Vec2::new(10.0, 10.0));
        let b = (Vec2::new(40.0, 20.0), Vec2::new(60.0, 50.0));
        let (hull, bridges) = fan_bridges(a, b);
        assert_eq!(bridges.len(), 2, "{hull:?}");
        let inner = (Vec2::new(42.0, 22.0), Vec2::new(50.0, 30.0));
        assert!(fan_bridges(b, inner).1.is_empty());
    }
}
