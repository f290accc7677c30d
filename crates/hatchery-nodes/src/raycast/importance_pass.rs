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
        Self::specialised(gpu, &[])
    }

    /// The pipelines with `constants` written into the program (see `shaders::specialise`),
    /// e.g. `TL_ID_QUADS`. Errors: a constant the program does not declare, or compilation.
    pub fn specialised(gpu: &GpuContext, constants: &[(&str, f64)]) -> Result<Self, GpuError> {
        let source = crate::kinds::source("importance").expect("registered program");
        let source = crate::shaders::specialise(&source, constants).map_err(|message| {
            GpuError::Validation {
                what: "specialising importance".into(),
                message,
            }
        })?;
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

    /// Records one dispatch of `entry` with bind groups 0 (the ray casters' shared group,
    /// empty for kernels that cast no rays) and 1 (the object tables and [`ImportanceBindings`])
    /// made of `bindings`' entries; `groups` workgroups in x and y.
    pub fn dispatch(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        entry: &str,
        bindings: [Vec<wgpu::BindGroupEntry>; 2],
        groups: (u32, u32),
    ) {
        let pipeline = self.get(entry);
        let bind_groups: Vec<wgpu::BindGroup> = bindings
            .iter()
            .enumerate()
            .map(|(i, entries)| {
                gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(entry),
                    layout: &pipeline.get_bind_group_layout(i as u32),
                    entries,
                })
            })
            .collect();
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(entry),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        for (i, group) in bind_groups.iter().enumerate() {
            pass.set_bind_group(i as u32, group, &[]);
        }
        pass.dispatch_workgroups(groups.0, groups.1, 1);
    }

    /// Passes of `entry` that read one of `views` and write the other (`which` says at which
    /// bindings), one per `(step, radius)` (`PassParams`), starting from `views[0]`; the index
    /// of the view holding the result.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn ping_pong(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        entry: &str,
        params: &wgpu::Buffer,
        views: &[wgpu::TextureView; 2],
        which: PingPong,
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
            let (read, write) = (Some(&views[at]), Some(&views[1 - at]));
            let mut own = ImportanceBindings {
                imp: Some(params),
                pass_params: Some(&pass),
                ..Default::default()
            };
            match which {
                PingPong::Bits => (own.bits_in, own.bits_out) = (read, write),
                PingPong::Sums => (own.sum_in, own.sum_out) = (read, write),
                PingPong::Seeds => (own.seed_in, own.seed_out) = (read, write),
            }
            self.dispatch(gpu, encoder, entry, [Vec::new(), own.entries()], groups);
            at = 1 - at;
        }
        at
    }
}

/// The texture pairs a ping-pong pass alternates between.
#[derive(Clone, Copy)]
pub(crate) enum PingPong {
    /// Object bits (dilate).
    Bits,
    /// Importance sums (box).
    Sums,
    /// Jump-flooding seeds (jfa_step).
    Seeds,
}

crate::bind_group! {
    /// ImportanceCompositing's own bindings, after the object tables (shaders/importance.wgsl;
    /// each kernel sets those it reads).
    pub struct ImportanceBindings in "importance", group 1 from 4 {
        pub imp: Buffer,
        pub pass_params: Buffer,
        pub footprint_out: TextureView,
        pub bits_out: TextureView,
        pub bits_in: TextureView,
        pub sum_out: TextureView,
        pub sum_in: TextureView,
        pub footprint_in: TextureView,
        pub seed_out: TextureView,
        pub seed_in: TextureView,
        pub stats_out: TextureView,
        pub stats_in: TextureView,
        pub buffer_out: TextureView,
        pub cut_out: TextureView,
        pub picture_in: TextureView,
    }
}
