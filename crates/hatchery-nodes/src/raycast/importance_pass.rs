//! The compute pipelines of shaders/importance.wgsl (importance compositing's footprints,
//! distance transform and sums, and the alpha mean `TwoLevelRaycast` reads), shared by both
//! ray casters of segmented volumes.

use hatchery_gpu::{GpuContext, GpuError};

crate::uniform_block! {
    /// `PassParams` of shaders/importance.wgsl.
    pub struct PassUniforms in "importance" as "PassParams" {
        /// The axis (0 = x, 1 = y) of a separable kernel, or the JFA step in pixels.
        pub step: u32,
        /// The kernel radius in pixels.
        pub radius: u32,
        pub pad0: u32,
        pub pad1: u32,
    }
}

pub(crate) const KERNELS: [&str; 9] = [
    "footprint",
    "dilate",
    "weigh",
    "box",
    "jfa_init",
    "jfa_step",
    "reduce",
    "finish",
    "alpha_mean",
];

/// The compute pipelines of shaders/importance.wgsl, by entry point (`KERNELS` order).
pub struct ImportancePipelines {
    pipelines: Vec<wgpu::ComputePipeline>,
}

impl ImportancePipelines {
    pub fn new(gpu: &GpuContext) -> Result<Self, GpuError> {
        let source = crate::kinds::source("importance").expect("registered program");
        let module = gpu.shader("importance", &source)?;
        let pipelines = KERNELS
            .iter()
            .map(|entry| {
                gpu.checked(&format!("pipeline importance/{entry}"), |device| {
                    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(entry),
                        layout: None,
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: Default::default(),
                        cache: None,
                    })
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Self { pipelines })
    }

    fn get(&self, entry: &str) -> &wgpu::ComputePipeline {
        let i = KERNELS.iter().position(|k| *k == entry).expect("a kernel");
        &self.pipelines[i]
    }

    /// Records one dispatch of `entry` with its bindings (binding number, resource); `groups`
    /// workgroups in x and y.
    pub fn dispatch(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        entry: &str,
        bindings: &[(u32, wgpu::BindingResource)],
        groups: (u32, u32),
    ) {
        let pipeline = self.get(entry);
        let group = gpu.bind_group(entry, &pipeline.get_bind_group_layout(0), bindings);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(entry),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(groups.0, groups.1, 1);
    }

    /// Passes of `entry` that read `views[i]` at binding `read` and write the other at `write`,
    /// one per `(step, radius)` (`PassParams`), starting from `views[0]`; the index of the view
    /// holding the result.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn ping_pong(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        entry: &str,
        params: &wgpu::Buffer,
        views: &[wgpu::TextureView; 2],
        (read, write): (u32, u32),
        steps: &[[u32; 2]],
        groups: (u32, u32),
    ) -> usize {
        let mut at = 0;
        for &[step, radius] in steps {
            let pass = gpu.buffer_init(
                "importance pass",
                bytemuck::bytes_of(&PassUniforms {
                    step,
                    radius,
                    pad0: 0,
                    pad1: 0,
                }),
                wgpu::BufferUsages::UNIFORM,
            );
            self.dispatch(
                gpu,
                encoder,
                entry,
                &[
                    (20, params.as_entire_binding()),
                    (21, pass.as_entire_binding()),
                    (read, wgpu::BindingResource::TextureView(&views[at])),
                    (write, wgpu::BindingResource::TextureView(&views[1 - at])),
                ],
                groups,
            );
            at = 1 - at;
        }
        at
    }
}
