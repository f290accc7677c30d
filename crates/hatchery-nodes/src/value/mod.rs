//! The data flowing along edges: one variant per [`PortType`], cheap to clone (shared handles).
//!
//! One enum of every value that flows on an edge, with its typed accessors and the volume and
//! label wrappers they hand out; it is ~600 lines because every port type is here, and the data
//! types of their own are in the submodules.

pub mod annotations;
mod bspline_quads;
pub mod camera;
mod gradient_texture;
mod id_quads;
pub mod light;
mod resident;
pub mod stream;
pub mod strokes;
pub mod vector_field;

use crate::brick_pool::GridTexture;
use crate::volume_texture::VolumeTexture;
use hatchery_data::{MeshData, VolumeData};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::PortType;
use std::sync::{Arc, OnceLock};

/// A scalar volume: CPU data for CPU nodes (marching cubes), uploaded to a 3-D texture the first
/// time a GPU node asks for it.
pub struct Volume {
    pub data: Arc<VolumeData>,
    texture: OnceLock<VolumeTexture>,
    max_gradient: OnceLock<f32>,
    /// Value range of each brick (empty-space skipping), as an Rg32Float 3-D texture.
    bricks: OnceLock<wgpu::Texture>,
    /// The same for tricubic B-spline samples (they reach one voxel further).
    bricks_bspline: OnceLock<wgpu::Texture>,
    frame_points: OnceLock<Vec<glam::Vec3>>,
    /// The next coarser level of detail, made when a brick pool cannot hold this one (and the
    /// same by majority, for a volume of label ids).
    coarser: OnceLock<Arc<Volume>>,
    coarser_labels: OnceLock<Arc<Volume>>,
    /// Its gradient and value as another volume's second field (see [`vector_field`]).
    second_field: OnceLock<wgpu::Texture>,
    /// The volume as x-quads for the B-spline on CPU adapters (see [`bspline_quads`]).
    bspline_quads: OnceLock<Option<wgpu::Texture>>,
    /// Its world gradients at the voxel centres for volume thinning (see [`gradient_texture`]).
    gradients: OnceLock<Option<wgpu::Texture>>,
    /// Whether `data` holds "no data" (NaN) voxels, scanned once.
    no_data: OnceLock<bool>,
    /// The file a volume beyond the host budget streams from (`data` is then its preview
    /// level; see [`stream`]).
    stream: Option<Arc<stream::Stream>>,
}

/// Whether a CPU-adapter read-ahead copy of `bytes` (x-quads, id quads, the gradient texture)
/// is wanted on `gpu`: a CPU adapter, within `VolumeLimits::quads_bytes` and the device's
/// buffer limit (the upload goes through one buffer). Errors: malformed volume settings.
fn read_ahead_fits(gpu: &GpuContext, bytes: u64) -> Result<bool, GpuError> {
    Ok(gpu.adapter_info.device_type == wgpu::DeviceType::Cpu
        && bytes <= gpu.volume_limits()?.quads_bytes
        && bytes <= gpu.device.limits().max_buffer_size)
}

