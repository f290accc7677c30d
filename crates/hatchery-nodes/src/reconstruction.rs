//! How the nodes that sample volumes reconstruct the field between voxels (Hadwiger et al.,
//! tutorial §1.3 "Filter kernel considerations"): trilinear values with central-difference
//! gradients, or the tricubic B-spline's values, gradients and Hessians
//! (shaders/ray_bspline.wgsl). A pipeline constant of every ray caster (RAY_RECONSTRUCTION).

hatchery_graph::param_choice! {
    /// The `reconstruction` parameter. `trilinear`: one fetch per value, six per gradient; the
    /// voxel lattice shows as a waffle of highlights on sharp boundaries under a sharp transfer
    /// function. `bspline`: the tricubic B-spline (C² smooth, slightly smoothing: it
    /// approximates rather than interpolates), 8 fetches per value and 24 per gradient — in
    /// Raycast on CPU adapters, for unbricked volumes within the budget, 16 loads of x-quads for
    /// both (value/bspline_quads.rs; docs/benchmarks.md gives the cost).
    pub enum Reconstruction { Trilinear = "trilinear", Bspline = "bspline" }
}

impl Reconstruction {
    /// The value of the shaders' RAY_RECONSTRUCTION constant (RECONSTRUCTION_* in
    /// shaders/ray_common.wgsl).
    pub fn code(self) -> i32 {
        self as i32
    }

    /// `(name, value)` of the pipeline constant, for `shaders::specialise` or a pipeline's
    /// overridable constants.
    pub fn constant(self) -> (&'static str, f64) {
        ("RAY_RECONSTRUCTION", f64::from(self.code()))
    }

    /// The filter a node uses on `volume`. The B-spline of a sample reads 64 voxels, and a
    /// "no data" (NaN) voxel among them that carries little weight cannot be told from data
    /// by the filtered fetches (it would pull the value down instead of falling back), so a
    /// volume with "no data" voxels is drawn trilinear, with a warning.
    pub fn on(self, ctx: &mut crate::Ctx, volume: &hatchery_data::VolumeData) -> Reconstruction {
        if self == Reconstruction::Bspline && volume.has_no_data() {
            ctx.warn(
                "reconstruction bspline: the volume has \"no data\" (NaN) voxels, which the \
                 B-spline cannot leave out; drawn with the trilinear filter",
            );
            return Reconstruction::Trilinear;
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::Reconstruction;

    #[test]
    fn codes_match_the_shader_constants() {
        let source = crate::shaders::RAY_COMMON;
        for r in Reconstruction::ALL {
            let name = format!(
                "const RECONSTRUCTION_{}: i32 = {};",
                r.name().to_uppercase(),
                r.code()
            );
            assert!(source.contains(&name), "ray_common.wgsl lacks `{name}`");
        }
    }
}
