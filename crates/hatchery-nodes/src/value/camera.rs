//! The view of a frame: an orbit camera's view and projection matrices (made by the `Camera`
//! node, camera.rs) and the uniform block every mesh shader reads.

// wgpu's clip space: right-handed view, NDC y up, depth in [0, 1] (the Direct3D convention).
use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec3};

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
            eye: self.eye.to_array(),
            orthographic: self.orthographic.into(),
        }
    }
}

crate::uniform_block! {
    /// `Camera` of shaders/mesh_common.wgsl (binding 0 of every mesh shader).
    pub struct CameraUniform in "gbuffer" as "Camera" {
        pub view: [[f32; 4]; 4],
        pub proj: [[f32; 4]; 4],
        /// World eye position.
        pub eye: [f32; 3],
        pub orthographic: u32,
    }
}
