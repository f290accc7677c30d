//! How large a volume texture may be before a volume is bricked, and how large the brick pool
//! may grow (issue 30). Read from the environment when a context opens; tests set them per
//! context (`GpuContext::set_volume_limits`) so that one process can render a volume
//! both ways.

use crate::error::GpuError;

/// The limits the volume upload works under.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VolumeLimits {
    /// Voxels per axis above which a volume is bricked instead of uploaded as one texture.
    /// `None`: the adapter's `max_texture_dimension_3d` (`HATCHERY_MAX_TEXTURE_3D` forces it
    /// lower). A brick pool's atlas is bounded by the adapter's limit and `pool_bytes` only.
    pub max_texture_3d: Option<u32>,
    /// Stored brick side in voxels, a one-voxel apron on each side included (so a brick holds
    /// `brick − 2` voxels of its own). `HATCHERY_BRICK`, default 64.
    pub brick: u32,
    /// Bytes each brick pool (one atlas texture per volume grid texture) may use, counted at 4
    /// bytes a voxel whatever its format. `HATCHERY_GPU_POOL_MB`, default 2048.
    pub pool_bytes: u64,
    /// Bytes each read-ahead copy may take on a CPU adapter, where a texture load is a loop in
    /// software and one load of four neighbours replaces four: a volume's x-quads for the
    /// tricubic B-spline (16 loads a sample instead of 32 filtered fetches; four times the
    /// volume texture) and a label map's 2×2 id quads for boundary filtering and object masks
    /// (2 loads instead of 8; two or four times the id texture), and a volume's voxel gradients
    /// for volume thinning's key (one fetch instead of six; 16 bytes a voxel). 0: never.
    /// `HATCHERY_QUADS_MB`, default 256; `HATCHERY_LOW_MEMORY=1` makes it 0.
    pub quads_bytes: u64,
}

impl Default for VolumeLimits {
    fn default() -> Self {
        Self {
            max_texture_3d: None,
            brick: 64,
            pool_bytes: 2048 << 20,
            quads_bytes: 256 << 20,
        }
    }
}

/// Smallest stored brick side: 2 voxels of apron leave at least 2 of the brick's own.
pub const MIN_BRICK: u32 = 4;

impl VolumeLimits {
    /// The defaults, overridden by `HATCHERY_MAX_TEXTURE_3D`, `HATCHERY_BRICK`,
    /// `HATCHERY_GPU_POOL_MB`, `HATCHERY_QUADS_MB` and `HATCHERY_LOW_MEMORY=1`. Errors: a value that is not a whole number in range, naming the
    /// variable.
    pub fn from_env() -> Result<Self, GpuError> {
        Self::from_vars(|name| std::env::var(name).ok())
    }

    /// [`Self::from_env`] over any source of variables (testable without touching the process
    /// environment).
    pub fn from_vars(var: impl Fn(&str) -> Option<String>) -> Result<Self, GpuError> {
        let number = |name: &str, min: u64| -> Result<Option<u64>, GpuError> {
            let Some(text) = var(name) else {
                return Ok(None);
            };
            match text.trim().parse::<u64>() {
                Ok(n) if n >= min => Ok(Some(n)),
                _ => Err(GpuError::Setting {
                    message: format!("{name}={text:?}: expected a whole number of at least {min}"),
                }),
            }
        };
        let mut limits = Self::default();
        if let Some(n) = number("HATCHERY_MAX_TEXTURE_3D", MIN_BRICK as u64)? {
            limits.max_texture_3d = Some(n.min(u32::MAX as u64) as u32);
        }
        if let Some(n) = number("HATCHERY_BRICK", MIN_BRICK as u64)? {
            limits.brick = n.min(4096) as u32;
        }
        if let Some(n) = number("HATCHERY_GPU_POOL_MB", 1)? {
            limits.pool_bytes = n.saturating_mul(1 << 20);
        }
        if let Some(n) = number("HATCHERY_QUADS_MB", 0)? {
            limits.quads_bytes = n.saturating_mul(1 << 20);
        }
        if var("HATCHERY_LOW_MEMORY").is_some_and(|v| v.trim() == "1") {
            limits.quads_bytes = 0;
        }
        Ok(limits)
    }

    /// The largest side of any volume texture on a device whose own limit is `device_max`.
    pub fn texture_side(&self, device_max: u32) -> u32 {
        self.max_texture_3d
            .map_or(device_max, |m| m.min(device_max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vars(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let pairs: Vec<(String, String)> = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| k == name)
                .map(|(_, v)| v.clone())
        }
    }

    #[test]
    fn settings_come_from_the_variables_and_bad_values_name_theirs() {
        assert_eq!(
            VolumeLimits::from_vars(vars(&[])).ok(),
            Some(VolumeLimits::default())
        );
        let l = VolumeLimits::from_vars(vars(&[
            ("HATCHERY_MAX_TEXTURE_3D", "64"),
            ("HATCHERY_BRICK", "16"),
            ("HATCHERY_GPU_POOL_MB", "3"),
            ("HATCHERY_QUADS_MB", "5"),
        ]))
        .unwrap();
        assert_eq!(l.quads_bytes, 5 << 20);
        let low = VolumeLimits::from_vars(vars(&[
            ("HATCHERY_QUADS_MB", "5"),
            ("HATCHERY_LOW_MEMORY", "1"),
        ]));
        assert_eq!(low.unwrap().quads_bytes, 0);
        assert_eq!(l.max_texture_3d, Some(64));
        assert_eq!(l.brick, 16);
        assert_eq!(l.pool_bytes, 3 << 20);
        assert_eq!(l.texture_side(2048), 64);
        assert_eq!(VolumeLimits::default().texture_side(2048), 2048);
        let e = VolumeLimits::from_vars(vars(&[("HATCHERY_BRICK", "2")]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("HATCHERY_BRICK=\"2\""), "{e}");
        let e = VolumeLimits::from_vars(vars(&[("HATCHERY_GPU_POOL_MB", "lots")]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("HATCHERY_GPU_POOL_MB"), "{e}");
    }
}
