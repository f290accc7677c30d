//! Turning and zooming the figure: a drag changes every Camera node's azimuth and elevation, a
//! wheel its distance (or, where the camera frames its data, how much of the frame it fills).

use hatchery_graph::{Graph, ParamValue};
use hatchery_nodes::Session;

/// The graph's Camera nodes.
pub struct Orbit {
    cameras: Vec<String>,
}

/// Degrees of azimuth per canvas width dragged.
const DEGREES_PER_WIDTH: f64 = 180.0;
/// Elevation stops short of the poles, where the up vector would flip.
const MAX_ELEVATION: f64 = 89.0;
/// Each wheel notch moves the camera by this factor.
const ZOOM_STEP: f64 = 1.1;

impl Orbit {
    pub fn of(graph: &Graph) -> Orbit {
        Orbit {
            cameras: graph
                .nodes()
                .filter(|n| n.kind == "Camera")
                .map(|n| n.id.clone())
                .collect(),
        }
    }

    fn float(session: &Session, node: &str, param: &str) -> f64 {
        session
            .graph
            .node(node)
            .and_then(|n| n.params.get(param))
            .and_then(|v| match v {
                ParamValue::Float(x) => Some(*x),
                _ => None,
            })
            .unwrap_or(0.0)
    }

    fn set(session: &mut Session, node: &str, param: &str, value: f64) -> Result<(), String> {
        session
            .graph
            .set_param(&session.registry, node, param, ParamValue::Float(value))
            .map_err(|e| e.to_string())
    }

    /// Turns by a drag of (`dx`, `dy`) CSS pixels on a canvas `width` pixels wide.
    pub fn drag(&self, session: &mut Session, dx: f64, dy: f64, width: u32) -> Result<(), String> {
        let per_pixel = DEGREES_PER_WIDTH / width.max(1) as f64;
        for camera in &self.cameras {
            let azimuth = Self::float(session, camera, "azimuth") - dx * per_pixel;
            // Kept within (-180, 180] so that long drags stay inside the parameter's range.
            let azimuth = (azimuth + 180.0).rem_euclid(360.0) - 180.0;
            let elevation = (Self::float(session, camera, "elevation") + dy * per_pixel)
                .clamp(-MAX_ELEVATION, MAX_ELEVATION);
            Self::set(session, camera, "azimuth", azimuth)?;
            Self::set(session, camera, "elevation", elevation)?;
        }
        Ok(())
    }

    /// Zooms by `steps` wheel notches (positive: closer).
    pub fn zoom(&self, session: &mut Session, steps: f64) -> Result<(), String> {
        let factor = ZOOM_STEP.powf(steps);
        for camera in &self.cameras {
            let frames_data = !session.graph.input_sources(camera).is_empty()
                && session
                    .graph
                    .node(camera)
                    .and_then(|n| n.params.get("framing"))
                    .is_some_and(|f| matches!(f, ParamValue::Choice(c) if c == "fit"));
            if frames_data {
                let fill = (Self::float(session, camera, "fill") * factor).clamp(0.05, 20.0);
                Self::set(session, camera, "fill", fill)?;
            } else {
                let distance = (Self::float(session, camera, "distance") / factor).clamp(1e-4, 1e6);
                Self::set(session, camera, "distance", distance)?;
            }
        }
        Ok(())
    }
}