impl Volume {
    pub fn new(data: VolumeData) -> Self {
        Self::shared(Arc::new(data))
    }
    /// A volume over data held elsewhere too (in-memory graph inputs), without a copy.
    pub fn shared(data: Arc<VolumeData>) -> Self {
        Self {
            data,
            texture: OnceLock::new(),
            max_gradient: OnceLock::new(),
            bricks: OnceLock::new(),
            bricks_bspline: OnceLock::new(),
            frame_points: OnceLock::new(),
            coarser: OnceLock::new(),
            coarser_labels: OnceLock::new(),
            second_field: OnceLock::new(),
            bspline_quads: OnceLock::new(),
            gradients: OnceLock::new(),
            no_data: OnceLock::new(),
            stream: None,
        }
    }
    /// What a Camera frames (see [`crate::framing`]), found once: the outline of the volume's
    /// foreground (voxels at or above Otsu's threshold), or its whole grid when the
    /// values do not split into two classes.
    pub fn frame_points(&self) -> &[glam::Vec3] {
        self.frame_points.get_or_init(|| {
            let d = &self.data;
            // Voxels read in their stored type: an f32 copy would double a uint16 volume.
            let points = hatchery_data::value_stats::otsu(d)
                .map(|t| {
                    crate::framing::occupied_block_outline(d.dims, &d.geometry, |i| {
                        d.voxels.get(i) >= t
                    })
                })
                .unwrap_or_default();
            if points.is_empty() {
                let last = d.dims.map(|n| (n - 1) as f32);
                crate::framing::box_corners(glam::Vec3::ZERO, glam::Vec3::from(last))
                    .map(|c| d.voxel_to_world(c))
                    .to_vec()
            } else {
                points
            }
        })
    }
    /// The 3-D texture in a format matching the voxel type (see [`crate::volume_texture`]),
    /// uploaded on first use.
    pub fn texture(&self, gpu: &GpuContext) -> Result<&VolumeTexture, GpuError> {
        if let Some(t) = self.texture.get() {
            return Ok(t);
        }
        let t = crate::volume_texture::upload(gpu, "volume", &self.data)?;
        Ok(self.texture.get_or_init(|| t))
    }
    /// How the uploaded texture is bricked (`None`: one texture, or not uploaded yet).
    pub fn bricked(&self) -> Option<&crate::brick_pool::BrickLayout> {
        self.texture.get().and_then(|t| t.layout.as_ref())
    }
    /// The `[min, max]` value samples of `reconstruction` can take in each brick of voxels (see
    /// `hatchery_data::bricks`; the B-spline reaches one voxel further), computed and uploaded
    /// once. Ranges are widened by 1/1000 of the value range: the volume texture stores values
    /// in half precision. Errors: the table (1/8 of the grid per axis) beyond the adapter's 3-D
    /// texture limit — a grid over 8 × that limit along an axis.
    pub fn bricks(
        &self,
        gpu: &GpuContext,
        reconstruction: crate::reconstruction::Reconstruction,
    ) -> Result<&wgpu::Texture, GpuError> {
        let (cell, reach) = match reconstruction {
            crate::reconstruction::Reconstruction::Trilinear => (&self.bricks, 0),
            crate::reconstruction::Reconstruction::Bspline => (&self.bricks_bspline, 1),
        };
        if let Some(t) = cell.get() {
            return Ok(t);
        }
        use hatchery_data::bricks::{brick_dims, brick_range_layers};
        let [lo, hi] = self.data.value_range;
        let pad = (hi - lo) * 1e-3;
        // Built and uploaded a slab of brick layers at a time: the whole table (8 MiB at
        // 800³) never sits in host memory next to its staging copy and the texture.
        let t = gpu.volume_texture_by_slabs(
            "empty-space skipping table",
            brick_dims(&self.data),
            wgpu::TextureFormat::Rg32Float,
            |z0, z1, out| {
                let ranges = brick_range_layers(&self.data, pad, z0..z1, reach);
                out.extend_from_slice(bytemuck::cast_slice(&ranges));
            },
        )?;
        Ok(cell.get_or_init(|| t))
    }
    /// Whether the data holds "no data" (NaN) voxels ([`VolumeData::has_no_data`]), scanned
    /// once: the ray casters' `RAY_NO_DATA` and the CPU-adapter copies ask every frame.
    pub fn has_no_data(&self) -> bool {
        *self.no_data.get_or_init(|| self.data.has_no_data())
    }
    /// The largest gradient magnitude (world units), computed once: normalises |g| to [0, 1].
    pub fn max_gradient(&self) -> f32 {
        *self
            .max_gradient
            .get_or_init(|| hatchery_data::gradient::max_gradient_magnitude(&self.data))
    }
}

