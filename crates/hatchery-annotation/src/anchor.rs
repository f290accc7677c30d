//! Annotation anchors: the 3-D points labels refer to, and their projection to the frame
//! (VolumeShop, Bruckner & Gröller 2005, §6.4: "for placing annotations we need their
//! screen-space bounding rectangles and anchor points").

use glam::{Mat4, Vec2, Vec3, Vec4};

/// One annotation: a 3-D anchor point with its label text.
#[derive(Clone, Debug, PartialEq)]
pub struct Anchor {
    /// Anchor point in world space, mm (the same space the view-projection matrix takes).
    pub position: Vec3,
    /// The label's text.
    pub text: String,
    /// The object (selection / segment label) the anchor belongs to.
    pub object: u16,
    /// Importance: when conflicts remain after the iterative layout, labels of lower priority
    /// are disabled first; among equal priorities the farthest anchor goes first (§6.4).
    pub priority: f32,
}

/// An anchor projected to the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedAnchor {
    /// Position in pixels, origin at the top-left corner of the frame, y down.
    pub screen: Vec2,
    /// Window depth in [0, 1], 0 at the near and 1 at the far plane (wgpu's NDC z).
    pub depth: f32,
    /// Whether the anchor is in front of the camera and inside the view volume (on screen and
    /// between the near and far planes). Labels of invisible anchors are never shown.
    pub visible: bool,
    /// The anchor's [`Anchor::priority`] (0 from [`project_point`]).
    pub priority: f32,
}

/// Projects one world-space point with the view-projection matrix `view_proj` (wgpu
/// conventions: clip space with NDC x, y in [-1, 1] with y up, z in [0, 1]) to a frame of
/// `frame` = (width, height) pixels. NDC y up becomes pixel y down:
/// `screen = ((x + 1) / 2 · width, (1 − y) / 2 · height)`.
///
/// A point with clip w ≤ 0 (behind the camera) returns `visible = false`, `screen` = the frame
/// centre and `depth` = 1.
pub fn project_point(position: Vec3, view_proj: Mat4, frame: Vec2) -> ProjectedAnchor {
    let clip: Vec4 = view_proj * position.extend(1.0);
    if clip.w <= f32::EPSILON {
        return ProjectedAnchor {
            screen: frame * 0.5,
            depth: 1.0,
            visible: false,
            priority: 0.0,
        };
    }
    let ndc = clip.truncate() / clip.w;
    let screen = Vec2::new((ndc.x + 1.0) * 0.5 * frame.x, (1.0 - ndc.y) * 0.5 * frame.y);
    let visible = ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0 && (0.0..=1.0).contains(&ndc.z);
    ProjectedAnchor {
        screen,
        depth: ndc.z,
        visible,
        priority: 0.0,
    }
}

/// Projects every anchor with [`project_point`], carrying its priority over; the result is in
/// anchor order.
pub fn project_anchors(anchors: &[Anchor], view_proj: Mat4, frame: Vec2) -> Vec<ProjectedAnchor> {
    anchors
        .iter()
        .map(|a| ProjectedAnchor {
            priority: a.priority,
            ..project_point(a.position, view_proj, frame)
        })
        .collect()
}

/// Projects world-space points (e.g. the corners of the visible objects' bounding boxes) to
/// pixels, keeping only those in front of the camera: the input of
/// [`convex_hull`](crate::convex_hull) for the silhouette polygon of §6.4.
pub fn project_footprint(points: &[Vec3], view_proj: Mat4, frame: Vec2) -> Vec<Vec2> {
    points
        .iter()
        .filter_map(|&p| {
            let clip = view_proj * p.extend(1.0);
            (clip.w > f32::EPSILON).then(|| {
                let ndc = clip.truncate() / clip.w;
                Vec2::new((ndc.x + 1.0) * 0.5 * frame.x, (1.0 - ndc.y) * 0.5 * frame.y)
            })
        })
        .collect()
}

/// The eight corners of the axis-aligned box `[min, max]` (world space), for
/// [`project_footprint`].
pub fn box_corners(min: Vec3, max: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::camera::rh::{proj::directx, view::look_at_mat4};

    #[test]
    fn projects_to_pixels_y_down() {
        let view = look_at_mat4(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y);
        let proj = directx::perspective(60f32.to_radians(), 2.0, 1.0, 100.0);
        let frame = Vec2::new(200.0, 100.0);
        let c = project_point(Vec3::ZERO, proj * view, frame);
        assert!(c.visible);
        assert!((c.screen - Vec2::new(100.0, 50.0)).length() < 1e-3);
        let up = project_point(Vec3::new(0.0, 1.0, 0.0), proj * view, frame);
        assert!(up.screen.y < 50.0, "world up is screen up (smaller y)");
        let near = project_point(Vec3::new(0.0, 0.0, 5.0), proj * view, frame);
        assert!(near.depth < c.depth);
        let behind = project_point(Vec3::new(0.0, 0.0, 20.0), proj * view, frame);
        assert!(!behind.visible);
    }
}
