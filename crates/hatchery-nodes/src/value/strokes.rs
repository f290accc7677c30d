//! Hatching strokes traced on the GPU (by HatchStrokes, hatch_strokes.rs), read back as
//! polylines on first use (SaveSvg, tests).

use glam::Vec2;
use hatchery_gpu::{GpuContext, GpuError};
use std::sync::OnceLock;

/// One traced stroke, pixels (top-left origin, y down).
#[derive(Clone, Debug, PartialEq)]
pub struct StrokeLine {
    /// Index of the seed (mesh vertex) it grew from.
    pub seed: u32,
    /// Whether it is a cross-hatching stroke (along the other principal direction).
    pub cross: bool,
    /// Its points, one RK4 step apart, the seed among them.
    pub points: Vec<Vec2>,
}

/// The strokes of one HatchStrokes run: the GPU buffers they were traced into, and their
/// polylines read back on first use (SaveSvg, tests).
pub struct Strokes {
    pub(crate) counter: wgpu::Buffer,
    pub(crate) headers: wgpu::Buffer,
    pub(crate) points: wgpu::Buffer,
    /// Point slots per stroke (2 · steps + 1).
    pub(crate) slots: u32,
    pub(crate) max_strokes: u32,
    /// Stroke width in the middle, px (the ends taper).
    pub width: f32,
    /// Fraction of a stroke's length over which each end tapers to nothing (0: none).
    pub taper: f32,
    /// Frame width × height, px.
    pub frame: (u32, u32),
    /// Kept once read; a failed read is not kept (in the browser the first read only starts the
    /// copy, hatchery_gpu::web_readback).
    pub(crate) lines: OnceLock<Vec<StrokeLine>>,
}

impl Strokes {
    /// The strokes as polylines of at least three points (read back from the GPU once).
    /// Errors: [`GpuError::Readback`] when the buffers cannot be read back.
    pub fn lines(&self, gpu: &GpuContext) -> Result<&[StrokeLine], GpuError> {
        if let Some(lines) = self.lines.get() {
            return Ok(lines);
        }
        let lines = self.read_back(gpu).map_err(|message| GpuError::Readback {
            what: "the strokes".into(),
            message,
        })?;
        Ok(self.lines.get_or_init(|| lines))
    }

    fn read_back(&self, gpu: &GpuContext) -> Result<Vec<StrokeLine>, String> {
        let read = |buffer: &wgpu::Buffer, bytes: u64| {
            gpu.read_buffer(buffer, bytes).map_err(|e| match e {
                GpuError::Readback { message, .. } => message,
                e => e.to_string(),
            })
        };
        let counter = read(&self.counter, 4)?;
        let count = counter
            .get(..4)
            .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .min(self.max_strokes) as usize;
        if count == 0 {
            return Ok(Vec::new());
        }
        let slots = self.slots as usize;
        let headers: Vec<u32> =
            bytemuck::pod_collect_to_vec(&read(&self.headers, 16 * count as u64)?);
        let points: Vec<[f32; 2]> =
            bytemuck::pod_collect_to_vec(&read(&self.points, 8 * (count * slots) as u64)?);
        if headers.len() < 4 * count || points.len() < count * slots {
            return Err("the strokes read back from the GPU are incomplete".into());
        }
        Ok((0..count)
            // A seed on a silhouette or a fold stops at once: the shader leaves such strokes
            // (under two steps) empty, and nothing is drawn for them.
            .filter(|&s| headers[4 * s + 2] > headers[4 * s + 1])
            .map(|s| {
                let h = &headers[4 * s..4 * s + 4];
                let last = (h[2] as usize).min(slots - 1);
                let first = (h[1] as usize).min(last);
                StrokeLine {
                    seed: h[0],
                    cross: h[3] == 1,
                    points: points[s * slots + first..=s * slots + last]
                        .iter()
                        .map(|&p| Vec2::from(p))
                        .collect(),
                }
            })
            .collect())
    }
}
