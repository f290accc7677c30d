//! Voxel values in the type a file stores them in (u8, i8, u16, i16, f32; f64 is narrowed to f32
//! on load), so a uint8 volume costs one byte per voxel, not four.

/// Volumes claiming more voxels than this are refused before anything is allocated.
pub const MAX_VOXELS: u64 = 1 << 30;

/// A voxel type kept natively.
pub trait Voxel: Copy + Send + Sync + 'static {
    fn to_f32(self) -> f32;
}

macro_rules! voxel_as {
    ($($t:ty),*) => {$(
        impl Voxel for $t {
            #[inline]
            fn to_f32(self) -> f32 {
                self as f32
            }
        }
    )*};
}
voxel_as!(u8, i8, u16, i16, f32);

/// Runs `$body` with `$v` bound to the typed slice of a [`Voxels`] (one monomorphised copy per
/// type, so hot loops index a plain slice).
#[macro_export]
macro_rules! with_voxels {
    ($voxels:expr, $v:ident => $body:expr) => {
        match $voxels {
            $crate::voxels::Voxels::U8($v) => $body,
            $crate::voxels::Voxels::I8($v) => $body,
            $crate::voxels::Voxels::U16($v) => $body,
            $crate::voxels::Voxels::I16($v) => $body,
            $crate::voxels::Voxels::F32($v) => $body,
        }
    };
}

/// A voxel array in its native type, x fastest.
#[derive(Debug, Clone, PartialEq)]
pub enum Voxels {
    U8(Vec<u8>),
    I8(Vec<i8>),
    U16(Vec<u16>),
    I16(Vec<i16>),
    F32(Vec<f32>),
}

impl Voxels {
    pub fn len(&self) -> usize {
        match self {
            Voxels::U8(v) => v.len(),
            Voxels::I8(v) => v.len(),
            Voxels::U16(v) => v.len(),
            Voxels::I16(v) => v.len(),
            Voxels::F32(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The type's name as `hatchery info` prints it.
    pub fn type_name(&self) -> &'static str {
        match self {
            Voxels::U8(_) => "uint8",
            Voxels::I8(_) => "int8",
            Voxels::U16(_) => "uint16",
            Voxels::I16(_) => "int16",
            Voxels::F32(_) => "float32",
        }
    }

    /// Bytes per voxel.
    pub fn bytes_per_voxel(&self) -> usize {
        match self {
            Voxels::U8(_) | Voxels::I8(_) => 1,
            Voxels::U16(_) | Voxels::I16(_) => 2,
            Voxels::F32(_) => 4,
        }
    }

    /// Value `i` as f32.
    #[inline]
    pub fn get(&self, i: usize) -> f32 {
        match self {
            Voxels::U8(v) => v[i] as f32,
            Voxels::I8(v) => v[i] as f32,
            Voxels::U16(v) => v[i] as f32,
            Voxels::I16(v) => v[i] as f32,
            Voxels::F32(v) => v[i],
        }
    }

    /// The values as an f32 slice when they are stored as f32.
    pub fn as_f32(&self) -> Option<&[f32]> {
        match self {
            Voxels::F32(v) => Some(v),
            _ => None,
        }
    }

    /// Every value as f32 (a copy for the integer types).
    pub fn to_f32(&self) -> Vec<f32> {
        match self {
            Voxels::U8(v) => v.iter().map(|&x| x as f32).collect(),
            Voxels::I8(v) => v.iter().map(|&x| x as f32).collect(),
            Voxels::U16(v) => v.iter().map(|&x| x as f32).collect(),
            Voxels::I16(v) => v.iter().map(|&x| x as f32).collect(),
            Voxels::F32(v) => v.clone(),
        }
    }

    /// Every value as f32, consuming the array (no copy for f32).
    pub fn into_f32(self) -> Vec<f32> {
        match self {
            Voxels::F32(v) => v,
            other => other.to_f32(),
        }
    }

    /// Appends `other`'s values (slabs of one grid read one after another); `other` of another
    /// type is turned into f32 with this array (one source never mixes types, so this is rare).
    pub fn append(&mut self, other: Voxels) {
        match (self, other) {
            (Voxels::U8(a), Voxels::U8(b)) => a.extend(b),
            (Voxels::I8(a), Voxels::I8(b)) => a.extend(b),
            (Voxels::U16(a), Voxels::U16(b)) => a.extend(b),
            (Voxels::I16(a), Voxels::I16(b)) => a.extend(b),
            (Voxels::F32(a), Voxels::F32(b)) => a.extend(b),
            (this, b) => {
                let mut a = std::mem::replace(this, Voxels::F32(Vec::new())).into_f32();
                a.extend(b.into_f32());
                *this = Voxels::F32(a);
            }
        }
    }

    /// Applies `value * slope + intercept` (NIfTI scl_*, DICOM rescale). The identity keeps the
    /// native type; anything else gives f32.
    pub fn rescaled(self, slope: f64, intercept: f64) -> Voxels {
        if slope == 1.0 && intercept == 0.0 {
            return self;
        }
        let (s, c) = (slope as f32, intercept as f32);
        Voxels::F32(self.into_f32().into_iter().map(|v| v * s + c).collect())
    }
}

impl From<Vec<f32>> for Voxels {
    fn from(v: Vec<f32>) -> Self {
        Voxels::F32(v)
    }
}

impl From<Vec<f64>> for Voxels {
    /// f64 is narrowed to f32 (GPUs filter f32 at most).
    fn from(v: Vec<f64>) -> Self {
        Voxels::F32(v.into_iter().map(|x| x as f32).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_and_rescale() {
        let v = Voxels::I16(vec![-2, 0, 300]);
        assert_eq!(v.get(0), -2.0);
        assert_eq!(v.type_name(), "int16");
        assert_eq!(v.bytes_per_voxel(), 2);
        assert_eq!(v.clone().rescaled(1.0, 0.0), v);
        assert_eq!(v.rescaled(0.5, 10.0), Voxels::F32(vec![9.0, 10.0, 160.0]));
        assert_eq!(Voxels::from(vec![1.5f64]).into_f32(), vec![1.5f32]);
    }
}
