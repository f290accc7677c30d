//! Svakhine, Jang, Ebert & Gaither 2005, Table 1 ("Illustration and rendering techniques"):
//! boundary enhancement, silhouette enhancement and the banding widget as options of `Raycast`
//! (DVR). The equations are applied per sample in shaders/raycast.wgsl; docs/enhancement.md
//! says what each does, in which order and how |∇P| is normalised.

hatchery_graph::node_params! {
    /// The Table 1 enhancements of Svakhine et al. 2005 (§3.2–3.3), shared by the ray casters
    /// that offer them. All off by default (exponents 0, period 0): the pipeline then has no
    /// enhancement code at all.
    pub struct EnhancementParams {
        /// boundary enhancement n (Svakhine et al. 2005 §3.2, Table 1: o_e = o_o · |∇P|^n):
        /// samples on strong boundaries keep their opacity, flat regions fade; |∇P| is the
        /// gradient magnitude divided by the volume's largest, so 1 on the sharpest boundary;
        /// larger n keeps only sharper boundaries (0 = off; DVR)
        pub boundary_enhancement: f32 = 0.0, range(0.0, 16.0);
        /// silhouette enhancement n (Svakhine et al. 2005 §3.2, Table 1: o_e = o_o · (1 −
        /// |∇P̂·V|)^n): samples whose boundary faces the viewer fade, those seen edge-on (the
        /// outlines) keep their opacity; larger n gives thinner outlines (0 = off; DVR)
        pub silhouette_enhancement: f32 = 0.0, range(0.0, 16.0);
        /// banding widget period m (Svakhine et al. 2005 §3.3, Table 1: o_e = ((1 + sin(o_o·π·m))
        /// / 2)^n): the transfer function's opacity is mapped through a sine, so the volume
        /// shows as alternating opaque and clear contour shells; more m, more and thinner bands
        /// (0 = off; DVR, where the transfer function is not transparent)
        pub banding: f32 = 0.0, range(0.0, 64.0);
        /// banding widget power n (Svakhine et al. 2005 §3.3, Table 1): above 1 makes the bands
        /// thinner and sharper, below 1 softer and wider
        pub banding_power: f32 = 1.0, range(0.05, 16.0);
        /// what boundary and silhouette enhancement measure (Svakhine et al. 2005 §3.2, Table
        /// 1): rendered (∇P of the rendered field), second (the gradient of the field on the
        /// `second` input, e.g. temperature while density is rendered) or vector (the vector
        /// field U on the `vector` input itself: |U|^n, divided by the largest |U|, and
        /// (1 − |Û·V|)^n, so flow seen side-on keeps its opacity)
        pub enhancement_field: EnhancementField = EnhancementField::Rendered;
    }
}

hatchery_graph::param_choice! {
    /// The field boundary and silhouette enhancement measure.
    pub enum EnhancementField { Rendered = "rendered", Second = "second", Vector = "vector" }
}

crate::gpu_enum! {
    /// raycast.wgsl's `RAY_ENHANCE_FIELD`: where boundary and silhouette enhancement take
    /// their direction and normalised magnitude.
    pub enum EnhanceField in "raycast" {
        /// ∇P / max |∇P| of the rendered field.
        Rendered = 0 as "ENHANCE_FROM_RENDERED",
        /// ∇S / max |∇S| of the second field (`second_field`'s xyz).
        Second = 1 as "ENHANCE_FROM_SECOND",
        /// U / max |U| (`vector_field`'s xyz).
        Vector = 2 as "ENHANCE_FROM_VECTOR",
    }
}

crate::gpu_enum! {
    /// The bits of raycast.wgsl's `RAY_ENHANCE` constant: which enhancements a pipeline applies.
    pub enum EnhanceBit in "raycast" {
        /// o_o · |∇P|^n.
        Boundary = 1 as "ENHANCE_BOUNDARY",
        /// o_o · (1 − |∇P̂·V|)^n.
        Silhouette = 2 as "ENHANCE_SILHOUETTE",
        /// ((1 + sin(o_o·π·m)) / 2)^n.
        Banding = 4 as "ENHANCE_BANDING",
    }
}

