//! `CurvatureContours`: contours of constant image-space thickness from the normal curvature
//! along the view direction (Kindlmann et al. 2003 §5, the tutorial's §1; see
//! shaders/curvature_contours.wgsl for the test).

use crate::curvature::{HessianFilter, Reconstruction, surface_pass};
use crate::screen_pass::MASK_FORMAT;
use crate::value::Mask;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `ContourParams` of shaders/curvature_contours.wgsl: the contour width in pixels.
    pub struct ContourUniforms in "curvature_contours" as "ContourParams" {
        pub thickness: f32,
        pub pad0: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `CurvatureContours`.
    pub struct CurvatureContoursParams {
        /// contour width, pixels
        pub thickness: f32 = 2.0, range(0.25, 32.0), unit(pixels);
        /// finite-difference step of the Hessian, voxels (as Curvature's)
        pub step: f32 = 1.0, range(0.25, 8.0);
        /// reconstruction of the gradient and Hessian (as Curvature's)
        pub reconstruction: Reconstruction = Reconstruction::Trilinear;
    }
}

pub struct CurvatureContoursNode;

impl Node<Value, Ctx> for CurvatureContoursNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "CurvatureContours",
            category: "Volume",
            doc: "Curvature-controlled contours (Kindlmann et al. 2003 §5, the tutorial's §1): \
                  a pixel of the iso-surface is on the contour where |n·v| ≤ √(T κv (2 − T κv)), \
                  κv the normal curvature along the view direction projected into the tangent \
                  plane (from the volume's Hessian, as Curvature computes it) and T \
                  `thickness` pixels at the point's depth, so the band is about `thickness` \
                  pixels wide on screen whatever the curvature (a plain |n·v| threshold is thin \
                  on sharp bends and thick on flat ones). No contour where the surface is \
                  concave along the view. Connect the G-buffer of IsoSurfaceRaycast and its \
                  volume.",
            inputs: vec![
                PortSpec::input("gbuffer", PortType::GBuffer, "the iso-surface's depth"),
                PortSpec::input(
                    "volume",
                    PortType::Volume,
                    "the scalar field it is a level of",
                ),
            ],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Mask,
                "1 on the contours",
            )],
            params: CurvatureContoursParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = CurvatureContoursParams::read(p)?;
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?.clone();
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let uniforms = ContourUniforms {
            thickness: params.thickness,
            pad0: 0.0,
            pad1: 0.0,
            pad2: 0.0,
        };
        let hessian = HessianFilter::of(params.step, params.reconstruction.on(ctx, &volume.data));
        let mask = surface_pass(
            ctx,
            "curvature_contours",
            MASK_FORMAT,
            &gbuffer,
            &volume,
            hessian,
            Some(bytemuck::bytes_of(&uniforms)),
        )?;
        Ok(vec![Value::Mask(Arc::new(Mask { texture: mask }))])
    }
}


crate::bind_group! {
    /// CurvatureContours' own uniform in group 1, after the curvature bindings (`surface_pass`
    /// binds it at [`crate::curvature::CURVATURE_OWN_FIRST`]).
    pub struct ContourBindings in "curvature_contours", group 1 from 2 {
        pub contour: Buffer,
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(CurvatureContoursNode)
        .program("curvature_contours", shaders::curvature(shaders::part!("curvature_contours.wgsl")))
        .uniform(ContourUniforms::layout())
        .bind_group(ContourBindings::layout())
        .bind_group_in("curvature_contours", crate::curvature::CurvatureBindings::layout())
        .bind_group_in("curvature_contours", crate::raycast::RayBindings::layout())
        .bind_group_in("curvature_contours", crate::raycast::RayOutputs::layout())
        .uniform_in("curvature_contours", crate::raycast::RayUniforms::layout())
        .uniform_in(
            "curvature_contours",
            crate::curvature::CurvatureUniforms::layout(),
        );
}