/// A segmented volume (object ids and names), its ids uploaded as an R16Uint 3-D texture on
/// first use: read with `textureLoad` only, never filtered as numbers (Hadwiger §2.3).
pub struct Labels {
    pub data: Arc<hatchery_data::segmentation::LabelData>,
    texture: OnceLock<GridTexture>,
    bricks: OnceLock<BrickObjects>,
    /// The last union mask of drawn objects, with the ids it was made for.
    drawn_mask: std::sync::Mutex<Option<(Vec<u16>, Arc<GridTexture>)>>,
    /// The last selection mask (SelectionRender), with its ids.
    selection_mask: std::sync::Mutex<Option<(Vec<u16>, Arc<GridTexture>)>>,
    frame_points: OnceLock<Vec<glam::Vec3>>,
    /// The next coarser level of detail, made when a brick pool cannot hold this one.
    coarser: OnceLock<Arc<Labels>>,
    /// The ids as 2×2 quads for CPU adapters (see [`id_quads`]).
    id_quads: OnceLock<Option<wgpu::Texture>>,
}

/// Which object ids the samples in each 8³-voxel brick can see (a sample's object comes from
/// the 8 voxels around it, so a brick also sees the first voxel layer of its upper
/// neighbours): the brick grid's dims and, per brick (x fastest), the ids, sorted.
pub struct BrickObjects {
    pub dims: [u32; 3],
    pub ids: Vec<Vec<u16>>,
}

impl Labels {
    pub fn new(data: hatchery_data::segmentation::LabelData) -> Self {
        Self::shared(Arc::new(data))
    }
    /// Labels over data held elsewhere too (in-memory graph inputs), without a copy.
    pub fn shared(data: Arc<hatchery_data::segmentation::LabelData>) -> Self {
        Self {
            data,
            texture: OnceLock::new(),
            bricks: OnceLock::new(),
            drawn_mask: std::sync::Mutex::new(None),
            selection_mask: std::sync::Mutex::new(None),
            frame_points: OnceLock::new(),
            coarser: OnceLock::new(),
            id_quads: OnceLock::new(),
        }
    }

    /// What a Camera frames: the outline of the labelled (non-background) voxels, found once;
    /// empty for a map of background only.
    pub fn frame_points(&self) -> &[glam::Vec3] {
        self.frame_points.get_or_init(|| {
            let d = &self.data;
            crate::framing::occupied_block_outline(d.dims, &d.geometry, |i| d.ids[i] != 0)
        })
    }

    /// An R8Unorm volume: 1 where a voxel's id is in `drawn` (sorted), else 0. Filtered
    /// trilinearly it bounds every drawn object's filtered mask from above, so a sample where it
    /// is below 0.5 belongs to no drawn object (one fetch instead of eight). Kept for the last
    /// `drawn` set.
    pub fn drawn_mask(
        &self,
        gpu: &GpuContext,
        drawn: &[u16],
    ) -> Result<Arc<GridTexture>, GpuError> {
        self.indicator(gpu, drawn, false)
    }

