//! The textures a ray-casting pass reads besides the volume: the classification tables (colour
//! TF, or the style TF's tft/ift rows per object, §4.1–4.2), the label → row table, the lighting
//! transfer function (eq. 8) and the empty-space skipping tables (bricks, visible values).

use super::RayOptions;
use super::bindings::RayBindings;
use super::pass::Statics;
use super::uniforms::TableInfo;
use super::uniforms::{RayMode, RayShading};
use crate::value::{TransferFunction, Volume};
use hatchery_data::{bricks, lighting};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::NodeError;

/// The style tables of §4.1 as textures, one row per object (§4.2): row 0 is the function for
/// every object, rows 1.. the per-label ones.
struct StyleTables {
    rows: u32,
    /// LUT_SIZE × rows of (i, α_u, 0, 0).
    tft: Vec<f32>,
    ift_width: u32,
    /// ift_width × rows of style indices.
    ift: Vec<f32>,
    label_width: u32,
    /// label_width × 2: row 0 = table row of each label (x); row 1 = (domain lo, hi, N, 0) per row.
    label_rows: Vec<f32>,
}

impl StyleTables {
    fn new(
        function: &hatchery_data::style::StyleTransferFunction,
        per_label: &[(i64, hatchery_data::style::StyleTransferFunction)],
    ) -> Self {
        let functions: Vec<&hatchery_data::style::StyleTransferFunction> =
            std::iter::once(function)
                .chain(per_label.iter().map(|(_, f)| f))
                .collect();
        let rows = functions.len() as u32;
        let ift_width = functions
            .iter()
            .map(|f| f.ift.len())
            .max()
            .unwrap_or(1)
            .max(1) as u32;
        let mut tft = Vec::new();
        let mut ift = Vec::new();
        for f in &functions {
            tft.extend(f.tft.iter().flat_map(|e| [e[0], e[1], 0.0, 0.0]));
            let mut row: Vec<f32> = f.ift.iter().map(|&j| j as f32).collect();
            row.resize(ift_width as usize, *row.last().unwrap_or(&0.0));
            ift.extend(row);
        }
        // Labels up to the largest listed one, plus one slot for every larger label (row 0).
        let max_label = per_label
            .iter()
            .map(|(l, _)| *l)
            .max()
            .unwrap_or(0)
            .clamp(0, 65_534);
        let label_width = (max_label as u32 + 2).max(rows);
        let mut label_rows = vec![0.0f32; label_width as usize * 8];
        for (row, (label, _)) in per_label.iter().enumerate() {
            if (0..=max_label).contains(label) {
                label_rows[*label as usize * 4] = (row + 1) as f32;
            }
        }
        for (row, f) in functions.iter().enumerate() {
            let at = (label_width as usize + row) * 4;
            label_rows[at..at + 4].copy_from_slice(&[
                f.domain[0],
                f.domain[1],
                f.ift.len() as f32,
                0.0,
            ]);
        }
        Self {
            rows,
            tft,
            ift_width,
            ift,
            label_width,
            label_rows,
        }
    }
}

fn floats_texture(
    gpu: &GpuContext,
    label: &str,
    width: u32,
    format: wgpu::TextureFormat,
    data: &[f32],
) -> wgpu::Texture {
    gpu.texture_2d_init(label, width, 1, format, bytemuck::cast_slice(data))
}

/// The views of the ray casters' tables (group 0, see shaders/ray_common.wgsl), and what
/// the tables put into the uniforms.
pub struct RayTables {
    pub table: wgpu::TextureView,
    pub lighting: wgpu::TextureView,
    pub styles: wgpu::TextureView,
    pub index: wgpu::TextureView,
    pub labels: wgpu::TextureView,
    pub label_rows: wgpu::TextureView,
    pub bricks: wgpu::TextureView,
    pub visibility: wgpu::TextureView,
    pub info: TableInfo,
}

