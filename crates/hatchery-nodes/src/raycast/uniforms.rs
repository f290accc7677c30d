//! The ray casters' uniform block (`Ray` in shaders/ray_common.wgsl).

use super::RayOptions;
use crate::camera::Camera;
use glam::{Vec3, Vec4Swizzles};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;

crate::uniform_block! {
    /// Everything a ray needs besides textures; field by field the WGSL struct `Ray` (its
    /// comments say what each component holds).
    pub struct RayUniforms in "raycast" as "Ray" {
        pub inv_view_proj: [[f32; 4]; 4],
        pub view: [[f32; 4]; 4],
        pub view_proj: [[f32; 4]; 4],
        pub box_min: [f32; 4],
        pub box_max: [f32; 4],
        pub origin: [f32; 4],
        pub spacing: [f32; 4],
        pub dims: [f32; 4],
        pub light: [f32; 4],
        pub frame: [f32; 4],
        pub mode: [f32; 4],
        pub phong: [f32; 4],
        pub context: [f32; 4],
        pub tf: [f32; 4],
        pub style: [f32; 4],
        pub eye: [f32; 4],
        pub labels: [f32; 4],
        pub skip: [f32; 4],
        pub to_voxel: [[f32; 4]; 4],
        pub grad_to_world: [[f32; 4]; 4],
        pub texel: [f32; 4],
    }
}

/// The voxel grid rays march through: its size, voxel → world geometry and value range.
pub struct Grid<'a> {
    pub dims: [u32; 3],
    pub geometry: &'a Geometry,
    pub value_range: [f32; 2],
}

impl Grid<'_> {
    fn spacing(&self) -> [f32; 3] {
        self.geometry.spacing.as_vec3().to_array()
    }
    fn origin(&self) -> [f32; 3] {
        self.geometry.origin.as_vec3().to_array()
    }
    fn voxel_to_world(&self, v: Vec3) -> Vec3 {
        self.geometry.voxel_to_world(v)
    }
}

/// What the tables contribute to the uniforms (see `tables::RayTables`).
pub struct TableInfo {
    /// Shading code: the option's, or 4 for a style transfer function.
    pub shading: f32,
    /// Transfer-function domain (lo, hi) of table row 0.
    pub domain: [f32; 2],
    /// Style nodes N of row 0 (0 for a colour TF).
    pub nodes: f32,
    /// Style map size in texels.
    pub map_size: f32,
    /// Whether a label volume picks table rows, its texel range, and the label → row table width.
    pub use_labels: bool,
    pub label_range: [f32; 2],
    pub label_count: f32,
    /// Whether empty bricks are skipped.
    pub skip_empty: bool,
}

impl TableInfo {
    /// No tables: casters that classify on their own (or not at all) — a colour TF domain of
    /// [0, 1], no labels, no skipping.
    pub fn plain() -> Self {
        Self {
            shading: 0.0,
            domain: [0.0, 1.0],
            nodes: 0.0,
            map_size: 1.0,
            use_labels: false,
            label_range: [0.0, 1.0],
            label_count: 0.0,
            skip_empty: false,
        }
    }
}

fn bool_f(b: bool) -> f32 {
    if b { 1.0 } else { 0.0 }
}

impl RayUniforms {
    /// The block for one pass. `max_gradient` normalises |∇f| (eq. 5, 8, 2); `texel_range` maps
    /// the volume texture's texels back to data values.
    pub fn new(
        camera: &Camera,
        data: &VolumeData,
        o: &RayOptions,
        t: &TableInfo,
        max_gradient: f32,
        texel_range: [f32; 2],
    ) -> Self {
        let grid = Grid {
            dims: data.dims,
            geometry: &data.geometry,
            value_range: data.value_range,
        };
        Self::for_grid(camera, &grid, o, t, max_gradient, texel_range)
    }