crate::uniform_block! {
    /// `Enhancement` of shaders/raycast.wgsl: the exponents and the banding period, and a 2-D
    /// transfer function's second domain.
    pub struct EnhancementUniforms in "raycast" as "Enhancement" {
        pub boundary: f32,
        pub silhouette: f32,
        pub banding_period: f32,
        pub banding_power: f32,
        pub second_domain: [f32; 2],
        /// The second field's value range (its texture's w is (S − min) / (max − min)).
        pub second_range: [f32; 2],
    }
}

crate::gpu_enum! {
    /// raycast.wgsl's `RAY_TF2D`: the second axis of a 2-D transfer function (0: a 1-D one).
    pub enum Tf2dAxis in "raycast" {
        /// |∇f| / max |∇f|.
        GradientMagnitude = 1 as "TF2D_GRADIENT",
        /// ∇²f (data units per voxel²).
        Laplacian = 2 as "TF2D_LAPLACIAN",
        /// The second field's value S (its data units).
        SecondField = 3 as "TF2D_SECOND",
    }
}

impl Tf2dAxis {
    /// The code of a data-crate axis.
    pub fn of(axis: hatchery_data::transfer_function_2d::SecondAxis) -> Self {
        use hatchery_data::transfer_function_2d::SecondAxis;
        match axis {
            SecondAxis::GradientMagnitude => Self::GradientMagnitude,
            SecondAxis::Laplacian => Self::Laplacian,
            SecondAxis::SecondField => Self::SecondField,
        }
    }
}

/// The enhancements one ray-casting pass applies (see [`EnhancementParams`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enhancement {
    /// Boundary-enhancement exponent (0: off).
    pub boundary: f32,
    /// Silhouette-enhancement exponent (0: off).
    pub silhouette: f32,
    /// Banding period m (0: off) and power n.
    pub banding_period: f32,
    pub banding_power: f32,
    /// What boundary and silhouette enhancement measure.
    pub field: EnhanceField,
}

impl Enhancement {
    /// No enhancement.
    pub const OFF: Self = Self {
        boundary: 0.0,
        silhouette: 0.0,
        banding_period: 0.0,
        banding_power: 1.0,
        field: EnhanceField::Rendered,
    };

    /// The bits of `RAY_ENHANCE` (0: none, the shader folds every enhancement away).
    pub fn bits(&self) -> u32 {
        let on = |x: f32, bit: EnhanceBit| if x > 0.0 { bit.code() } else { 0 };
        on(self.boundary, EnhanceBit::Boundary)
            | on(self.silhouette, EnhanceBit::Silhouette)
            | on(self.banding_period, EnhanceBit::Banding)
    }

    /// Whether any enhancement is on.
    pub fn any(&self) -> bool {
        self.bits() != 0
    }

    /// The field boundary or silhouette enhancement read, if one of them is on.
    pub fn measured_field(&self) -> Option<EnhanceField> {
        let measuring = EnhanceBit::Boundary.code() | EnhanceBit::Silhouette.code();
        (self.bits() & measuring != 0).then_some(self.field)
    }

    /// The uniform block.
    pub fn uniforms(&self) -> EnhancementUniforms {
        EnhancementUniforms {
            boundary: self.boundary,
            silhouette: self.silhouette,
            banding_period: self.banding_period,
            banding_power: self.banding_power,
            second_domain: [0.0, 1.0],
            second_range: [0.0, 1.0],
        }
    }
}

impl EnhancementParams {
    /// The enhancements these parameters ask for.
    pub fn enhancement(&self) -> Enhancement {
        Enhancement {
            boundary: self.boundary_enhancement,
            silhouette: self.silhouette_enhancement,
            banding_period: self.banding,
            banding_power: self.banding_power,
            field: match self.enhancement_field {
                EnhancementField::Rendered => EnhanceField::Rendered,
                EnhancementField::Second => EnhanceField::Second,
                EnhancementField::Vector => EnhanceField::Vector,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Enhancement;

    #[test]
    fn off_has_no_bits_and_each_option_its_own() {
        assert_eq!(Enhancement::OFF.bits(), 0);
        let on = |f: fn(&mut Enhancement)| {
            let mut e = Enhancement::OFF;
            f(&mut e);
            e.bits()
        };
        assert_eq!(on(|e| e.boundary = 2.0), 1);
        assert_eq!(on(|e| e.silhouette = 0.5), 2);
        assert_eq!(on(|e| e.banding_period = 8.0), 4);
        assert_eq!(on(|e| e.banding_power = 3.0), 0);
    }
}