impl RayTables {
    /// Builds the tables for `tf` (none: the iso-surface ray caster) and an optional label
    /// volume; `preintegrated`, the pre-integration table of `tf` where `o.preintegrated`
    /// (`hatchery_data::preintegration::preintegrated_table`), goes into the TF texture's rows
    /// 1 … LUT_SIZE. Errors: a style TF with per-label rows but no label volume, a label volume on
    /// another grid or elsewhere in the world, an unknown lighting model.
    pub fn new(
        gpu: &GpuContext,
        st: &Statics,
        volume: &Volume,
        tf: Option<&TransferFunction>,
        labels: Option<&Volume>,
        o: &RayOptions,
        preintegrated: Option<&[[f32; 4]]>,
    ) -> Result<Self, NodeError> {
        let err = |e: GpuError| NodeError::new(e.to_string());
        let data = &volume.data;
        let mut info = TableInfo {
            shading: o.shading,
            domain: [0.0, 1.0],
            nodes: 0,
            map_size: 1.0,
            use_labels: false,
            label_range: [0.0, 1.0],
            label_count: 0,
            skip_empty: false,
        };
        let mut style_view = None;
        let mut index_texture = None;
        let mut label_rows = None;
        let table = match tf {
            Some(TransferFunction::Color(f)) => {
                info.domain = f.domain;
                let mut flat: Vec<f32> = f.lut.iter().flatten().copied().collect();
                if let Some(table) = preintegrated {
                    // Rows 1 … LUT_SIZE: the pre-integrated table, row 1 + front position,
                    // column back position (shaders/raycast.wgsl, preintegrated_lookup).
                    flat.extend(table.iter().flatten());
                }
                let width = f.lut.len() as u32;
                Some(gpu.texture_2d_init(
                    "tf",
                    width,
                    (flat.len() / 4) as u32 / width,
                    wgpu::TextureFormat::Rgba32Float,
                    bytemuck::cast_slice(&flat),
                ))
            }
            Some(TransferFunction::Style {
                function,
                per_label,
                styles,
            }) => {
                info.domain = function.domain;
                info.shading = RayShading::Style;
                info.nodes = function.ift.len() as u32;
                info.map_size = styles.maps.first().map_or(1, |m| m.size) as f32;
                style_view = Some(
                    styles
                        .texture(gpu)
                        .create_view(&wgpu::TextureViewDescriptor {
                            dimension: Some(wgpu::TextureViewDimension::D2Array),
                            ..Default::default()
                        }),
                );
                if !per_label.is_empty() && labels.is_none() {
                    return Err(NodeError::at_port(
                        "labels",
                        "the style transfer function has per-label rows (`label_nodes`): connect a label volume",
                    ));
                }
                let tables = StyleTables::new(function, per_label);
                index_texture = Some(gpu.texture_2d_init(
                    "ift",
                    tables.ift_width,
                    tables.rows,
                    wgpu::TextureFormat::R32Float,
                    bytemuck::cast_slice(&tables.ift),
                ));
                label_rows = Some(gpu.texture_2d_init(
                    "label rows",
                    tables.label_width,
                    2,
                    wgpu::TextureFormat::Rgba32Float,
                    bytemuck::cast_slice(&tables.label_rows),
                ));
                info.label_count = tables.label_width;
                Some(gpu.texture_2d_init(
                    "tft",
                    hatchery_data::transfer_function::LUT_SIZE as u32,
                    tables.rows,
                    wgpu::TextureFormat::Rgba32Float,
                    bytemuck::cast_slice(&tables.tft),
                ))
            }
            Some(TransferFunction::TwoD(f)) => {
                // LUT_SIZE × ROWS (value × second coordinate); the second domain is in the
                // `Enhancement` block (raycast.wgsl, RAY_TF2D).
                info.domain = f.domain;
                let flat: Vec<f32> = f.table.iter().flatten().copied().collect();
                Some(gpu.texture_2d_init(
                    "tf 2d",
                    hatchery_data::transfer_function::LUT_SIZE as u32,
                    hatchery_data::transfer_function_2d::ROWS as u32,
                    wgpu::TextureFormat::Rgba32Float,
                    bytemuck::cast_slice(&flat),
                ))
            }
            None => None,
        };
        // Which values the transfer function shows, for empty-space skipping.
        let visible_rows: Vec<(Vec<f32>, [f32; 2])> = match tf {
            Some(TransferFunction::Color(f)) => {
                vec![(f.lut.iter().map(|e| e[3]).collect(), f.domain)]
            }
            Some(TransferFunction::Style {
                function,
                per_label,
                ..
            }) => std::iter::once(function)
                .chain(per_label.iter().map(|(_, f)| f))
                .map(|f| (f.tft.iter().map(|e| e[1]).collect(), f.domain))
                .collect(),
            // A value is visible where any second coordinate makes it so (exact: the lookup
            // interpolates between columns as a 1-D table does).
            Some(TransferFunction::TwoD(f)) => vec![(f.max_opacity_per_value(), f.domain)],
            None => Vec::new(),
        };
        let rows: Vec<bricks::OpacityRow> = visible_rows
            .iter()
            .map(|(opacity, domain)| bricks::OpacityRow {
                domain: *domain,
                opacity,
            })
            .collect();
        // DVR skips by the transfer function's visible values, so it needs one.
        info.skip_empty = o.skip_empty && (o.mode != RayMode::Dvr || !rows.is_empty());
        let visibility = floats_texture(
            gpu,
            "visibility",
            bricks::VISIBILITY_ENTRIES as u32,
            wgpu::TextureFormat::R32Float,
            &bricks::visibility_prefix(data.value_range, &rows),
        );

        let lighting_model = lighting::lighting_tf(o.lighting_model).ok_or_else(|| {
            NodeError::new(format!("unknown lighting model `{}`", o.lighting_model))
        })?;
        let lighting_flat: Vec<f32> = lighting_model.table.iter().flatten().copied().collect();
        let size = lighting::LIGHTING_SIZE as u32;
        let lighting_texture = gpu.texture_2d_init(
            "lighting tf",
            size,
            size,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&lighting_flat),
        );

