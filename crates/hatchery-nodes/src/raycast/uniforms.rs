//! The ray casters' uniform block (`Ray` in shaders/ray_common.wgsl).

use super::RayOptions;
use crate::camera::Camera;
use glam::{Vec3, Vec4Swizzles};
use hatchery_data::VolumeData;
use hatchery_data::geometry::Geometry;

crate::uniform_block! {
    /// Everything a ray needs besides textures: the WGSL struct `Ray` of
    /// shaders/ray_common.wgsl, field by field (its comments say what each field holds).
    pub struct RayUniforms in "raycast" as "Ray" {
        pub inv_view_proj: [[f32; 4]; 4],
        pub view: [[f32; 4]; 4],
        pub view_proj: [[f32; 4]; 4],
        pub to_voxel: [[f32; 4]; 4],
        pub grad_to_world: [[f32; 4]; 4],
        pub box_min: [f32; 3],
        pub step_world: f32,
        pub box_max: [f32; 3],
        pub step_voxels: f32,
        pub dims: [f32; 3],
        pub max_gradient: f32,
        pub light: [f32; 3],
        pub orthographic: u32,
        pub eye: [f32; 3],
        pub fast_exponent: u32,
        pub frame: [f32; 2],
        pub jitter: u32,
        pub early_termination: f32,
        /// A [`RayMode`] code.
        pub mode: u32,
        pub iso: f32,
        /// A [`RayShading`] code.
        pub shading: u32,
        pub hit_opacity: f32,
        pub ambient: f32,
        pub diffuse: f32,
        pub specular: f32,
        pub shininess: f32,
        pub kappa_t: f32,
        pub kappa_s: f32,
        pub distance_near: f32,
        pub distance_far: f32,
        pub tf_domain: [f32; 2],
        pub style_nodes: u32,
        pub contour_thickness: f32,
        pub contours: u32,
        pub transparency: u32,
        pub mip_bias: f32,
        pub style_map_size: f32,
        pub label_texels: [f32; 2],
        pub label_rows: u32,
        pub use_labels: u32,
        pub value_range: [f32; 2],
        pub brick_size: u32,
        pub visibility_bins: u32,
        pub texel_values: [f32; 2],
        pub skip_empty: u32,
        pub embed_strokes: u32,
        pub rho: f32,
        pub bricked: u32,
        pub page_inner: f32,
        pub pad0: f32,
        pub atlas_inv: [f32; 3],
        pub pad1: f32,
    }
}

crate::gpu_enum! {
    /// How a ray composites (`Ray.mode`; raycast.wgsl's `RAY_MODE` pipeline constant).
    pub enum RayMode in "raycast" {
        /// Direct volume rendering, front to back (eq. 1).
        Dvr = 0 as "RAY_MODE_DVR",
        /// Maximum intensity projection.
        Mip = 1 as "RAY_MODE_MIP",
        /// The first hit of the iso value.
        Iso = 2 as "RAY_MODE_ISO",
    }
}

crate::gpu_enum! {
    /// How a sample is shaded (`Ray.shading`; shaders/ray_shade.wgsl).
    pub enum RayShading in "raycast" {
        /// Unshaded.
        None = 0 as "SHADING_NONE",
        /// Blinn–Phong, eq. 3.
        Phong = 1 as "SHADING_PHONG",
        /// The lighting transfer function, eq. 8.
        Lighting = 2 as "SHADING_LIGHTING",
        /// Context-preserving, eq. 5.
        ContextPreserving = 3 as "SHADING_CONTEXT",
        /// A style transfer function (Bruckner & Gröller 2007).
        Style = 4 as "SHADING_STYLE",
    }
}

impl From<super::Mode> for RayMode {
    fn from(mode: super::Mode) -> Self {
        match mode {
            super::Mode::Dvr => RayMode::Dvr,
            super::Mode::Mip => RayMode::Mip,
            super::Mode::Iso => RayMode::Iso,
        }
    }
}

