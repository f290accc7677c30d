//! `Camera`: an orbit camera, perspective or orthographic.

use crate::{Ctx, Value};
// wgpu's clip space: right-handed view, NDC y up, depth in [0, 1] (the Direct3D convention).
use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec3};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// View and projection for one frame size. Depth range is wgpu's [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub view: Mat4,
    pub proj: Mat4,
    pub eye: Vec3,
    /// The point looked at and the world up vector of the view (for exports to other tools).
    pub target: Vec3,
    pub up: Vec3,
    pub orthographic: bool,
    pub near: f32,
    pub far: f32,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    /// Orbit camera looking at `target` from `distance`, angles in degrees. With `up_z`, elevation
    /// is measured from the xy plane and azimuth 0 looks along -y (medical RAS data); otherwise
    /// azimuth 0, elevation 0 looks along -z with +y up, so view space equals world space shifted.
    #[allow(clippy::too_many_arguments)]
    pub fn orbit(
        target: Vec3,
        azimuth_deg: f32,
        elevation_deg: f32,
        distance: f32,
        fov_y_deg: f32,
        orthographic: bool,
        near: f32,
        far: f32,
        up_z: bool,
        width: u32,
        height: u32,
    ) -> Camera {
        let (offset, up) = crate::framing::orbit_basis(azimuth_deg, elevation_deg, up_z);
        let eye = target + offset * distance;
        let view = look_at_mat4(eye, target, up);
        let aspect = width as f32 / height as f32;
        // The field of view spans the shorter side, so a tall frame (a narrow editor panel)
        // shows the same subject as a wide one instead of cropping its sides.
        let half_short = (fov_y_deg.to_radians() / 2.0).tan();
        let half_tan_y = if aspect >= 1.0 {
            half_short
        } else {
            half_short / aspect
        };
        let proj = if orthographic {
            let half_h = distance * half_tan_y;
            let half_w = half_h * aspect;
            directx::orthographic(-half_w, half_w, -half_h, half_h, near, far)
        } else {
            directx::perspective(2.0 * half_tan_y.atan(), aspect, near, far)
        };
        Camera {
            target,
            up,
            view,
            proj,
            eye,
            orthographic,
            near,
            far,
            width,
            height,
        }
    }

    /// The same orthographic view showing 2·`extent_distance`·tan(fov/2) across the frame's
    /// shorter side (framing puts the eye outside the data and sizes the view separately).
    pub fn with_orthographic_extent(mut self, extent_distance: f32, fov_deg: f32) -> Camera {
        let aspect = self.width as f32 / self.height as f32;
        let half_short = (fov_deg.to_radians() / 2.0).tan();
        let half_h = extent_distance
            * if aspect >= 1.0 {
                half_short
            } else {
                half_short / aspect
            };
        let half_w = half_h * aspect;
        self.proj = directx::orthographic(-half_w, half_w, -half_h, half_h, self.near, self.far);
        self
    }

    pub fn view_proj(&self) -> Mat4 {
        self.proj * self.view
    }

    /// View-space position of the point at pixel (x, y) (top-left origin) with window depth `depth`.
    pub fn view_position(&self, x: usize, y: usize, depth: f32) -> Vec3 {
        let ndc_x = (x as f32 + 0.5) / self.width as f32 * 2.0 - 1.0;
        let ndc_y = 1.0 - (y as f32 + 0.5) / self.height as f32 * 2.0;
        let p = self.proj.inverse() * glam::Vec4::new(ndc_x, ndc_y, depth, 1.0);
        p.truncate() / p.w
    }

    /// Unit vector from the surface point at pixel (x, y) towards the viewer, in view space.
    pub fn view_direction_at(&self, x: usize, y: usize, depth: f32) -> Vec3 {
        if self.orthographic {
            Vec3::Z
        } else {
            -self.view_position(x, y, depth).normalize()
        }
    }

    /// The camera as JSON for other renderers (benches/peers): eye, target and up in world
    /// units, the vertical field of view in degrees (of the frame's height), near, far, frame
    /// size, projection; orthographic cameras also give the half height of the view.
    pub fn to_json(&self) -> String {
        let v = |p: Vec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
        let fov_y = 2.0 * (1.0 / self.proj.y_axis.y).atan().to_degrees();
        let half_height = 1.0 / self.proj.y_axis.y;
        format!(
            "{{\"eye\": {}, \"target\": {}, \"up\": {}, \"fov_y_deg\": {fov_y}, \"near\": {}, \"far\": {}, \"width\": {}, \"height\": {}, \"orthographic\": {}, \"ortho_half_height\": {half_height}}}\n",
            v(self.eye),
            v(self.target),
            v(self.up),
            self.near,
            self.far,
            self.width,
            self.height,
            self.orthographic
        )
    }

    /// The camera block as a uniform buffer (binding 0 of every mesh shader).
    pub fn uniform_buffer(&self, gpu: &hatchery_gpu::GpuContext) -> wgpu::Buffer {
        gpu.buffer_init(
            "camera",
            bytemuck::bytes_of(&self.uniform()),
            wgpu::BufferUsages::UNIFORM,
        )
    }

    /// The uniform block shared by mesh shaders (`Camera` in shaders/mesh_common.wgsl).
    pub fn uniform(&self) -> CameraUniform {
        CameraUniform {
            view: self.view.to_cols_array_2d(),
            proj: self.proj.to_cols_array_2d(),
            eye: [
                self.eye.x,
                self.eye.y,
                self.eye.z,
                if self.orthographic { 1.0 } else { 0.0 },
            ],
        }
    }
}

crate::uniform_block! {
    /// `Camera` of shaders/mesh_common.wgsl (binding 0 of every mesh shader).
    pub struct CameraUniform in "gbuffer" as "Camera" {
        pub view: [[f32; 4]; 4],
        pub proj: [[f32; 4]; 4],
        /// World eye position; w = 1 for orthographic.
        pub eye: [f32; 4],
    }
}

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
        /// projection type
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
