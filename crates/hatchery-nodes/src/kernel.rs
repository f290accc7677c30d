//! Which GPU path a full-frame pass takes (ray casters, fused image-space passes): a fragment
//! shader or a compute kernel, the same picture either way.

/// The GPU path of a ray-casting pass: a full-screen fragment shader, or a compute kernel over
/// 8×8-pixel tiles. Same rays, same samples, same picture (tests/raycast.rs compares them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    Fragment,
    Compute,
}

hatchery_graph::param_choice! {
    /// The `kernel` parameter of the ray casters: a GPU path, or `auto`.
    pub enum KernelChoice { Auto = "auto", Fragment = "fragment", Compute = "compute" }
}

impl Kernel {
    /// The path for `choice` on `gpu`. `auto` picks the fragment path, the faster one measured
    /// on lavapipe, except on adapters whose graphics pipeline runs on part of the chip only
    /// (NVIDIA's H100/H200 compute parts), where compute is many times faster
    /// (docs/benchmarks.md).
    pub fn choose(choice: KernelChoice, gpu: &hatchery_gpu::GpuContext) -> Kernel {
        match choice {
            KernelChoice::Fragment => Kernel::Fragment,
            KernelChoice::Compute => Kernel::Compute,
            KernelChoice::Auto if gpu.is_compute_part() => Kernel::Compute,
            KernelChoice::Auto => Kernel::Fragment,
        }
    }
}