    /// The indicator of `ids` (sorted) as a texture whose trilinear filtering is the selection
    /// degree f_S of VolumeShop (SelectionRender): R8Unorm, or R16Unorm on CPU adapters, whose
    /// sampler filters 8-bit textures in 8-bit arithmetic (see `volume_texture`). Kept for the
    /// last set.
    pub fn selection_mask(
        &self,
        gpu: &GpuContext,
        ids: &[u16],
    ) -> Result<Arc<GridTexture>, GpuError> {
        let wide = gpu.adapter_info.device_type == wgpu::DeviceType::Cpu
            && gpu
                .device
                .features()
                .contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM);
        self.indicator(gpu, ids, wide)
    }

    fn indicator(
        &self,
        gpu: &GpuContext,
        drawn: &[u16],
        wide: bool,
    ) -> Result<Arc<GridTexture>, GpuError> {
        let slot = if wide {
            &self.selection_mask
        } else {
            &self.drawn_mask
        };
        let mut cached = slot.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((ids, texture)) = cached.as_ref()
            && ids == drawn
        {
            return Ok(texture.clone());
        }
        let mut is_drawn = vec![false; u16::MAX as usize + 1];
        for &id in drawn {
            is_drawn[id as usize] = true;
        }
        let [nx, ny, _] = self.data.dims.map(|d| d as usize);
        let ids = &self.data.ids;
        let (format, one): (_, &[u8]) = if wide {
            (wgpu::TextureFormat::R16Unorm, &[255, 255])
        } else {
            (wgpu::TextureFormat::R8Unorm, &[255])
        };
        let zero = vec![0u8; one.len()];
        let texture = Arc::new(crate::brick_pool::grid_texture(
            gpu,
            "object indicator",
            self.data.dims,
            format,
            |z0, z1, out| {
                for &id in &ids[z0 as usize * nx * ny..z1 as usize * nx * ny] {
                    out.extend_from_slice(if is_drawn[id as usize] { one } else { &zero });
                }
            },
        )?);
        *cached = Some((drawn.to_vec(), texture.clone()));
        Ok(texture)
    }

    /// How the uploaded id texture is bricked (`None`: one texture, or not uploaded yet).
    pub fn bricked(&self) -> Option<&crate::brick_pool::BrickLayout> {
        self.texture.get().and_then(|t| t.layout.as_ref())
    }

    /// The ids each brick's samples can see, computed once.
    pub fn brick_objects(&self) -> &BrickObjects {
        self.bricks.get_or_init(|| {
            let brick = hatchery_data::bricks::BRICK;
            let l = &self.data;
            let dims = l.dims.map(|d| d.div_ceil(brick));
            let mut ids: Vec<Vec<u16>> =
                vec![Vec::new(); dims.iter().map(|&d| d as usize).product()];
            let [nx, ny, nz] = l.dims;
            // Voxel v is seen by samples with floor(q) ∈ {v − 1, v}: the bricks of v − 1 and v.
            let near = |v: u32| [v.saturating_sub(1) / brick, v / brick];
            let mut i = 0;
            for z in 0..nz {
                for y in 0..ny {
                    for x in 0..nx {
                        let id = l.ids[i];
                        i += 1;
                        for bz in near(z) {
                            for by in near(y) {
                                for bx in near(x) {
                                    let list =
                                        &mut ids[(bx + dims[0] * (by + dims[1] * bz)) as usize];
                                    if !list.contains(&id) {
                                        list.push(id);
                                    }
                                }
                            }
                        }
                    }
                }
            }
            ids.iter_mut().for_each(|list| list.sort_unstable());
            BrickObjects { dims, ids }
        })
    }

    /// The id texture (R16Uint, dims of the label volume; bricked like a volume of these dims,
    /// see [`crate::brick_pool`]). Errors: dims beyond a brick pool.
    pub fn texture(&self, gpu: &GpuContext) -> Result<&GridTexture, GpuError> {
        if let Some(t) = self.texture.get() {
            return Ok(t);
        }
        let [nx, ny, _] = self.data.dims.map(|d| d as usize);
        let ids = &self.data.ids;
        let t = crate::brick_pool::grid_texture(
            gpu,
            "labels",
            self.data.dims,
            wgpu::TextureFormat::R16Uint,
            |z0, z1, out| {
                let slab = &ids[z0 as usize * nx * ny..z1 as usize * nx * ny];
                out.extend_from_slice(bytemuck::cast_slice(slab));
            },
        )?;
        Ok(self.texture.get_or_init(|| t))
    }
}

/// How one object's samples are coloured (the rendering modes of Hadwiger §2.2, Fig. 16/17).
/// The discriminants are the shader's codes (`MODE_*`, see `raycast::objects`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderMode {
    /// The transfer function's colour and opacity, unshaded.
    Dvr = 0,
    /// Colour × Blinn–Phong (eq. 3 of the context-preserving paper).
    ShadedDvr,
    /// Cool-to-warm tone shading by N·L (Gooch et al. 1998, as in the tutorial's figures).
    Tone,
    /// Contour enhancement: opacity × gradient magnitude × (1 − |N·V|)^8 (Csébfalvi et al. 2001).
    Contours,
    /// The transfer function's colour of the largest value (with MIP compositing).
    Mip,
    /// The shaded surface at the object's iso value (with iso compositing).
    Iso,
}

