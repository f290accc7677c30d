//! Per-node GPU time from timestamp queries written around each of a node's submissions.
//!
//! Timestamps bracket the command buffers themselves, not the node's whole `execute`: a node that
//! works on the CPU first (loading, marching cubes) would otherwise count that time as GPU time.

use crate::context::GpuContext;
use std::collections::BTreeMap;
use std::time::Duration;

pub struct GpuTimer {
    queries: wgpu::QuerySet,
    /// Number of timestamp pairs the query set holds.
    capacity: u32,
    /// Node id per pair of queries written in this pass.
    pairs: Vec<String>,
}

impl GpuTimer {
    /// `None` when the device has no timestamp queries inside encoders.
    pub fn new(ctx: &GpuContext, capacity: u32) -> Option<Self> {
        if !ctx.has_timestamps() {
            return None;
        }
        let queries = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("node timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: capacity * 2,
        });
        Some(Self {
            queries,
            capacity,
            pairs: Vec::new(),
        })
    }

    fn stamp(&self, ctx: &GpuContext, index: u32) -> wgpu::CommandBuffer {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.write_timestamp(&self.queries, index);
        encoder.finish()
    }

    /// Submits `work` for `node`, between two timestamps (untimed once the query set is full).
    pub fn submit(&mut self, ctx: &GpuContext, node: &str, work: wgpu::CommandBuffer) {
        let pair = self.pairs.len() as u32;
        if pair >= self.capacity {
            ctx.queue.submit([work]);
            return;
        }
        let (begin, end) = (self.stamp(ctx, pair * 2), self.stamp(ctx, pair * 2 + 1));
        ctx.queue.submit([begin, work, end]);
        self.pairs.push(node.to_owned());
    }

    /// Waits for the pass's GPU work and returns each node's summed GPU time.
    pub fn finish(&mut self, ctx: &GpuContext) -> Vec<(String, Duration)> {
        let pairs = std::mem::take(&mut self.pairs);
        if pairs.is_empty() {
            return Vec::new();
        }
        let count = pairs.len() as u32 * 2;
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
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")))
            .collect();
        let period = ctx.queue.get_timestamp_period() as f64;
        let mut per_node: BTreeMap<String, f64> = BTreeMap::new();
        for (i, node) in pairs.into_iter().enumerate() {
            let ns = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * period;
            *per_node.entry(node).or_default() += ns;
        }
        per_node
            .into_iter()
            .map(|(node, ns)| (node, Duration::from_nanos(ns as u64)))
            .collect()
    }
}