        if let Some(l) = labels {
            info.label_range = l.texture(gpu).map_err(err)?.texel_range;
        }
        info.use_labels = labels.is_some() && label_rows.is_some();
        let labels_view = match labels.filter(|_| info.use_labels) {
            Some(l) => {
                check_same_grid(l, volume)?;
                l.texture(gpu)
                    .map_err(err)?
                    .texture
                    .create_view(&Default::default())
            }
            None => st.blank_labels.create_view(&Default::default()),
        };
        let view = |t: Option<&wgpu::Texture>, blank: &wgpu::Texture| {
            t.unwrap_or(blank).create_view(&Default::default())
        };
        Ok(Self {
            table: view(table.as_ref(), &st.blank_table),
            lighting: lighting_texture.create_view(&Default::default()),
            styles: style_view.unwrap_or_else(|| {
                st.blank_styles.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2Array),
                    ..Default::default()
                })
            }),
            index: view(index_texture.as_ref(), &st.blank_index),
            labels: labels_view,
            label_rows: view(label_rows.as_ref(), &st.blank_label_rows),
            bricks: volume
                .bricks(gpu, o.reconstruction)
                .map_err(err)?
                .create_view(&Default::default()),
            visibility: visibility.create_view(&Default::default()),
            info,
        })
    }
}

impl RayTables {
    /// Group 0 of a ray caster: `ray`, the volume (whole or its atlas) with its page table, and
    /// these tables.
    pub fn bindings<'a>(
        &'a self,
        ray: &'a wgpu::Buffer,
        volume: &'a wgpu::TextureView,
        page_table: &'a wgpu::TextureView,
        sampler: &'a wgpu::Sampler,
    ) -> RayBindings<'a> {
        RayBindings {
            ray: Some(ray),
            volume: Some(volume),
            linear_clamp: Some(sampler),
            tf_table: Some(&self.table),
            lighting_table: Some(&self.lighting),
            styles: Some(&self.styles),
            style_index: Some(&self.index),
            label_volume: Some(&self.labels),
            label_rows: Some(&self.label_rows),
            bricks: Some(&self.bricks),
            visibility: Some(&self.visibility),
            page_table: Some(page_table),
        }
    }
}

/// Labels are read at the volume's voxels: the grids must be the same and lie in the same place.
pub fn check_same_grid(labels: &Volume, volume: &Volume) -> Result<(), NodeError> {
    let l = &labels.data;
    check_grid_at("labels", "label volume", l.dims, &l.geometry, volume)
}

/// That a field on port `port` (`what`, in messages) with `dims` and `geometry` lies on
/// `volume`'s grid: the same dims and voxel → world transform.
pub fn check_grid_at(
    port: &str,
    what: &str,
    dims: [u32; 3],
    geometry: &hatchery_data::geometry::Geometry,
    volume: &Volume,
) -> Result<(), NodeError> {
    let data = &volume.data;
    if dims != data.dims {
        return Err(NodeError::at_port(
            port,
            format!(
                "{what} is {dims:?} voxels, the volume {:?}: they must share the grid",
                data.dims
            ),
        ));
    }
    if !data.geometry.same_placement(geometry) {
        return Err(NodeError::at_port(
            port,
            format!(
                "{what} lies elsewhere in the world ({}) than the volume ({}): \
                 they must share the voxel → world transform",
                geometry.describe(),
                data.geometry.describe()
            ),
        ));
    }
    Ok(())
}
