//! `Camera`: an orbit camera, perspective or orthographic.

use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub use crate::value::camera::{Camera, CameraUniform};

hatchery_graph::param_choice! {
    /// Projection type.
    pub enum Projection { Perspective = "perspective", Orthographic = "orthographic" }
}

hatchery_graph::param_choice! {
    /// World axis that points up on screen.
    pub enum Up { Y = "y", Z = "z" }
}

hatchery_graph::param_choice! {
    /// Fit: frame the connected data; fixed: use target and distance (also when nothing is
    /// connected).
    pub enum Framing { Fit = "fit", Fixed = "fixed" }
}

hatchery_graph::node_params! {
    /// Parameters of `Camera`.
    pub struct CameraParams {
        /// rotation around the up axis, degrees
        pub azimuth: f32 = 30.0, range(-360.0, 360.0);
        /// angle above the horizontal plane, degrees
        pub elevation: f32 = 20.0, range(-90.0, 90.0);
        /// distance from the target, world units
        pub distance: f32 = 3.5, range(1e-4, 1e6);
        /// point looked at, world units
        pub target: [f32; 3] = [0.0, 0.0, 0.0];
        /// field of view across the frame's shorter side (the height of a wide frame), degrees
        pub fov: f32 = 40.0, range(1.0, 170.0);
        /// perspective, or orthographic (parallel rays: sizes do not shrink with depth)
        pub projection: Projection = Projection::Perspective;
        /// world axis that points up on screen
        pub up: Up = Up::Y;
        /// near clipping distance
        pub near: f32 = 0.05, range(1e-5, 1e6);
        /// far clipping distance
        pub far: f32 = 100.0, range(1e-4, 1e7);
        /// fit: frame the connected data; fixed: use target and distance (also when nothing is
        /// connected)
        pub framing: Framing = Framing::Fit;
        /// framing: the fraction of the frame's width or height the data fills (above 1: closer,
        /// part of the data)
        pub fill: f32 = 0.8, range(0.05, 20.0);
        /// framing: target shift to the right, in frame widths (shorter side)
        pub pan_x: f32 = 0.0, range(-10.0, 10.0);
        /// framing: target shift upwards, in frame heights (shorter side)
        pub pan_y: f32 = 0.0, range(-10.0, 10.0);
    }
}

pub struct CameraNode;

impl Node<Value, Ctx> for CameraNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Camera",
            category: "Scene",
            doc: "Orbit camera around a target point, perspective or orthographic. The field of view \
                  spans the frame's shorter side; orthographic views show 2·distance·tan(fov/2) \
                  across it; azimuth 0, elevation 0 with up \"y\" looks \
                  along -z (axis-aligned). With data connected (a volume, labels, a mesh, or \
                  several) and `framing` \"fit\", it frames them: the target is the centre of \
                  their bounds (moved by `pan_x`, `pan_y`), the distance (or orthographic extent) \
                  makes them fill `fill` of the frame's width or height from this azimuth and \
                  elevation; `near` and `far` scale with the framed distance relative to \
                  `distance` (so depth-based thresholds act alike on data of any size), widened \
                  to enclose the data; `target` goes unused.",
            inputs: vec![
                PortSpec::optional(
                    "volume",
                    PortType::Volume,
                    "data to frame: the volume's foreground (voxels at or above Otsu's threshold)",
                ),
                PortSpec::optional(
                    "labels",
                    PortType::Labels,
                    "data to frame: the labelled objects (not the background)",
                ),
                PortSpec::optional("mesh", PortType::Mesh, "data to frame: the mesh's vertices"),
            ],
            outputs: vec![PortSpec::output(
                "camera",
                PortType::Camera,
                "view and projection for the frame",
            )],
            params: CameraParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = CameraParams::read(p)?;
        let (width, height) = ctx.size();
        let orthographic = params.projection == Projection::Orthographic;
        let (az, el, fov, up_z) = (
            params.azimuth,
            params.elevation,
            params.fov,
            params.up == Up::Z,
        );
        // The data's outline is only gathered when the camera frames it.
        let framing = if params.framing == Framing::Fit {
            crate::framing::frame_points(
                &framed_points(inputs)?,
                az,
                el,
                up_z,
                fov,
                width as f32 / height as f32,
                orthographic,
                params.fill,
                [params.pan_x, params.pan_y],
                (params.near, params.far, params.distance),
            )
        } else {
            None
        };
        let (target, distance, near, far) = match framing {
            Some(f) => (f.target, f.distance, f.near, f.far),
            None => {
                let (near, far) = (params.near, params.far);
                if near >= far {
                    return Err(NodeError::new(format!(
                        "near ({near}) must be less than far ({far})"
                    )));
                }
                (Vec3::from(params.target), params.distance, near, far)
            }
        };
        let mut camera = Camera::orbit(
            target,
            az,
            el,
            distance,
            fov,
            orthographic,
            near,
            far,
            up_z,
            width,
            height,
        );
        if let (Some(f), true) = (framing, orthographic) {
            camera = camera.with_orthographic_extent(f.extent_distance, fov);
        }
        Ok(vec![Value::Camera(Arc::new(camera))])
    }
}

/// World points the camera frames (see [`crate::framing`]): the outlines of the connected
/// volume's foreground and of the labelled objects, and the mesh's vertices.
fn framed_points(inputs: &NodeInputs<Value>) -> Result<Vec<Vec3>, NodeError> {
    let mut points = Vec::new();
    if let Some(v) = inputs.get("volume") {
        points.extend_from_slice(v.volume("volume")?.frame_points());
    }
    if let Some(v) = inputs.get("labels") {
        points.extend_from_slice(v.labels("labels")?.frame_points());
    }
    if let Some(v) = inputs.get("mesh") {
        points.extend(crate::framing::strided(
            &v.mesh("mesh")?.data.positions,
            65_536,
        ));
    }
    Ok(points)
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(CameraNode);
}
