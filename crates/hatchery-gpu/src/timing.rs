//! Per-node GPU time from timestamp queries written before and after each node's work.

use crate::context::GpuContext;
use std::time::Duration;

/// Brackets each node's submissions with two timestamps; resolves them at the end of a pass.
pub struct GpuTimer {
    queries: wgpu::QuerySet,
    capacity: u32,
    /// Node id per pair of queries written in this pass.
    nodes: Vec<String>,
}

impl GpuTimer {
    /// `None` when the device has no timestamp queries inside encoders.
    pub fn new(ctx: &GpuContext, max_nodes: u32) -> Option<Self> {
        if !ctx.has_timestamps() {
            return None;
        }
        let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("node timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: max_nodes * 2,
        });
        Some(Self {
            queries,
            capacity: max_nodes,
            nodes: Vec::new(),
        })
    }

    fn write(&self, ctx: &GpuContext, index: u32) {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.write_timestamp(&self.queries, index);
        ctx.queue.submit([encoder.finish()]);
    }

    pub fn begin(&mut self, ctx: &GpuContext, node: &str) {
        if (self.nodes.len() as u32) < self.capacity {
            self.write(ctx, self.nodes.len() as u32 * 2);
            self.nodes.push(node.to_owned());
        }
    }

    pub fn end(&mut self, ctx: &GpuContext, node: &str) {
        if self.nodes.last().map(String::as_str) == Some(node) {
            self.write(ctx, self.nodes.len() as u32 * 2 - 1);
        }
    }

    /// Waits for the pass's GPU work and returns each node's GPU time.
    pub fn finish(&mut self, ctx: &GpuContext) -> Vec<(String, Duration)> {
        let nodes = std::mem::take(&mut self.nodes);
        if nodes.is_empty() {
            return Vec::new();
        }
        let count = nodes.len() as u32 * 2;
        let size = count as u64 * 8;
        let resolve = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps resolve"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps read"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.resolve_query_set(&self.queries, 0..count, &resolve, 0);
        encoder.copy_buffer_to_buffer(&resolve, 0, &read, 0, size);
        ctx.queue.submit([encoder.finish()]);
        let Ok(bytes) = ctx.map_buffer(&read) else {
            return Vec::new();
        };
        let ticks: &[u64] = bytemuck::cast_slice(&bytes);
        let period = ctx.queue.get_timestamp_period() as f64;
        nodes
            .into_iter()
            .enumerate()
            .map(|(i, node)| {
                let ns = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * period;
                (node, Duration::from_nanos(ns as u64))
            })
            .collect()
    }
}
