//! A minimal 3-vector in the collision frame (m/s, rad/s or N·s per component).
//!
//! Kept local rather than pulling in `glam`: the core must route every float call
//! through [`crate::math`], and only a handful of operations are needed.

use core::ops::{Add, AddAssign, Mul, Neg, Sub};

/// Cartesian 3-vector `(x, y, z)` in the collision frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Vec3 {
    /// Component along the line of centres (cue ball → object ball).
    pub x: f32,
    /// Component along the tangent line, in the table plane (`y = z × x`).
    pub y: f32,
    /// Vertical component (up).
    pub z: f32,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Self = Self::new(0.0, 0.0, 0.0);

    /// Build from components.
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }

    /// Build from an `[x, y, z]` array.
    pub const fn from_array(a: [f32; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// Components as an `[x, y, z]` array.
    pub const fn to_array(self) -> [f32; 3] {
        [self.x, self.y, self.z]
    }

    /// Dot product.
    pub fn dot(self, other: Self) -> f32 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// Cross product `self × other`.
    pub fn cross(self, other: Self) -> Self {
        Self::new(
            self.y * other.z - self.z * other.y,
            self.z * other.x - self.x * other.z,
            self.x * other.y - self.y * other.x,
        )
    }

    /// Euclidean length (one square root through the math shim). Out of line with the
    /// `compact-sqrt` feature, as the root is (60 B of a firmware image).
    #[cfg_attr(feature = "compact-sqrt", inline(never))]
    pub fn length(self) -> f32 {
        crate::math::sqrt(self.dot(self))
    }

    /// `true` when every component is finite.
    pub fn is_finite(self) -> bool {
        crate::math::is_finite(self.x)
            && crate::math::is_finite(self.y)
            && crate::math::is_finite(self.z)
    }
}

impl Add for Vec3 {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for Vec3 {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl Sub for Vec3 {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Vec3 {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f32> for Vec3 {
    type Output = Self;
    fn mul(self, s: f32) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cross_follows_right_hand_rule() {
        let x = Vec3::new(1.0, 0.0, 0.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        assert_eq!(x.cross(y), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(y.cross(x), Vec3::new(0.0, 0.0, -1.0));
    }

    #[test]
    fn length_of_3_4_0_is_5() {
        assert_eq!(Vec3::new(3.0, 4.0, 0.0).length(), 5.0);
    }
}
