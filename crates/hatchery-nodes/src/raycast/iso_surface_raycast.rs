//! `IsoSurfaceRaycast`: the first hit of an iso value along each ray as a G-buffer (declared
//! with `Raycast` in mod.rs: the same program).

use super::{Kernel, KernelChoice, RayMode, RayOptions, RayShading, Reconstruction, cast};
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_graph::{
    DataValue, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `IsoSurfaceRaycast`.
    pub struct IsoSurfaceRaycastParams {
        /// iso value, in the volume's units, or relative to its values: "percentile(60)",
        /// "range(0.3)", "otsu"
        pub iso: DataValue = 0.0, range(-1e12, 1e12);
        /// sample distance in voxels
        pub step: f32 = 0.25, range(0.05, 8.0);
        /// reconstruction between voxels: trilinear, or the tricubic B-spline's values and
        /// normals (a smooth surface where trilinear shows the voxel lattice)
        pub reconstruction: Reconstruction = Reconstruction::Trilinear;
    }
}

pub struct IsoSurfaceRaycastNode;

impl Node<Value, Ctx> for IsoSurfaceRaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "IsoSurfaceRaycast",
            category: "Volume",
            doc: "First hit of an iso value along each ray (refined linearly between samples) as a \
                  G-buffer: window depth and the view-space normal −∇f/|∇f|. Feeds Silhouette, \
                  DiffuseIntensity, Halftone and the compositing nodes with no mesh at all.",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![PortSpec::output(
                "gbuffer",
                PortType::GBuffer,
                "depth + normal of the iso-surface",
            )],
            params: IsoSurfaceRaycastParams::specs(),
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
        let params = IsoSurfaceRaycastParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let options = RayOptions {
            mode: RayMode::Iso,
            iso: crate::relative::data_value(ctx, "iso", params.iso, &volume.data)?,
            step_voxels: params.step,
            shading: RayShading::None,
            lighting_model: "phong",
            phong: [0.0, 1.0, 0.0, 1.0],
            kappa: [0.0, 0.0],
            contours: false,
            thickness: 0.0,
            transparency: false,
            mip_bias: 0.0,
            jitter: false,
            early_termination: 1.0,
            hit_opacity: 1.0,
            light_view: Vec3::Z,
            skip_empty: true,
            kernel: Kernel::choose(KernelChoice::Auto, &ctx.gpu),
            rho: 1.0,
            embed: false,
            fast_exponent: false,
            reconstruction: params.reconstruction.on(ctx, &volume.data),
            preintegrated: false,
            enhancement: super::Enhancement::OFF,
            second_field: None,
            vector_field: None,
        };
        let (_, gbuffer) = cast(ctx, &volume, &camera, None, None, None, &options)?;
        Ok(vec![Value::GBuffer(Arc::new(gbuffer))])
    }
}

/// This kind (its program is `Raycast`'s, declared in mod.rs).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(IsoSurfaceRaycastNode);
}