/// How the samples of one object's ray segment are combined (local compositing, §2.4). The
/// discriminants are the shader's codes (`LOCAL_*`, see `raycast::objects`).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compositing {
    /// Front-to-back alpha blending.
    Over = 0,
    /// The sample of largest intensity.
    Mip,
    /// The first sample at or above the object's iso value.
    Iso,
    /// The sum of the samples' premultiplied colours (alpha clamped to 1).
    Sum,
}

/// One object of a segmented volume: how it is rendered and composited.
#[derive(Clone, Debug)]
pub struct ObjectStyle {
    pub id: u16,
    pub name: String,
    pub enabled: bool,
    pub tf: hatchery_data::transfer_function::TransferFunction1D,
    pub mode: RenderMode,
    pub compositing: Compositing,
    /// Iso value for iso compositing, data units.
    pub iso: f32,
    /// Importance (importance-driven rendering, Viola et al.); not used by two-level rendering.
    pub importance: f32,
}

/// A triangle mesh: CPU data plus vertex (position, normal) and index buffers uploaded on first use.
pub struct Mesh {
    pub data: Arc<MeshData>,
    buffers: OnceLock<MeshBuffers>,
}

pub struct MeshBuffers {
    /// Interleaved position (xyz) and normal (xyz), 24 bytes per vertex.
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

impl Mesh {
    pub fn new(data: MeshData) -> Self {
        Self::shared(Arc::new(data))
    }
    /// A mesh over data held elsewhere too (in-memory graph inputs), without a copy.
    pub fn shared(data: Arc<MeshData>) -> Self {
        Self {
            data,
            buffers: OnceLock::new(),
        }
    }
    pub fn buffers(&self, gpu: &GpuContext) -> &MeshBuffers {
        self.buffers.get_or_init(|| {
            let d = &self.data;
            let mut interleaved = Vec::with_capacity(d.positions.len() * 6);
            for (p, n) in d.positions.iter().zip(&d.normals) {
                interleaved.extend_from_slice(p);
                interleaved.extend_from_slice(n);
            }
            // Empty meshes still get (tiny) buffers so that drawing them is a no-op.
            if interleaved.is_empty() {
                interleaved.resize(6, 0.0);
            }
            let indices: Vec<u32> = if d.indices.is_empty() {
                vec![0, 0, 0]
            } else {
                d.indices.clone()
            };
            MeshBuffers {
                vertices: gpu.buffer_init(
                    "mesh vertices",
                    bytemuck::cast_slice(&interleaved),
                    // Storage too: HatchStrokes reads the vertices as seeds.
                    wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
                ),
                indices: gpu.buffer_init(
                    "mesh indices",
                    bytemuck::cast_slice(&indices),
                    wgpu::BufferUsages::INDEX,
                ),
                index_count: d.indices.len() as u32,
            }
        })
    }
}

/// Screen-space surface data of one layer.
pub struct GBuffer {
    /// Window-space depth in [0, 1] (Depth32Float); 1 where no surface.
    pub depth: wgpu::Texture,
    /// View-space unit normal in xyz, coverage (1 or 0) in w (Rgba16Float).
    pub normal: wgpu::Texture,
    /// The camera the layer was rendered with (to unproject depth).
    pub camera: camera::Camera,
}

/// RGBA colour, premultiplied alpha (Rgba16Float).
pub struct Image {
    pub texture: wgpu::Texture,
}

/// One-channel float image (R32Float).
pub struct Mask {
    pub texture: wgpu::Texture,
}

/// A transfer function: colour + opacity per value, or a style transfer function (§4.1 of
/// Bruckner & Gröller 2007) referring to a set of lit-sphere styles.
pub enum TransferFunction {
    Color(hatchery_data::transfer_function::TransferFunction1D),
    /// `function` applies to every object; `per_label` rows replace it for the listed labels of
    /// a label volume (the 2-D value × object variant of §4.2).
    Style {
        function: hatchery_data::style::StyleTransferFunction,
        per_label: Vec<(i64, hatchery_data::style::StyleTransferFunction)>,
        styles: Arc<StyleSet>,
    },
    /// A 2-D colour transfer function over value × a second coordinate (gradient magnitude or
    /// Laplacian; `TransferFunction2D`, Kniss et al. 2002 / Svakhine et al. 2005 §3.3). Only
    /// `Raycast` (mode dvr) classifies with it; the other consumers refuse it.
    TwoD(hatchery_data::transfer_function_2d::TransferFunction2D),
}

/// Lit-sphere maps (§3.1), each with its own mip chain, uploaded as the layers of one texture
/// array on first use (mip-mapping per layer never mixes styles, §4.3).
pub struct StyleSet {
    pub names: Vec<String>,
    pub maps: Vec<hatchery_data::lit_sphere::LitSphere>,
    texture: OnceLock<wgpu::Texture>,
}

impl StyleSet {
    pub fn new(names: Vec<String>, maps: Vec<hatchery_data::lit_sphere::LitSphere>) -> Self {
        Self {
            names,
            maps,
            texture: OnceLock::new(),
        }
    }