    /// The block for rays through a voxel grid without a scalar volume (a label map: then
    /// `value_range` is informative only).
    pub fn for_grid(
        camera: &Camera,
        data: &Grid,
        o: &RayOptions,
        t: &TableInfo,
        max_gradient: f32,
        texel_range: [f32; 2],
    ) -> Self {
        // MIP compares texels, not values (raycast.wgsl `cast_mip`): the map must increase.
        debug_assert!(texel_range[1] > texel_range[0], "{texel_range:?}");
        let min_spacing = data.spacing().iter().copied().fold(f32::INFINITY, f32::min);
        // Rays march in voxel space (through the world → voxel transform, so rotated and
        // mirrored grids work) against the box of voxel centres, widened a little so rays
        // running exactly along a face (axis-aligned orthographic views) still hit it;
        // sampling clamps to the grid.
        let margin = Vec3::splat(1e-4);
        let last = Vec3::new(
            (data.dims[0] - 1) as f32,
            (data.dims[1] - 1) as f32,
            (data.dims[2] - 1) as f32,
        );
        let (lo, hi) = (-margin, last + margin);
        let step_world = o.step_voxels * min_spacing;
        let distances = corner_distances(camera, data);
        let view_proj = camera.view_proj();
        let l = o.light_view.normalize_or(Vec3::Z);
        let eye = camera.view.inverse().w_axis.xyz();
        let [ox, oy, oz] = data.origin();
        let [sx, sy, sz] = data.spacing();
        let linear = data.geometry.to_world().as_mat4();
        // Voxel-space gradients → world: M^-T of the linear part.
        let normal_matrix =
            glam::Mat4::from_mat3(glam::Mat3::from_mat4(linear).inverse().transpose());
        Self {
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            view: camera.view.to_cols_array_2d(),
            view_proj: view_proj.to_cols_array_2d(),
            box_min: [lo.x, lo.y, lo.z, step_world],
            box_max: [hi.x, hi.y, hi.z, o.step_voxels],
            origin: [ox, oy, oz, data.value_range[0]],
            spacing: [sx, sy, sz, data.value_range[1]],
            dims: [
                data.dims[0] as f32,
                data.dims[1] as f32,
                data.dims[2] as f32,
                max_gradient,
            ],
            light: [l.x, l.y, l.z, bool_f(camera.orthographic)],
            frame: [
                camera.width as f32,
                camera.height as f32,
                bool_f(o.jitter),
                o.early_termination,
            ],
            mode: [o.mode as f32, o.iso, t.shading, o.hit_opacity],
            phong: o.phong,
            context: [o.kappa[0], o.kappa[1], distances[0], distances[1]],
            tf: [t.domain[0], t.domain[1], t.nodes, o.thickness],
            style: [
                bool_f(o.contours),
                bool_f(o.transparency),
                o.mip_bias,
                t.map_size,
            ],
            eye: [eye.x, eye.y, eye.z, bool_f(o.fast_exponent)],
            labels: [
                bool_f(t.use_labels),
                t.label_range[0],
                t.label_range[1],
                t.label_count,
            ],
            skip: [
                bool_f(t.skip_empty),
                hatchery_data::bricks::BRICK as f32,
                hatchery_data::bricks::VISIBILITY_BINS as f32,
                0.0,
            ],
            to_voxel: data.geometry.to_voxel().as_mat4().to_cols_array_2d(),
            grad_to_world: normal_matrix.to_cols_array_2d(),
            texel: [texel_range[0], texel_range[1], bool_f(o.embed), o.rho],
        }
    }
}

/// Nearest and farthest distance from the eye (perspective) or the near plane (orthographic) to
/// the corners of the volume's box: the normalisation of ‖P − E‖ in eq. 5.
fn corner_distances(camera: &Camera, data: &Grid) -> [f32; 2] {
    let mut range = [f32::INFINITY, 0.0f32];
    let last = Vec3::new(
        (data.dims[0] - 1) as f32,
        (data.dims[1] - 1) as f32,
        (data.dims[2] - 1) as f32,
    );
    for i in 0..8 {
        // The corners of the (possibly rotated) box of voxel centres.
        let corner = data.voxel_to_world(Vec3::new(
            if i & 1 == 0 { 0.0 } else { last.x },
            if i & 2 == 0 { 0.0 } else { last.y },
            if i & 4 == 0 { 0.0 } else { last.z },
        ));
        let d = if camera.orthographic {
            -(camera.view * corner.extend(1.0)).z - camera.near
        } else {
            (corner - camera.eye).length()
        };
        range = [range[0].min(d), range[1].max(d)];
    }
    [range[0].max(0.0), range[1]]
}
