//! A directional light (made by the `Light` node, light.rs).

use super::camera::Camera;
use glam::Vec3;

/// A directional light.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Unit vector towards the light.
    pub direction: Vec3,
    /// Whether `direction` is in view space (a headlight that follows the camera) or world space.
    pub view_space: bool,
    pub color: [f32; 3],
    pub intensity: f32,
    pub ambient: f32,
}

impl Light {
    /// Unit direction towards the light in the camera's view space.
    pub fn view_direction(&self, camera: &Camera) -> Vec3 {
        if self.view_space {
            self.direction
        } else {
            camera.view.transform_vector3(self.direction).normalize()
        }
    }
}