    /// The Rgba16Float texture array, one layer per style, full mip chains.
    pub fn texture(&self, gpu: &GpuContext) -> &wgpu::Texture {
        self.texture.get_or_init(|| {
            let size = self.maps.first().map_or(1, |m| m.size);
            let chains: Vec<Vec<hatchery_data::lit_sphere::LitSphere>> =
                self.maps.iter().map(|m| m.mip_chain()).collect();
            let levels = chains.first().map_or(1, |c| c.len() as u32);
            let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("styles"),
                size: wgpu::Extent3d {
                    width: size,
                    height: size,
                    depth_or_array_layers: self.maps.len().max(1) as u32,
                },
                mip_level_count: levels,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba16Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            for (layer, chain) in chains.iter().enumerate() {
                for (level, map) in chain.iter().enumerate() {
                    let texels: Vec<half::f16> = map
                        .texels
                        .iter()
                        .flat_map(|t| t.map(half::f16::from_f32))
                        .collect();
                    gpu.queue.write_texture(
                        wgpu::TexelCopyTextureInfo {
                            texture: &texture,
                            mip_level: level as u32,
                            origin: wgpu::Origin3d {
                                x: 0,
                                y: 0,
                                z: layer as u32,
                            },
                            aspect: wgpu::TextureAspect::All,
                        },
                        bytemuck::cast_slice(&texels),
                        wgpu::TexelCopyBufferLayout {
                            offset: 0,
                            bytes_per_row: Some(map.size * 8),
                            rows_per_image: None,
                        },
                        wgpu::Extent3d {
                            width: map.size,
                            height: map.size,
                            depth_or_array_layers: 1,
                        },
                    );
                }
            }
            texture
        })
    }
}

/// How importance compositing turns importance into levels of sparseness (Viola et al.). The
/// discriminants are the shader's codes (`IMP_*`, see `raycast::objects`; 0 is "none").
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImportanceMethod {
    /// Maximum importance projection: in the focus footprint only the focus is drawn; around
    /// it the context in front of the countersink (eq. 1) is cut away.
    Mimp = 1,
    /// Average importance compositing, image space: every sample of object o at a pixel gets
    /// S_o = I_o / Σ I (eq. 2) over the (dilated, averaged) footprints covering the pixel.
    AimcImage,
    /// Average importance compositing, object space: only context samples in front of the
    /// countersink (in front of the focus) get S_o.
    AimcObject,
    /// Visibility-preserving importance compositing: the occluding context's accumulated
    /// opacity is scaled by S_o / α_avg (eq. 3).
    Vpimc,
}

/// The per-pixel data of importance compositing for one frame (ImportanceCompositing →
/// TwoLevelRaycast), all on the GPU.
pub struct Importance {
    pub method: ImportanceMethod,
    /// The focus object's id.
    pub focus: u16,
    /// Importance I_o of every drawn object, by id.
    pub importance: Vec<(u16, f32)>,
    /// Frame-sized Rgba32Float: (countersink depth E as view depth in world units — the
    /// focus's first hit inside the footprint, e_max − d_i·s_c around it, −1e30 where nothing
    /// is cut —, footprint-weighted importance sum Σ I, 1 inside the focus footprint else 0,
    /// the focus's last-hit view depth or −1).
    pub buffer: wgpu::Texture,
    /// Frame-sized Rgba32Float: the countersink's view-space unit normal (xyz) and d_i, the
    /// distance to the footprint in pixels (w).
    pub cut: wgpu::Texture,
    /// 1×1 Rgba32Float: (e_max, footprint size in pixels, 0, 0).
    pub stats: wgpu::Texture,
    /// The view the buffers were made for.
    pub camera: camera::Camera,
}

/// A value on an edge.
#[derive(Clone)]
pub enum Value {
    Volume(Arc<Volume>),
    Mesh(Arc<Mesh>),
    Camera(Arc<camera::Camera>),
    Light(Arc<light::Light>),
    GBuffer(Arc<GBuffer>),
    Image(Arc<Image>),
    Mask(Arc<Mask>),
    TransferFunction(Arc<TransferFunction>),
    StyleSet(Arc<StyleSet>),
    Labels(Arc<Labels>),
    ObjectStyles(Arc<Vec<ObjectStyle>>),
    Importance(Arc<Importance>),
    Annotations(Arc<annotations::Annotations>),
    Strokes(Arc<strokes::Strokes>),
    VectorField(Arc<vector_field::VectorField>),
}

impl Value {
    pub fn port_type(&self) -> PortType {
        match self {
            Value::Volume(_) => PortType::Volume,
            Value::Mesh(_) => PortType::Mesh,
            Value::Camera(_) => PortType::Camera,
            Value::Light(_) => PortType::Light,
            Value::GBuffer(_) => PortType::GBuffer,
            Value::Image(_) => PortType::Image,
            Value::Mask(_) => PortType::Mask,
            Value::TransferFunction(_) => PortType::TransferFunction,
            Value::StyleSet(_) => PortType::StyleSet,
            Value::Labels(_) => PortType::Labels,
            Value::ObjectStyles(_) => PortType::ObjectStyles,
            Value::Importance(_) => PortType::Importance,
            Value::Annotations(_) => PortType::Annotations,
            Value::Strokes(_) => PortType::Strokes,
            Value::VectorField(_) => PortType::VectorField,
        }
    }
}

/// Typed access to inputs: `inputs.require(..)?.volume(..)?`. A wrong variant means a node and
/// its schema disagree (validation checked the edge types), reported as a node error.
macro_rules! accessor {
    ($fn:ident, $variant:ident, $ty:ty) => {
        impl Value {
            pub fn $fn(&self, port: &str) -> Result<&$ty, hatchery_graph::NodeError> {
                match self {
                    Value::$variant(v) => Ok(v),
                    other => Err(hatchery_graph::NodeError::at_port(
                        port,
                        format!(
                            "expected {}, got {}",
                            stringify!($variant),
                            other.port_type()
                        ),
                    )),
                }
            }
        }
    };
}
accessor!(volume, Volume, Arc<Volume>);
accessor!(mesh, Mesh, Arc<Mesh>);
accessor!(camera, Camera, Arc<camera::Camera>);
accessor!(light, Light, Arc<light::Light>);
accessor!(gbuffer, GBuffer, Arc<GBuffer>);
accessor!(image, Image, Arc<Image>);
accessor!(mask, Mask, Arc<Mask>);
accessor!(transfer_function, TransferFunction, Arc<TransferFunction>);
accessor!(style_set, StyleSet, Arc<StyleSet>);
accessor!(labels, Labels, Arc<Labels>);
accessor!(object_styles, ObjectStyles, Arc<Vec<ObjectStyle>>);
accessor!(importance, Importance, Arc<Importance>);
accessor!(annotations, Annotations, Arc<annotations::Annotations>);
accessor!(strokes, Strokes, Arc<strokes::Strokes>);
accessor!(vector_field, VectorField, Arc<vector_field::VectorField>);