impl From<super::Shading> for RayShading {
    fn from(shading: super::Shading) -> Self {
        match shading {
            super::Shading::None => RayShading::None,
            super::Shading::Phong => RayShading::Phong,
            super::Shading::Lighting => RayShading::Lighting,
            super::Shading::ContextPreserving => RayShading::ContextPreserving,
        }
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
    fn voxel_to_world(&self, v: Vec3) -> Vec3 {
        self.geometry.voxel_to_world(v)
    }
}

/// What the tables contribute to the uniforms (see `tables::RayTables`).
pub struct TableInfo {
    /// The option's shading, or `Style` for a style transfer function.
    pub shading: RayShading,
    /// Transfer-function domain (lo, hi) of table row 0.
    pub domain: [f32; 2],
    /// Style nodes N of row 0 (0 for a colour TF).
    pub nodes: u32,
    /// Style map size in texels.
    pub map_size: f32,
    /// Whether a label volume picks table rows, its texel range, and the label → row table width.
    pub use_labels: bool,
    pub label_range: [f32; 2],
    pub label_count: u32,
    /// Whether empty bricks are skipped.
    pub skip_empty: bool,
}

impl TableInfo {
    /// No tables: casters that classify on their own (or not at all) — a colour TF domain of
    /// [0, 1], no labels, no skipping.
    pub fn plain() -> Self {
        Self {
            shading: RayShading::None,
            domain: [0.0, 1.0],
            nodes: 0,
            map_size: 1.0,
            use_labels: false,
            label_range: [0.0, 1.0],
            label_count: 0,
            skip_empty: false,
        }
    }
}

impl RayUniforms {
    /// This block with the grid textures read through `layout`'s page table (bricked), or as
    /// whole textures (`None`); see `grid_uv` in shaders/ray_common.wgsl.
    pub fn with_bricks(mut self, layout: Option<&crate::brick_pool::BrickLayout>) -> Self {
        if let Some(l) = layout {
            self.bricked = 1;
            self.page_inner = l.inner as f32;
            self.atlas_inv = l.atlas_dims().map(|d| 1.0 / d as f32);
        }
        self
    }

    /// This block with the eye-to-box distances (eq. 5) of the whole grid `whole` that the
    /// volume is a region of (a streamed view, `value::stream`), so a region shades as the
    /// whole grid does.
    pub fn with_whole_grid(mut self, camera: &Camera, whole: &Grid) -> Self {
        [self.distance_near, self.distance_far] = corner_distances(camera, whole);
        self
    }

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
        let linear = data.geometry.to_world().as_mat4();
        // Voxel-space gradients → world: M^-T of the linear part.
        let normal_matrix =
            glam::Mat4::from_mat3(glam::Mat3::from_mat4(linear).inverse().transpose());
        Self {
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            view: camera.view.to_cols_array_2d(),
            view_proj: view_proj.to_cols_array_2d(),
            to_voxel: data.geometry.to_voxel().as_mat4().to_cols_array_2d(),
            grad_to_world: normal_matrix.to_cols_array_2d(),
            box_min: lo.to_array(),
            step_world,
            box_max: hi.to_array(),
            step_voxels: o.step_voxels,
            dims: data.dims.map(|d| d as f32),
            max_gradient,
            light: l.to_array(),
            orthographic: camera.orthographic.into(),
            eye: eye.to_array(),
            fast_exponent: o.fast_exponent.into(),
            frame: [camera.width as f32, camera.height as f32],
            jitter: o.jitter.into(),
            early_termination: o.early_termination,
            mode: o.mode.code(),
            iso: o.iso,
            shading: t.shading.code(),
            hit_opacity: o.hit_opacity,
            ambient: o.phong[0],
            diffuse: o.phong[1],
            specular: o.phong[2],
            shininess: o.phong[3],
            kappa_t: o.kappa[0],
            kappa_s: o.kappa[1],
            distance_near: distances[0],
            distance_far: distances[1],
            tf_domain: t.domain,
            style_nodes: t.nodes,
            contour_thickness: o.thickness,
            contours: o.contours.into(),
            transparency: o.transparency.into(),
            mip_bias: o.mip_bias,
            style_map_size: t.map_size,
            label_texels: t.label_range,
            label_rows: t.label_count,
            use_labels: t.use_labels.into(),
            value_range: data.value_range,
            brick_size: hatchery_data::bricks::BRICK,
            visibility_bins: hatchery_data::bricks::VISIBILITY_BINS as u32,
            texel_values: texel_range,
            skip_empty: t.skip_empty.into(),
            embed_strokes: o.embed.into(),
            rho: o.rho,
            bricked: 0,
            page_inner: 1.0,
            pad0: 0.0,
            atlas_inv: [1.0; 3],
            pad1: 0.0,
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
